#include "core/dynamics/scene_stage.h"

#include <algorithm>

#include "optim/linear_solver.h"

namespace superdex {

SceneStageProblem::SceneStageProblem(int numDofs, double dt, const Eigen::Vector3d& gravity,
                                     ContactPipeline* contact, const SoftStage& soft,
                                     std::vector<Eigen::VectorXd>* softX,
                                     const StageDissipation& dissipation,
                                     StageWorkspace* workspace)
    : numDofs_(numDofs),
      dt_(dt),
      gravity_(gravity),
      contact_(contact),
      ownWorkspace_(workspace ? nullptr : std::make_unique<StageWorkspace>()),
      ws_(workspace ? workspace : ownWorkspace_.get()),
      softTrial_(ws_->softTrial),
      scratch_(ws_->scratch),
      pendingStep_(ws_->pendingStep),
      triplets_(ws_->triplets),
      dissipation_(dissipation),
      soft_(softX && !soft.Empty() ? &soft : nullptr),
      softX_(soft_ ? softX : nullptr) {
  if (soft_) {
    softTrial_ = *softX_;
    if (ws_->soft.size() < soft_->targets.size()) ws_->soft.resize(soft_->targets.size());
    // The soft nodes' dofs: one range, the last dofs (Scene::Prepare).
    softBegin_ = softEnd_ = numDofs_;
    for (size_t s = 0; s < soft_->targets.size(); ++s)
      if ((*soft_->models)[s].numFree > 0) softBegin_ = std::min(softBegin_, soft_->dofOffset[s]);
  }
  context_ = ContextOf(dissipation_, dt_);
  if (soft_) {  // the kinds' loads at the stage's time
    const KindStage& ks = soft_->kinds;
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

KindView KindViewOf(const SoftStage& soft, const std::vector<Eigen::VectorXd>& x) {
  KindView kinds;
  if (soft.kinds.Size() == 0) return kinds;
  kinds.q = &x;
  kinds.first = static_cast<int>(soft.targets.size());
  kinds.qLast = &soft.kinds.qLast;
  kinds.q0 = &soft.kinds.q0;
  kinds.stageDof = &soft.kinds.stageDof;
  return kinds;
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
  const std::vector<int>& dof = soft_->kinds.stageDof[k];
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
  if (!soft_) return;
  for (size_t s = 0; s < soft_->targets.size(); ++s) {
    const SoftBodyModel& m = (*soft_->models)[s];
    Eigen::VectorXd& x = (*out)[s];
    x = (*softX_)[s];
    for (int a = 0; a < m.NumNodes(); ++a)
      if (m.freeIndex[a] >= 0)
        x.segment<3>(3 * a) += d.segment<3>(soft_->dofOffset[s] + 3 * m.freeIndex[a]);
  }
  const size_t ns = soft_->targets.size();
  for (size_t k = 0; k < soft_->kinds.Size(); ++k)
    (*soft_->kinds.kinds)[k]->Retract((*softX_)[ns + k], KindLocal(k, d), &(*out)[ns + k]);
}

double SceneStageProblem::EvaluateAt(const std::vector<Eigen::VectorXd>& softX, int order,
                                     PsdProjection projection, Eigen::VectorXd* gPot,
                                     Eigen::VectorXd* rDiss, ContactStats* stats,
                                     double* minDetF) {
  double value = 0.0;
  if (order >= 1) {
    gPot->setZero(numDofs_);
    if (rDiss != gPot) rDiss->setZero(numDofs_);
  }
  triplets_.clear();
  ws_->blocks.clear();
  ws_->kindValue.clear();
  if (minDetF) *minDetF = INFINITY;
  if (!soft_) {
    ws_->blockPosition = 0;
    if (stats) *stats = ContactStats();
    return value;
  }
  double minDet = INFINITY;
  for (size_t s = 0; s < soft_->targets.size(); ++s) {
    double md = INFINITY;
    value += EvaluateSoftStageTerms((*soft_->models)[s], soft_->targets[s], dt_, gravity_,
                                    softX[s], order, projection, soft_->dofOffset[s], gPot,
                                    &triplets_, &ws_->soft[s], &md);
    minDet = std::min(minDet, md);
  }
  if (minDetF) *minDetF = minDet;
  value += EvaluateKindTerms(softX, order, projection, gPot, rDiss);
  SoftView view;
  view.x = &softX;
  view.xLast = &soft_->xLast;
  view.x0 = &soft_->x0;
  view.dofOffset = &soft_->dofOffset;
  ws_->blockPosition = triplets_.size();
  const KindView kinds = KindViewOf(*soft_, softX);
  value += contact_->Evaluate(order, projection, gPot, &triplets_, &ws_->blocks, stats,
                              dissipation_.enabled ? &context_ : nullptr, rDiss, &view,
                              kinds.q ? &kinds : nullptr);
  return value;
}

double SceneStageProblem::EvaluateKindTerms(const std::vector<Eigen::VectorXd>& softX, int order,
                                            PsdProjection projection, Eigen::VectorXd* gPot,
                                            Eigen::VectorXd* rDiss) {
  const KindStage& ks = soft_->kinds;
  const size_t ns = soft_->targets.size();
  double value = 0.0;
  Eigen::VectorXd& g = ws_->kindGradient;
  std::vector<Eigen::Triplet<double>>& H = ws_->kindHessian;
  std::vector<double>& kindValue = ws_->kindValue;
  kindValue.assign(ks.Size(), 0.0);
  for (size_t k = 0; k < ks.Size(); ++k) {
    const ActorKind& kind = *(*ks.kinds)[k];
    const std::vector<int>& dof = ks.stageDof[k];
    if (order >= 1) g.setZero(kind.NumTangentDofs());
    H.clear();
    kindValue[k] = kind.StageEnergy(ks.data[k], softX[ns + k], order, projection,
                                    order >= 1 ? &g : nullptr, order >= 2 ? &H : nullptr);
    if (!kindLoad_.empty() && kindLoad_[k].size() > 0) {
      const Eigen::VectorXd& f = kindLoad_[k];
      kindValue[k] -= kindLoadWork_[k];
      if (&softX != softX_) {  // at the current iterate the tangent step is zero exactly
        kind.TangentBetween((*softX_)[ns + k], softX[ns + k], &ws_->kindDelta);
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
    // Every entry the kind appends, zero or not: the kind keeps its pattern stable.
    for (const Eigen::Triplet<double>& t : H) {
      const int r = dof[t.row()], c = dof[t.col()];
      if (r >= 0 && c >= 0) triplets_.emplace_back(r, c, t.value());
    }
  }
  return value;
}

double SceneStageProblem::Value(const Eigen::VectorXd& d) {
  Retract(d, &softTrial_);
  return EvaluateAt(softTrial_, 0, PsdProjection::None, nullptr, nullptr);
}

double SceneStageProblem::Evaluate(Eigen::VectorXd* gradient,
                                   Eigen::SparseMatrix<double>* hessian,
                                   PsdProjection projection) {
  return ValueAndDerivatives(SoftPositions(), gradient, hessian, projection, &lastStats_,
                             &lastMinDetF_);
}

void SceneStageProblem::BeginTrial(const Eigen::VectorXd& d) {
  // softTrial_ is what Commit(d) installs (the same Retract), so the sums evaluated there are
  // those that Evaluate and EvaluateResidual form after it, bit for bit.
  Retract(d, &softTrial_);
  pendingStep_ = d;
  hasPending_ = true;
}

bool SceneStageProblem::EvaluateAtStep(const Eigen::VectorXd& d, double* value,
                                       Eigen::VectorXd* gradient,
                                       Eigen::SparseMatrix<double>* hessian,
                                       PsdProjection projection) {
  BeginTrial(d);
  *value = ValueAndDerivatives(softTrial_, gradient, hessian, projection, &pendingStats_,
                               &pendingMinDetF_);
  return true;
}

double SceneStageProblem::ValueAndDerivatives(const std::vector<Eigen::VectorXd>& softX,
                                              Eigen::VectorXd* gradient,
                                              Eigen::SparseMatrix<double>* hessian,
                                              PsdProjection projection, ContactStats* stats,
                                              double* minDetF) {
  const double value =
      EvaluateAt(softX, hessian ? 2 : 1, projection, gradient, gradient, stats, minDetF);
  if (hessian)
    ws_->hessianAssembly.Assemble(triplets_, ws_->blocks, ws_->blockPosition, numDofs_, hessian);
  return value;
}

void SceneStageProblem::Residual(const Eigen::VectorXd& d, Eigen::VectorXd* r) {
  Retract(d, &softTrial_);
  EvaluateAt(softTrial_, 1, PsdProjection::None, r, r);
}

void SceneStageProblem::EvaluateResidual(Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J) {
  ResidualAndJacobian(SoftPositions(), r, J, &lastStats_, &lastMinDetF_);
}

bool SceneStageProblem::EvaluateResidualAtStep(const Eigen::VectorXd& d, Eigen::VectorXd* r,
                                               Eigen::SparseMatrix<double>* J) {
  BeginTrial(d);
  ResidualAndJacobian(softTrial_, r, J, &pendingStats_, &pendingMinDetF_);
  return true;
}

void SceneStageProblem::ResidualAndJacobian(const std::vector<Eigen::VectorXd>& softX,
                                            Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J,
                                            ContactStats* stats, double* minDetF) {
  EvaluateAt(softX, J ? 2 : 1, PsdProjection::None, r, &scratch_, stats, minDetF);
  if (J) {
    // A kind's rotation-like dofs see its potential's generalized force change along the
    // retraction (a rigid actor: (H − ½[τ]×) δθ, H assembled above); the dissipation Jacobian of
    // the residual modes is already that of the world torque.
    if (soft_) AddKindJacobianCorrections(*r, DissipationIsPotential(), softX);
    ws_->jacobianAssembly.Assemble(triplets_, ws_->blocks, ws_->blockPosition, numDofs_, J);
  }
  *r += scratch_;
}

void SceneStageProblem::AddKindJacobianCorrections(const Eigen::VectorXd& r,
                                                   bool dissipationIsPotential,
                                                   const std::vector<Eigen::VectorXd>& softX) {
  const KindStage& ks = soft_->kinds;
  const size_t ns = soft_->targets.size();
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
    (*ks.kinds)[k]->AddResidualJacobianCorrection(softX[ns + k], residual, &local);
    for (const Eigen::Triplet<double>& t : local) {
      const int row = dof[t.row()], col = dof[t.col()];
      if (row >= 0 && col >= 0) triplets_.emplace_back(row, col, t.value());
    }
  }
}

void SceneStageProblem::SetChartOrigin() {
  std::fill(kindLoadWork_.begin(), kindLoadWork_.end(), 0.0);  // the chart's solvers read residuals alone
  if (soft_) softOrigin_ = *softX_;
}

void SceneStageProblem::MoveInChart(const Eigen::VectorXd& d) {
  if (!soft_) return;
  // Each vector state retracts from the chart's origin (soft nodes: the identity).
  *softX_ = softOrigin_;
  Retract(d, &softTrial_);
  *softX_ = softTrial_;
}

Eigen::MatrixXd SceneStageProblem::ChartTangentMap(const Eigen::VectorXd& d) const {
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(numDofs_, numDofs_);
  if (!soft_) return T;
  for (size_t k = 0; k < soft_->kinds.Size(); ++k) {
    const std::vector<int>& dof = soft_->kinds.stageDof[k];
    const Eigen::MatrixXd Tk = (*soft_->kinds.kinds)[k]->ChartTangentMap(KindLocal(k, d));
    for (size_t i = 0; i < dof.size(); ++i)
      for (size_t j = 0; j < dof.size(); ++j)
        if (dof[i] >= 0 && dof[j] >= 0) T(dof[i], dof[j]) = Tk(i, j);
  }
  return T;
}

void SceneStageProblem::Commit(const Eigen::VectorXd& d) {
  Retract(d, &softTrial_);
  // The loads' work along the committed iterates, as EvaluateKindTerms evaluates the trial's.
  if (!kindLoad_.empty()) {
    const size_t ns = soft_->targets.size();
    for (size_t k = 0; k < kindLoad_.size(); ++k) {
      if (kindLoad_[k].size() == 0) continue;
      (*soft_->kinds.kinds)[k]->TangentBetween((*softX_)[ns + k], softTrial_[ns + k],
                                               &ws_->kindDelta);
      kindLoadWork_[k] += kindLoad_[k].dot(ws_->kindDelta);
    }
  }
  if (soft_) *softX_ = softTrial_;
  if (hasPending_ && pendingStep_ == d) {
    lastStats_ = pendingStats_;
    lastMinDetF_ = pendingMinDetF_;
  }
  hasPending_ = false;
}

bool SceneStageProblem::LastSplit(StageSplit* split) {
  // Units: one per kind.
  if (soft_ && !soft_->targets.empty()) return false;  // soft actors: not split
  const KindStage* kinds = soft_ && soft_->kinds.Size() > 0 ? &soft_->kinds : nullptr;
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
  split->share.assign(value.begin(), value.end());
  return true;
}

bool SceneStageProblem::TrustStep(Eigen::VectorXd* d) {
  if (!soft_) return false;
  bool changed = false;
  const size_t ns = soft_->targets.size();
  for (size_t k = 0; k < soft_->kinds.Size(); ++k) {
    const double f = (*soft_->kinds.kinds)[k]->TrustFraction((*softX_)[ns + k], KindLocal(k, *d));
    if (!(f < 1.0)) continue;
    for (int i : soft_->kinds.stageDof[k])
      if (i >= 0) (*d)[i] *= f;
    changed = true;
  }
  return changed;
}

bool SceneStageProblem::LimitStep(Eigen::VectorXd* d) {
  if (!contact_ || !soft_ || soft_->kinds.Size() == 0) return false;
  std::vector<double>& kindLimits = ws_->kindLimits;
  Retract(*d, &softTrial_);
  const KindView now = KindViewOf(*soft_, *softX_), next = KindViewOf(*soft_, softTrial_);
  contact_->StepLimits(now, next, &kindLimits);
  bool changed = false;
  for (size_t k = 0; k < soft_->kinds.Size(); ++k) {
    if (kindLimits[k] >= 1.0) continue;
    for (int i : soft_->kinds.stageDof[k])
      if (i >= 0) (*d)[i] *= kindLimits[k];
    changed = true;
  }
  return changed;
}

void SceneStageProblem::BlockLayout(DofBlockLayout* layout) const {
  // In dof order: each kind's free dofs in blocks of its DofBlockSize, then the free soft nodes
  // (3 each).
  std::vector<int>& sizes = layout->sizes;
  sizes.clear();
  if (!soft_) return;
  for (size_t k = 0; k < soft_->kinds.Size(); ++k) {
    int free = 0;
    for (int i : soft_->kinds.stageDof[k]) free += i >= 0;
    const int size = (*soft_->kinds.kinds)[k]->DofBlockSize();
    if (free % size != 0) {  // blocks of 3 then; 1×1 if those do not fit
      sizes.clear();
      return;
    }
    sizes.insert(sizes.end(), free / size, size);
  }
  for (size_t s = 0; s < soft_->targets.size(); ++s)
    sizes.insert(sizes.end(), (*soft_->models)[s].numFree, 3);
}

double SceneStageProblem::StepNorm(const Eigen::VectorXd& d) const {
  double norm = 0.0;
  if (!soft_) return norm;
  // soft nodes [m]
  norm = std::max(norm, d.segment(softBegin_, softEnd_ - softBegin_).lpNorm<Eigen::Infinity>());
  const size_t ns = soft_->targets.size();
  for (size_t k = 0; k < soft_->kinds.Size(); ++k)
    norm = std::max(norm, (*soft_->kinds.kinds)[k]->StepLength((*softX_)[ns + k], KindLocal(k, d)));
  return norm;
}

}  // namespace superdex
