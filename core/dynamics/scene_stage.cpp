#include "core/dynamics/scene_stage.h"


#include "core/model/rigid_kind.h"
#include "core/model/rigid_math.h"
#include "energies/psd_projection.h"
#include "energies/rigid_inertia.h"
#include "optim/linear_solver.h"

namespace superdex {

SceneStageProblem::SceneStageProblem(const std::vector<RigidBodyModel>& models,
                                     const std::vector<int>& dofOffset, int numDofs,
                                     const StageTargets& targets, const Eigen::Vector3d& gravity,
                                     ContactPipeline* contact, std::vector<RigidPose>* poses,
                                     const StageDissipation& dissipation, const SoftStage* soft,
                                     std::vector<Eigen::VectorXd>* softX,
                                     StageWorkspace* workspace)
    : models_(models),
      dofOffset_(dofOffset),
      numDofs_(numDofs),
      targets_(targets),
      gravity_(gravity),
      contact_(contact),
      poses_(poses),
      ownWorkspace_(workspace ? nullptr : std::make_unique<StageWorkspace>()),
      ws_(workspace ? workspace : ownWorkspace_.get()),
      trial_(ws_->trial),
      softTrial_(ws_->softTrial),
      limits_(ws_->limits),
      scratch_(ws_->scratch),
      pendingStep_(ws_->pendingStep),
      triplets_(ws_->triplets),
      dissipation_(dissipation),
      soft_(soft && softX && !soft->Empty() ? soft : nullptr),
      softX_(soft_ ? softX : nullptr) {
  trial_.resize(poses->size());  // Retract writes every entry
  if (soft_) {
    softTrial_ = *softX_;
    if (ws_->soft.size() < soft_->targets.size()) ws_->soft.resize(soft_->targets.size());
    // The soft nodes' dofs: one range, the last dofs (Scene::Prepare).
    softBegin_ = softEnd_ = numDofs_;
    for (size_t s = 0; s < soft_->targets.size(); ++s)
      if ((*soft_->models)[s].numFree > 0) softBegin_ = std::min(softBegin_, soft_->dofOffset[s]);
  }
  context_ = ContextOf(dissipation_, targets_.dt);
  for (size_t i = 0; i < targets_.torque.size(); ++i)
    if (dofOffset_[i] >= 0 && targets_.torque[i].any()) hasTorque_ = true;
  if (hasTorque_) torqueWork_.assign(models_.size(), 0.0);
  if (soft_) {  // the kinds' loads at the stage's time
    const KindStage& ks = soft_->kinds;
    for (size_t k = 0; k < ks.Size(); ++k) {
      Eigen::VectorXd f;
      if (!(*ks.kinds)[k]->StageLoad(ks.data[k], &f) || !f.any()) continue;
      kindLoad_.resize(ks.Size());
      kindLoadWork_.assign(ks.Size(), 0.0);
      kindLoad_[k] = std::move(f);
      hasTorque_ = true;
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

bool SceneStageProblem::IsPotential() const { return DissipationIsPotential() && !hasTorque_; }

bool SceneStageProblem::DissipationIsPotential() const {
  return !dissipation_.enabled || dissipation_.mode == DissipationMode::ExplicitNormals;
}

double SceneStageProblem::AppliedLoads(size_t i, const RigidPose& pose, int order,
                                       Eigen::VectorXd* gPot, Eigen::VectorXd* rDiss) const {
  double value = 0.0;
  const int o = dofOffset_[i];
  if (!targets_.force.empty()) {
    const Eigen::Vector3d& F = targets_.force[i];
    value -= F.dot(pose.p);
    if (order >= 1) gPot->segment<3>(o) -= F;
  }
  if (hasTorque_) {
    const Eigen::Vector3d& tau = targets_.torque[i];
    if (tau.any()) {
      const bool current = &pose == &(*poses_)[i];  // Evaluate's: log(R R_cᵀ) = 0 exactly
      value -= torqueWork_[i] +
               (current ? 0.0 : tau.dot(LogSo3(pose.R * (*poses_)[i].R.transpose())));
      if (order >= 1) rDiss->segment<3>(o + 3) -= tau;
    }
  }
  return value;
}

void SceneStageProblem::Retract(const Eigen::VectorXd& d, std::vector<RigidPose>* out,
                                std::vector<Eigen::VectorXd>* softOut) const {
  if (soft_ && softOut) {
    for (size_t s = 0; s < soft_->targets.size(); ++s) {
      const SoftBodyModel& m = (*soft_->models)[s];
      Eigen::VectorXd& x = (*softOut)[s];
      x = (*softX_)[s];
      for (int a = 0; a < m.NumNodes(); ++a)
        if (m.freeIndex[a] >= 0)
          x.segment<3>(3 * a) += d.segment<3>(soft_->dofOffset[s] + 3 * m.freeIndex[a]);
    }
    const size_t ns = soft_->targets.size();
    for (size_t k = 0; k < soft_->kinds.Size(); ++k)
      (*soft_->kinds.kinds)[k]->Retract((*softX_)[ns + k], KindLocal(k, d), &(*softOut)[ns + k]);
  }
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    (*out)[i] = (*poses_)[i];
    if (o < 0) continue;
    (*out)[i].p += d.segment<3>(o);
    (*out)[i].R = ExpSo3(d.segment<3>(o + 3)) * (*poses_)[i].R;
  }
}

double SceneStageProblem::EvaluateAt(const std::vector<RigidPose>& poses,
                                     const std::vector<Eigen::VectorXd>& softX, int order,
                                     PsdProjection projection, Eigen::VectorXd* gPot,
                                     Eigen::VectorXd* rDiss, ContactStats* stats,
                                     double* minDetF) {
  const double w = 1.0 / (targets_.dt * targets_.dt);
  double value = 0.0;
  if (order >= 1) {
    gPot->setZero(numDofs_);
    if (rDiss != gPot) rDiss->setZero(numDofs_);
  }
  triplets_.clear();
  ws_->blocks.clear();
  std::vector<double>& bodyValue = ws_->bodyValue;
  bodyValue.assign(models_.size(), 0.0);
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    if (o < 0) continue;
    const RigidBodyModel& m = models_[i];
    const RigidInertiaTerm t = RigidInertia(m.mass, m.secondMoment, poses[i].p, poses[i].R,
                                            targets_.pHat[i], targets_.RHat[i], order >= 1);
    bodyValue[i] = w * t.value + GravityPotential(m.mass, gravity_, poses[i].p) +
                   AppliedLoads(i, poses[i], order, gPot, rDiss);
    value += bodyValue[i];
    if (order == 0) continue;
    gPot->segment<6>(o) += w * t.gradient;
    gPot->segment<3>(o) -= m.mass * gravity_;
    if (order < 2) continue;
    AppendRigidInertiaHessian(w * t.hessian, projection, o, &triplets_);
  }
  SoftView view;
  if (soft_) {
    double minDet = INFINITY;
    for (size_t s = 0; s < soft_->targets.size(); ++s) {
      double md = INFINITY;
      value += EvaluateSoftStageTerms((*soft_->models)[s], soft_->targets[s], targets_.dt, gravity_,
                                      softX[s], order, projection, soft_->dofOffset[s], gPot,
                                      &triplets_, &ws_->soft[s], &md);
      minDet = std::min(minDet, md);
    }
    if (minDetF) *minDetF = minDet;
    value += EvaluateKindTerms(softX, order, projection, gPot, rDiss);
    view.x = &softX;
    view.xLast = &soft_->xLast;
    view.x0 = &soft_->x0;
    view.dofOffset = &soft_->dofOffset;
  }
  ws_->blockPosition = triplets_.size();
  const KindView kinds = soft_ ? KindViewOf(*soft_, softX) : KindView();
  value += contact_->Evaluate(poses, dofOffset_, order, projection, gPot, &triplets_, &ws_->blocks,
                              stats, dissipation_.enabled ? &context_ : nullptr, rDiss,
                              targets_.start.empty() ? nullptr : &targets_.start,
                              soft_ ? &view : nullptr, kinds.q ? &kinds : nullptr);
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
  Retract(d, &trial_, &softTrial_);
  return EvaluateAt(trial_, softTrial_, 0, PsdProjection::None, nullptr, nullptr);
}

double SceneStageProblem::Evaluate(Eigen::VectorXd* gradient,
                                   Eigen::SparseMatrix<double>* hessian,
                                   PsdProjection projection) {
  return ValueAndDerivatives(*poses_, SoftPositions(), gradient, hessian, projection, &lastStats_,
                             &lastMinDetF_);
}

void SceneStageProblem::BeginTrial(const Eigen::VectorXd& d) {
  // trial_ is what Commit(d) installs (the same Retract), so the sums evaluated there are those
  // that Evaluate and EvaluateResidual form after it, bit for bit.
  Retract(d, &trial_, &softTrial_);
  pendingStep_ = d;
  hasPending_ = true;
}

bool SceneStageProblem::EvaluateAtStep(const Eigen::VectorXd& d, double* value,
                                       Eigen::VectorXd* gradient,
                                       Eigen::SparseMatrix<double>* hessian,
                                       PsdProjection projection) {
  BeginTrial(d);
  *value = ValueAndDerivatives(trial_, softTrial_, gradient, hessian, projection, &pendingStats_,
                               &pendingMinDetF_);
  return true;
}

double SceneStageProblem::ValueAndDerivatives(const std::vector<RigidPose>& poses,
                                              const std::vector<Eigen::VectorXd>& softX,
                                              Eigen::VectorXd* gradient,
                                              Eigen::SparseMatrix<double>* hessian,
                                              PsdProjection projection, ContactStats* stats,
                                              double* minDetF) {
  const double value = EvaluateAt(poses, softX, hessian ? 2 : 1, projection, gradient, gradient,
                                  stats, minDetF);
  if (hessian)
    ws_->hessianAssembly.Assemble(triplets_, ws_->blocks, ws_->blockPosition, numDofs_, hessian);
  return value;
}

void SceneStageProblem::Residual(const Eigen::VectorXd& d, Eigen::VectorXd* r) {
  Retract(d, &trial_, &softTrial_);
  EvaluateAt(trial_, softTrial_, 1, PsdProjection::None, r, r);
}

void SceneStageProblem::EvaluateResidual(Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J) {
  ResidualAndJacobian(*poses_, SoftPositions(), r, J, &lastStats_, &lastMinDetF_);
}

bool SceneStageProblem::EvaluateResidualAtStep(const Eigen::VectorXd& d, Eigen::VectorXd* r,
                                               Eigen::SparseMatrix<double>* J) {
  BeginTrial(d);
  ResidualAndJacobian(trial_, softTrial_, r, J, &pendingStats_, &pendingMinDetF_);
  return true;
}

void SceneStageProblem::ResidualAndJacobian(const std::vector<RigidPose>& poses,
                                            const std::vector<Eigen::VectorXd>& softX,
                                            Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J,
                                            ContactStats* stats, double* minDetF) {
  EvaluateAt(poses, softX, J ? 2 : 1, PsdProjection::None, r, &scratch_, stats, minDetF);
  if (J) {
    // The rotation entries of r are world torques τ. Along the retraction exp([δθ]×) R the torque
    // of a potential changes by (H − ½[τ]×) δθ, H its second derivative (assembled above); the
    // dissipation Jacobian of the residual modes is already that of the world torque.
    // An applied torque (in scratch_) is a constant world torque: it adds nothing to J.
    const bool dissipationIsPotential = DissipationIsPotential();
    for (size_t i = 0; i < models_.size(); ++i) {
      const int o = dofOffset_[i];
      if (o < 0) continue;
      Eigen::Vector3d tau = r->segment<3>(o + 3);
      if (dissipationIsPotential) tau += scratch_.segment<3>(o + 3);
      if (dissipationIsPotential && hasTorque_) tau += targets_.torque[i];
      AppendSpinTrivialization(tau, o + 3, &triplets_);
    }
    if (soft_) AddKindJacobianCorrections(*r, dissipationIsPotential, softX);
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
  origin_ = *poses_;
  torqueWork_.assign(models_.size(), 0.0);  // the chart's solvers read residuals alone
  std::fill(kindLoadWork_.begin(), kindLoadWork_.end(), 0.0);
  if (soft_) softOrigin_ = *softX_;
}

void SceneStageProblem::MoveInChart(const Eigen::VectorXd& d) {
  if (soft_) {
    // Soft nodes live in a vector space: the chart is the identity.
    *softX_ = softOrigin_;
    Retract(d, &trial_, &softTrial_);
    *softX_ = softTrial_;
  }
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    (*poses_)[i] = origin_[i];
    if (o < 0) continue;
    (*poses_)[i].p += d.segment<3>(o);
    (*poses_)[i].R = ExpSo3(d.segment<3>(o + 3)) * origin_[i].R;
  }
}

Eigen::MatrixXd SceneStageProblem::ChartTangentMap(const Eigen::VectorXd& d) const {
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(numDofs_, numDofs_);
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    if (o >= 0) T.block<3, 3>(o + 3, o + 3) = LeftJacobianSo3(d.segment<3>(o + 3));
  }
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
  Retract(d, &trial_, &softTrial_);
  // The torques' work along the committed iterates, as AppliedLoads evaluates the trial's.
  if (hasTorque_)
    for (size_t i = 0; i < models_.size(); ++i)
      if (dofOffset_[i] >= 0 && targets_.torque[i].any())
        torqueWork_[i] += targets_.torque[i].dot(LogSo3(trial_[i].R * (*poses_)[i].R.transpose()));
  if (!kindLoad_.empty()) {
    const size_t ns = soft_->targets.size();
    for (size_t k = 0; k < kindLoad_.size(); ++k) {
      if (kindLoad_[k].size() == 0) continue;
      (*soft_->kinds.kinds)[k]->TangentBetween((*softX_)[ns + k], softTrial_[ns + k],
                                               &ws_->kindDelta);
      kindLoadWork_[k] += kindLoad_[k].dot(ws_->kindDelta);
    }
  }
  *poses_ = trial_;
  if (soft_) *softX_ = softTrial_;
  if (hasPending_ && pendingStep_ == d) {
    lastStats_ = pendingStats_;
    lastMinDetF_ = pendingMinDetF_;
  }
  hasPending_ = false;
}

bool SceneStageProblem::LastSplit(StageSplit* split) {
  // Units: the dynamic rigid bodies (unit = dofOffset / 6: their dofs lead), then one per kind.
  if (soft_ && !soft_->targets.empty()) return false;  // soft actors: not split
  const KindStage* kinds = soft_ && soft_->kinds.Size() > 0 ? &soft_->kinds : nullptr;
  const size_t nk = kinds ? kinds->Size() : 0;
  int rigidDofs = 0;
  for (size_t i = 0; i < models_.size(); ++i)
    if (dofOffset_[i] >= 0) rigidDofs += 6;
  const int rigidUnits = rigidDofs / 6;
  const int units = rigidUnits + static_cast<int>(nk);
  if (static_cast<int>(split->unitOfDof.size()) != numDofs_ || split->units != units) {
    split->unitOfDof.assign(numDofs_, 0);
    for (int k = 0; k < rigidDofs; ++k) split->unitOfDof[k] = k / 6;
    for (size_t k = 0; k < nk; ++k)
      for (int i : kinds->stageDof[k])
        if (i >= 0) split->unitOfDof[i] = rigidUnits + static_cast<int>(k);
    split->units = units;
  }
  if (ws_->bodyValue.size() != models_.size() || ws_->kindValue.size() != nk) return false;
  // Per actor (rigid models, then kinds): its terms' values, then the contact pairs' shares.
  std::vector<double>& value = ws_->splitValue;
  value = ws_->bodyValue;
  value.insert(value.end(), ws_->kindValue.begin(), ws_->kindValue.end());
  split->joins.clear();
  if (contact_ && !contact_->SplitLastEvaluation(dofOffset_, &value, &split->joins)) return false;
  auto unit = [&](int actor) {
    const int n = static_cast<int>(models_.size());
    return actor < n ? dofOffset_[actor] / 6 : rigidUnits + actor - n;
  };
  split->share.assign(units, 0.0);
  for (size_t i = 0; i < models_.size(); ++i)
    if (dofOffset_[i] >= 0) split->share[unit(static_cast<int>(i))] += value[i];
  for (size_t k = 0; k < nk; ++k)
    split->share[rigidUnits + k] += value[models_.size() + k];
  for (std::pair<int, int>& j : split->joins) j = {unit(j.first), unit(j.second)};
  return true;
}

bool SceneStageProblem::TrustStep(Eigen::VectorXd* d) {
  bool changed = false;
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    if (o < 0) continue;
    const double f = RigidTrustFraction(models_[i], d->segment<3>(o), d->segment<3>(o + 3));
    if (!(f < 1.0)) continue;
    d->segment<6>(o) *= f;
    changed = true;
  }
  if (!soft_) return changed;
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
  if (!contact_) return false;
  const bool kinds = soft_ && soft_->kinds.Size() > 0;
  std::vector<double>& kindLimits = ws_->kindLimits;
  Retract(*d, &trial_, kinds ? &softTrial_ : nullptr);
  if (kinds) {
    const KindView now = KindViewOf(*soft_, *softX_), next = KindViewOf(*soft_, softTrial_);
    contact_->StepLimits(*poses_, trial_, &limits_, &now, &next, &kindLimits);
  } else {
    contact_->StepLimits(*poses_, trial_, &limits_);
  }
  bool changed = false;
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    if (o < 0 || limits_[i] >= 1.0) continue;
    d->segment<6>(o) *= limits_[i];
    changed = true;
  }
  if (!kinds) return changed;
  for (size_t k = 0; k < soft_->kinds.Size(); ++k) {
    if (kindLimits[k] >= 1.0) continue;
    for (int i : soft_->kinds.stageDof[k])
      if (i >= 0) (*d)[i] *= kindLimits[k];
    changed = true;
  }
  return changed;
}

void SceneStageProblem::BlockLayout(DofBlockLayout* layout) const {
  // In dof order: the dynamic rigid bodies (6 each, leading without gaps), each kind's free dofs
  // in blocks of its DofBlockSize, then the free soft nodes (3 each).
  std::vector<int>& sizes = layout->sizes;
  sizes.clear();
  int expected = 0;
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    if (o < 0) continue;
    if (o != expected) {  // not leading in order: no blocks of six claimed
      sizes.clear();
      return;
    }
    sizes.push_back(6);
    expected += 6;
  }
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
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    if (o < 0) continue;
    norm = std::max(norm, RigidStepLength(models_[i], d.segment<3>(o), d.segment<3>(o + 3)));
  }
  if (soft_) {  // soft nodes [m]
    norm = std::max(norm, d.segment(softBegin_, softEnd_ - softBegin_).lpNorm<Eigen::Infinity>());
    const size_t ns = soft_->targets.size();
    for (size_t k = 0; k < soft_->kinds.Size(); ++k)
      norm = std::max(norm, (*soft_->kinds.kinds)[k]->StepLength((*softX_)[ns + k],
                                                                  KindLocal(k, d)));
  }
  return norm;
}

}  // namespace superdex
