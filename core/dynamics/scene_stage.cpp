#include "core/dynamics/scene_stage.h"

#include <algorithm>

#include "core/model/rigid_math.h"
#include "optim/linear_solver.h"

namespace superdex {

SceneStageProblem::SceneStageProblem(int numDofs, double dt, ContactPipeline* contact,
                                     const KindStage& stage, std::vector<Eigen::VectorXd>* x,
                                     const StageDissipation& dissipation,
                                     StageWorkspace* workspace)
    : numDofs_(numDofs),
      dt_(dt),
      contact_(contact),
      ownWorkspace_(workspace ? nullptr : std::make_unique<StageWorkspace>()),
      ws_(workspace ? workspace : ownWorkspace_.get()),
      trial_(ws_->trial),
      scratch_(ws_->scratch),
      pendingStep_(ws_->pendingStep),
      triplets_(ws_->triplets),
      dissipation_(dissipation),
      stage_(x && stage.Size() > 0 ? &stage : nullptr),
      x_(stage_ ? x : nullptr) {
  if (stage_) {
    SyncAttached(*stage_, x_);
    trial_ = *x_;
  }
  context_ = ContextOf(dissipation_, dt_);
  if (stage_) {  // the kinds' loads at the stage's time
    const KindStage& ks = *stage_;
    for (size_t k = 0; k < ks.Size(); ++k) {
      Eigen::VectorXd f;
      if (!(*ks.kinds)[k]->StageLoad(ks.data[k], &f) || !f.any()) continue;
      kindLoad_.resize(ks.Size());
      kindLoadWork_.assign(ks.Size(), 0.0);
      kindLoad_[k] = std::move(f);
      hasLoad_ = true;
    }
  }
  // Where the linear solves are Krylov by default, the matrices keep a superset pattern while
  // contacts come and go (explicit zeros: the Krylov iterates are the same).
  const bool keepSuperset = numDofs_ >= kAutoIterativeUnknowns;
  ws_->hessianAssembly.SetKeepSuperset(keepSuperset);
  ws_->jacobianAssembly.SetKeepSuperset(keepSuperset);
}

KindView KindViewOf(const KindStage& stage, const std::vector<Eigen::VectorXd>& x) {
  KindView kinds;
  if (stage.Size() == 0) return kinds;
  kinds.q = &x;
  kinds.qLast = &stage.qLast;
  kinds.q0 = &stage.q0;
  kinds.stageDof = stage.attached.empty() ? &stage.stageDof : &stage.contactDof;
  return kinds;
}

void SyncAttached(const KindStage& stage, std::vector<Eigen::VectorXd>* x) {
  for (const KindStage::Attached& a : stage.attached)
    AttachedConfiguration(*(*stage.kinds)[a.carrier], *(*stage.kinds)[a.actor]->CarriedParts(),
                          (*x)[a.carrier], &(*x)[a.actor]);
}

DissipationContext ContextOf(const StageDissipation& dissipation, double dt) {
  DissipationContext c;
  c.dt = dt;
  c.mode = dissipation.mode;
  c.fadeFriction = dissipation.fadeFriction;
  c.slips = dissipation.slips;
  c.recordSlips = dissipation.recordSlips;
  return c;
}

const Eigen::VectorXd& SceneStageProblem::KindLocal(size_t k, const Eigen::VectorXd& d) const {
  const std::vector<int>& dof = stage_->stageDof[k];
  Eigen::VectorXd& local = ws_->kindDelta;
  local.resize(static_cast<Eigen::Index>(dof.size()));
  for (size_t i = 0; i < dof.size(); ++i) local[i] = dof[i] >= 0 ? d[dof[i]] : 0.0;
  return local;
}

bool SceneStageProblem::IsPotential() const { return DissipationIsPotential() && !hasLoad_; }

bool SceneStageProblem::DissipationIsPotential() const {
  return !dissipation_.enabled || dissipation_.mode == DissipationMode::ExplicitNormals;
}

void SceneStageProblem::Retract(const Eigen::VectorXd& d, std::vector<Eigen::VectorXd>* out) const {
  if (!stage_) return;
  for (size_t k = 0; k < stage_->Size(); ++k)
    (*stage_->kinds)[k]->Retract((*x_)[k], KindLocal(k, d), &(*out)[k]);
  SyncAttached(*stage_, out);
}

double SceneStageProblem::EvaluateAt(const std::vector<Eigen::VectorXd>& x, int order,
                                     PsdProjection projection, Eigen::VectorXd* gPot,
                                     Eigen::VectorXd* rDiss, ContactStats* stats) {
  double value = 0.0;
  const bool attached = stage_ && !stage_->attached.empty();
  if (order >= 1) {  // with attached actors, at the contact's numbering until reduced
    const int n = attached ? stage_->numContactDofs : numDofs_;
    gPot->setZero(n);
    if (rDiss != gPot) rDiss->setZero(n);
  }
  triplets_.clear();
  ws_->blocks.clear();
  ws_->kindValue.clear();
  if (!stage_) {
    ws_->blockPosition = 0;
    if (stats) *stats = ContactStats();
    return value;
  }
  value += EvaluateKindTerms(x, order, projection, gPot, rDiss);
  ws_->blockPosition = triplets_.size();
  const KindView kinds = KindViewOf(*stage_, x);
  value += contact_->Evaluate(order, projection, gPot, &triplets_, &ws_->blocks, stats,
                              dissipation_.enabled ? &context_ : nullptr, rDiss, &kinds);
  if (attached && order >= 1) ReduceAttached(x, order, projection, gPot, rDiss);
  return value;
}

void SceneStageProblem::ReduceAttached(const std::vector<Eigen::VectorXd>& x, int order,
                                       PsdProjection projection, Eigen::VectorXd* gPot,
                                       Eigen::VectorXd* rDiss) {
  const KindStage& ks = *stage_;
  // The carried parts in the attached actors' order, each with its first contact dof (−1: its
  // carrier has no unknowns, nothing to reduce) and its total chart gradient (the potential's,
  // with the dissipation's where that is a potential too; a point takes no torque).
  std::vector<StagePart>& parts = ws_->parts;
  parts.clear();
  for (const KindStage::Attached& a : ks.attached)
    for (const CarriedPart& p : *(*ks.kinds)[a.actor]->CarriedParts())
      parts.push_back({a.actor, a.carrier, &p, ks.contactDof[a.actor][p.dof]});
  const size_t np = parts.size();
  std::vector<Eigen::MatrixXd>& A = ws_->frameJacobians;
  std::vector<FramePoint>& points = ws_->framePoints;
  std::vector<Eigen::Matrix<double, 6, 1>>& loads = ws_->frameLoads;
  A.resize(np);
  loads.resize(np);
  std::vector<Eigen::MatrixXd> carrierA;
  std::vector<Eigen::Triplet<double>> curvature;
  for (size_t i = 0; i < np; ++i) {
    loads[i].setZero();
    const int first = parts[i].first, size = parts[i].part->Size();
    if (first < 0) continue;
    loads[i].head(size) = gPot->segment(first, size);
    if (rDiss != gPot) loads[i].head(size) += rDiss->segment(first, size);
  }
  for (size_t i = 0; i < np; ++i) {
    const int carrier = parts[i].carrier;
    if (i > 0 && parts[i - 1].carrier == carrier) continue;  // done with its run
    size_t end = i;
    points.clear();
    for (; end < np && parts[end].carrier == carrier; ++end) {
      const CarriedPart& p = *parts[end].part;
      points.push_back({p.frame, x[parts[end].actor].segment<3>(p.entry)});
    }
    const ActorKind& kind = *(*ks.kinds)[carrier];
    kind.CarriedFrameJacobians(x[carrier], points, &carrierA);
    for (size_t j = i; j < end; ++j) A[j] = carrierA[j - i];
    if (order < 2 || projection != PsdProjection::None) continue;
    // The exact Hessian's curvature of the carrier's chart (its tangent dofs' entries, all of
    // them, so that the pattern stays put).
    const int m = kind.NumTangentDofs();
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(m, m);
    std::vector<Eigen::Matrix<double, 6, 1>> runLoads(loads.begin() + i, loads.begin() + end);
    kind.AddCarriedFrameCurvature(x[carrier], points, runLoads, &C);
    // The residual modes' dissipative load r_d is no gradient: the curvature's symmetric form
    // carries −½ Aᵀ[τ_d]×A of the chart's trivialization, which the true ∂(Aᵀ r_d)/∂δ has not
    // (the pipeline's J_d is already the derivative along the retraction): add it back.
    if (rDiss != gPot && !DissipationIsPotential())
      for (size_t j = i; j < end; ++j) {
        if (parts[j].first < 0 || parts[j].part->kind != CarriedPart::Kind::Pose) continue;
        const Eigen::MatrixXd Ar = carrierA[j - i].bottomRows<3>();
        C += 0.5 * Ar.transpose() * Skew(rDiss->segment<3>(parts[j].first + 3)) * Ar;
      }
    const std::vector<int>& dof = ks.stageDof[carrier];
    for (int r = 0; r < m; ++r)
      for (int c = 0; c < m; ++c)
        if (dof[r] >= 0 && dof[c] >= 0) curvature.emplace_back(dof[r], dof[c], C(r, c));
  }
  auto reduce = [&](Eigen::VectorXd* v) {
    for (size_t i = 0; i < np; ++i) {
      const int first = parts[i].first, size = parts[i].part->Size();
      if (first < 0) continue;
      const Eigen::VectorXd r = A[i].topRows(size).transpose() * v->segment(first, size);
      const std::vector<int>& dof = ks.stageDof[parts[i].carrier];
      for (size_t j = 0; j < dof.size(); ++j)
        if (dof[j] >= 0) (*v)[dof[j]] += r[static_cast<Eigen::Index>(j)];
    }
    v->conservativeResize(numDofs_);
  };
  reduce(gPot);
  if (rDiss != gPot) reduce(rDiss);
  if (order < 2) return;
  // H = Pᵀ H_ext P, P = [I; A] (N × n), then the curvature.
  const int N = ks.numContactDofs;
  ws_->extendedAssembly.Assemble(triplets_, ws_->blocks, ws_->blockPosition, N, &ws_->extended);
  std::vector<Eigen::Triplet<double>> p;
  for (int r = 0; r < numDofs_; ++r) p.emplace_back(r, r, 1.0);
  for (size_t i = 0; i < np; ++i) {
    const int first = parts[i].first;
    if (first < 0) continue;
    const std::vector<int>& dof = ks.stageDof[parts[i].carrier];
    for (int k = 0; k < parts[i].part->Size(); ++k)
      for (size_t j = 0; j < dof.size(); ++j)
        if (dof[j] >= 0 && A[i](k, static_cast<Eigen::Index>(j)) != 0.0)
          p.emplace_back(first + k, dof[j], A[i](k, static_cast<Eigen::Index>(j)));
  }
  ws_->reduction.resize(N, numDofs_);
  ws_->reduction.setFromTriplets(p.begin(), p.end());
  const Eigen::SparseMatrix<double> H =
      Eigen::SparseMatrix<double>(ws_->reduction.transpose()) * ws_->extended * ws_->reduction;
  triplets_.clear();
  ws_->blocks.clear();
  ws_->blockPosition = 0;
  for (int c = 0; c < H.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, c); it; ++it)
      triplets_.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
  triplets_.insert(triplets_.end(), curvature.begin(), curvature.end());
}

double SceneStageProblem::EvaluateKindTerms(const std::vector<Eigen::VectorXd>& x, int order,
                                            PsdProjection projection, Eigen::VectorXd* gPot,
                                            Eigen::VectorXd* rDiss) {
  const KindStage& ks = *stage_;
  double value = 0.0;
  Eigen::VectorXd& g = ws_->kindGradient;
  std::vector<double>& kindValue = ws_->kindValue;
  kindValue.assign(ks.Size(), 0.0);
  for (size_t k = 0; k < ks.Size(); ++k) {
    const ActorKind& kind = *(*ks.kinds)[k];
    // With attached actors the vectors are at the contact's numbering (a carried part's dofs
    // there, reduced with the contact's by ReduceAttached).
    const std::vector<int>& dof = ks.attached.empty() ? ks.stageDof[k] : ks.contactDof[k];
    if (order >= 1) g.setZero(kind.NumTangentDofs());
    // The kind appends its local entries to triplets_; they are renumbered in place below.
    const size_t first = triplets_.size();
    kindValue[k] = kind.StageEnergy(ks.data[k], x[k], order, projection,
                                    order >= 1 ? &g : nullptr, order >= 2 ? &triplets_ : nullptr);
    if (!kindLoad_.empty() && kindLoad_[k].size() > 0) {
      const Eigen::VectorXd& f = kindLoad_[k];
      kindValue[k] -= kindLoadWork_[k];
      if (&x != x_) {  // at the current iterate the tangent step is zero exactly
        kind.TangentBetween((*x_)[k], x[k], &ws_->kindDelta);
        kindValue[k] -= f.dot(ws_->kindDelta);
      }
      if (order >= 1)
        for (size_t i = 0; i < dof.size(); ++i)
          if (dof[i] >= 0) (*rDiss)[dof[i]] -= f[i];
    }
    value += kindValue[k];
    if (order < 1) continue;
    for (size_t i = 0; i < dof.size(); ++i)
      if (dof[i] >= 0) (*gPot)[dof[i]] += g[i];
    // Every entry the kind appends, zero or not (the kind keeps its pattern stable), at the
    // stage dofs; entries on a prescribed dof are dropped.
    size_t kept = first;
    for (size_t e = first; e < triplets_.size(); ++e) {
      const Eigen::Triplet<double>& t = triplets_[e];
      const int r = dof[t.row()], c = dof[t.col()];
      if (r >= 0 && c >= 0) triplets_[kept++] = Eigen::Triplet<double>(r, c, t.value());
    }
    triplets_.resize(kept);
  }
  return value;
}

double SceneStageProblem::Value(const Eigen::VectorXd& d) {
  Retract(d, &trial_);
  return EvaluateAt(trial_, 0, PsdProjection::None, nullptr, nullptr);
}

double SceneStageProblem::Evaluate(Eigen::VectorXd* gradient,
                                   Eigen::SparseMatrix<double>* hessian,
                                   PsdProjection projection) {
  return ValueAndDerivatives(Positions(), gradient, hessian, projection, &lastStats_);
}

void SceneStageProblem::BeginTrial(const Eigen::VectorXd& d) {
  // trial_ is what Commit(d) installs (the same Retract), so the sums evaluated there are
  // those that Evaluate and EvaluateResidual form after it, bit for bit.
  Retract(d, &trial_);
  pendingStep_ = d;
  hasPending_ = true;
}

bool SceneStageProblem::EvaluateAtStep(const Eigen::VectorXd& d, double* value,
                                       Eigen::VectorXd* gradient,
                                       Eigen::SparseMatrix<double>* hessian,
                                       PsdProjection projection) {
  BeginTrial(d);
  *value = ValueAndDerivatives(trial_, gradient, hessian, projection, &pendingStats_);
  return true;
}

double SceneStageProblem::ValueAndDerivatives(const std::vector<Eigen::VectorXd>& x,
                                              Eigen::VectorXd* gradient,
                                              Eigen::SparseMatrix<double>* hessian,
                                              PsdProjection projection, ContactStats* stats) {
  const double value = EvaluateAt(x, hessian ? 2 : 1, projection, gradient, gradient, stats);
  if (hessian)
    ws_->hessianAssembly.Assemble(triplets_, ws_->blocks, ws_->blockPosition, numDofs_, hessian);
  return value;
}

void SceneStageProblem::Residual(const Eigen::VectorXd& d, Eigen::VectorXd* r) {
  Retract(d, &trial_);
  EvaluateAt(trial_, 1, PsdProjection::None, r, r);
}

void SceneStageProblem::EvaluateResidual(Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J) {
  ResidualAndJacobian(Positions(), r, J, &lastStats_);
}

bool SceneStageProblem::EvaluateResidualAtStep(const Eigen::VectorXd& d, Eigen::VectorXd* r,
                                               Eigen::SparseMatrix<double>* J) {
  BeginTrial(d);
  ResidualAndJacobian(trial_, r, J, &pendingStats_);
  return true;
}

void SceneStageProblem::ResidualAndJacobian(const std::vector<Eigen::VectorXd>& x,
                                            Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J,
                                            ContactStats* stats) {
  EvaluateAt(x, J ? 2 : 1, PsdProjection::None, r, &scratch_, stats);
  if (J) {
    // A kind's rotation-like dofs see its potential's generalized force change along the
    // retraction (a rigid actor: (H − ½[τ]×) δθ, H assembled above); the dissipation Jacobian of
    // the residual modes is already that of the world torque.
    if (stage_) AddKindJacobianCorrections(*r, DissipationIsPotential(), x);
    ws_->jacobianAssembly.Assemble(triplets_, ws_->blocks, ws_->blockPosition, numDofs_, J);
  }
  *r += scratch_;
}

void SceneStageProblem::AddKindJacobianCorrections(const Eigen::VectorXd& r,
                                                   bool dissipationIsPotential,
                                                   const std::vector<Eigen::VectorXd>& x) {
  const KindStage& ks = *stage_;
  std::vector<Eigen::Triplet<double>>& local = ws_->kindHessian;
  for (size_t k = 0; k < ks.Size(); ++k) {
    const std::vector<int>& dof = ks.stageDof[k];
    Eigen::VectorXd& residual = ws_->kindDelta;  // the potential part of r at the kind's dofs
    residual.setZero(static_cast<Eigen::Index>(dof.size()));
    for (size_t i = 0; i < dof.size(); ++i)
      if (dof[i] >= 0) residual[i] = r[dof[i]] + (dissipationIsPotential ? scratch_[dof[i]] : 0.0);
    // A StageLoad (in scratch_) is constant in the tangent's own terms: it adds nothing to J.
    if (dissipationIsPotential && !kindLoad_.empty() && kindLoad_[k].size() > 0)
      residual += kindLoad_[k];
    local.clear();
    (*ks.kinds)[k]->AddResidualJacobianCorrection(x[k], residual, &local);
    for (const Eigen::Triplet<double>& t : local) {
      const int row = dof[t.row()], col = dof[t.col()];
      if (row >= 0 && col >= 0) triplets_.emplace_back(row, col, t.value());
    }
  }
}

void SceneStageProblem::SetChartOrigin() {
  std::fill(kindLoadWork_.begin(), kindLoadWork_.end(), 0.0);  // the chart's solvers read residuals alone
  if (stage_) origin_ = *x_;
}

void SceneStageProblem::MoveInChart(const Eigen::VectorXd& d) {
  if (!stage_) return;
  // Each vector state retracts from the chart's origin (soft nodes: the identity).
  *x_ = origin_;
  Retract(d, &trial_);
  *x_ = trial_;
}

Eigen::MatrixXd SceneStageProblem::ChartTangentMap(const Eigen::VectorXd& d) const {
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(numDofs_, numDofs_);
  if (!stage_) return T;
  for (size_t k = 0; k < stage_->Size(); ++k) {
    const std::vector<int>& dof = stage_->stageDof[k];
    const Eigen::MatrixXd Tk = (*stage_->kinds)[k]->ChartTangentMap(KindLocal(k, d));
    for (size_t i = 0; i < dof.size(); ++i)
      for (size_t j = 0; j < dof.size(); ++j)
        if (dof[i] >= 0 && dof[j] >= 0) T(dof[i], dof[j]) = Tk(i, j);
  }
  return T;
}

void SceneStageProblem::Commit(const Eigen::VectorXd& d) {
  Retract(d, &trial_);
  // The loads' work along the committed iterates, as EvaluateKindTerms evaluates the trial's.
  if (!kindLoad_.empty()) {
      for (size_t k = 0; k < kindLoad_.size(); ++k) {
      if (kindLoad_[k].size() == 0) continue;
      (*stage_->kinds)[k]->TangentBetween((*x_)[k], trial_[k],
                                               &ws_->kindDelta);
      kindLoadWork_[k] += kindLoad_[k].dot(ws_->kindDelta);
    }
  }
  if (stage_) *x_ = trial_;
  if (hasPending_ && pendingStep_ == d) {
    lastStats_ = pendingStats_;
  }
  hasPending_ = false;
}

bool SceneStageProblem::LastSplit(StageSplit* split) {
  // Units: one per kind.
  const KindStage* kinds = stage_ && stage_->Size() > 0 ? stage_ : nullptr;
  const size_t nk = kinds ? kinds->Size() : 0;
  for (size_t k = 0; k < nk; ++k)  // a kind that refuses it keeps the stage whole
    if (!(*kinds->kinds)[k]->Shortcuts().splitParts) return false;
  const int units = static_cast<int>(nk);
  if (static_cast<int>(split->unitOfDof.size()) != numDofs_ || split->units != units) {
    split->unitOfDof.assign(numDofs_, 0);
    for (size_t k = 0; k < nk; ++k)
      for (int i : kinds->stageDof[k])
        if (i >= 0) split->unitOfDof[i] = static_cast<int>(k);
    split->units = units;
  }
  if (ws_->kindValue.size() != nk) return false;
  // Per kind: its stage energy, then the contact pairs' shares.
  std::vector<double>& value = ws_->splitValue;
  value = ws_->kindValue;
  split->joins.clear();
  if (contact_ && !contact_->SplitLastEvaluation(&value, &split->joins)) return false;
  // An attached body's pairs are its carrier's.
  if (kinds) for (const KindStage::Attached& a : kinds->attached) {
    value[a.carrier] += value[a.actor];
    value[a.actor] = 0.0;
    for (std::pair<int, int>& j : split->joins) {
      if (j.first == a.actor) j.first = a.carrier;
      if (j.second == a.actor) j.second = a.carrier;
    }
  }
  split->share.assign(value.begin(), value.end());
  return true;
}

bool SceneStageProblem::TrustStep(Eigen::VectorXd* d) {
  if (!stage_) return false;
  bool changed = false;
  for (size_t k = 0; k < stage_->Size(); ++k) {
    const double f = (*stage_->kinds)[k]->TrustFraction((*x_)[k], KindLocal(k, *d));
    if (!(f < 1.0)) continue;
    for (int i : stage_->stageDof[k])
      if (i >= 0) (*d)[i] *= f;
    changed = true;
  }
  return changed;
}

bool SceneStageProblem::LimitStep(Eigen::VectorXd* d) {
  if (!contact_ || !stage_ || stage_->Size() == 0) return false;
  std::vector<double>& kindLimits = ws_->kindLimits;
  Retract(*d, &trial_);
  const KindView now = KindViewOf(*stage_, *x_), next = KindViewOf(*stage_, trial_);
  contact_->StepLimits(now, next, &kindLimits);
  for (const KindStage::Attached& a : stage_->attached)  // an attached body's moves its carrier
    kindLimits[a.carrier] = std::min(kindLimits[a.carrier], kindLimits[a.actor]);
  bool changed = false;
  for (size_t k = 0; k < stage_->Size(); ++k) {
    if (kindLimits[k] >= 1.0) continue;
    for (int i : stage_->stageDof[k])
      if (i >= 0) (*d)[i] *= kindLimits[k];
    changed = true;
  }
  return changed;
}

void SceneStageProblem::BlockLayout(DofBlockLayout* layout) const {
  // In dof order: each kind's free dofs in blocks of its DofBlockSize.
  std::vector<int>& sizes = layout->sizes;
  sizes.clear();
  if (!stage_) return;
  for (size_t k = 0; k < stage_->Size(); ++k) {
    int free = 0;
    for (int i : stage_->stageDof[k]) free += i >= 0;
    const int size = (*stage_->kinds)[k]->DofBlockSize();
    if (free % size != 0) {  // blocks of 3 then; 1×1 if those do not fit
      sizes.clear();
      return;
    }
    sizes.insert(sizes.end(), free / size, size);
  }
}

double SceneStageProblem::StepNorm(const Eigen::VectorXd& d) const {
  double norm = 0.0;
  if (!stage_) return norm;
  for (size_t k = 0; k < stage_->Size(); ++k)
    norm = std::max(norm, (*stage_->kinds)[k]->StepLength((*x_)[k], KindLocal(k, d)));
  return norm;
}

}  // namespace superdex
