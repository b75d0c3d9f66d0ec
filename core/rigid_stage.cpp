#include "core/rigid_stage.h"

#include "core/rigid_math.h"
#include "energies/psd_projection.h"
#include "energies/rigid_inertia.h"

namespace superdex {

RigidStageProblem::RigidStageProblem(const std::vector<RigidBodyModel>& models,
                                     const std::vector<int>& dofOffset, int numDofs,
                                     const StageTargets& targets, const Eigen::Vector3d& gravity,
                                     ContactPipeline* contact, std::vector<RigidPose>* poses,
                                     const StageDissipation& dissipation)
    : models_(models),
      dofOffset_(dofOffset),
      numDofs_(numDofs),
      targets_(targets),
      gravity_(gravity),
      contact_(contact),
      poses_(poses),
      dissipation_(dissipation) {
  trial_ = *poses;
  context_.dt = targets_.dt;
  context_.mode = dissipation_.mode;
  context_.fadeFriction = dissipation_.fadeFriction;
}

bool RigidStageProblem::IsPotential() const {
  return !dissipation_.enabled || dissipation_.mode == DissipationMode::ExplicitNormals;
}

double RigidStageProblem::BodyEnergy(size_t i, const RigidPose& pose) const {
  const RigidBodyModel& m = models_[i];
  const double w = 1.0 / (targets_.dt * targets_.dt);
  const RigidInertiaTerm t = RigidInertia(m.mass, m.secondMoment, pose.p, pose.R,
                                          targets_.pHat[i], targets_.RHat[i], false);
  return w * t.value + GravityPotential(m.mass, gravity_, pose.p);
}

void RigidStageProblem::Retract(const Eigen::VectorXd& d, std::vector<RigidPose>* out) const {
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    (*out)[i] = (*poses_)[i];
    if (o < 0) continue;
    (*out)[i].p += d.segment<3>(o);
    (*out)[i].R = ExpSo3(d.segment<3>(o + 3)) * (*poses_)[i].R;
  }
}

double RigidStageProblem::EvaluateAt(const std::vector<RigidPose>& poses, int order,
                                     PsdProjection projection, Eigen::VectorXd* gPot,
                                     Eigen::VectorXd* rDiss, ContactStats* stats) {
  const double w = 1.0 / (targets_.dt * targets_.dt);
  double value = 0.0;
  if (order >= 1) {
    gPot->setZero(numDofs_);
    if (rDiss != gPot) rDiss->setZero(numDofs_);
  }
  triplets_.clear();
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    if (o < 0) continue;
    const RigidBodyModel& m = models_[i];
    const RigidInertiaTerm t = RigidInertia(m.mass, m.secondMoment, poses[i].p, poses[i].R,
                                            targets_.pHat[i], targets_.RHat[i], order >= 1);
    value += w * t.value + GravityPotential(m.mass, gravity_, poses[i].p);
    if (order == 0) continue;
    gPot->segment<6>(o) += w * t.gradient;
    gPot->segment<3>(o) -= m.mass * gravity_;
    if (order < 2) continue;
    StencilMatrix H = w * t.hessian;
    if (projection != PsdProjection::None) ProjectToPsd(&H, projection == PsdProjection::Abs);
    for (int c = 0; c < 6; ++c)
      for (int r = 0; r < 6; ++r)
        if (H(r, c) != 0.0) triplets_.emplace_back(o + r, o + c, H(r, c));
  }
  value += contact_->Evaluate(poses, dofOffset_, order, projection, gPot, &triplets_, stats,
                              dissipation_.enabled ? &context_ : nullptr, rDiss,
                              targets_.start.empty() ? nullptr : &targets_.start);
  return value;
}

double RigidStageProblem::Value(const Eigen::VectorXd& d) {
  Retract(d, &trial_);
  return EvaluateAt(trial_, 0, PsdProjection::None, nullptr, nullptr);
}

double RigidStageProblem::Evaluate(Eigen::VectorXd* gradient,
                                   Eigen::SparseMatrix<double>* hessian,
                                   PsdProjection projection) {
  const double value =
      EvaluateAt(*poses_, hessian ? 2 : 1, projection, gradient, gradient, &lastStats_);
  if (hessian) {
    hessian->resize(numDofs_, numDofs_);
    hessian->setFromTriplets(triplets_.begin(), triplets_.end());
  }
  return value;
}

void RigidStageProblem::Residual(const Eigen::VectorXd& d, Eigen::VectorXd* r) {
  Retract(d, &trial_);
  EvaluateAt(trial_, 1, PsdProjection::None, r, r);
}

void RigidStageProblem::EvaluateResidual(Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J) {
  EvaluateAt(*poses_, J ? 2 : 1, PsdProjection::None, r, &scratch_, &lastStats_);
  if (J) {
    // The rotation entries of r are world torques τ. Along the retraction exp([δθ]×) R the torque
    // of a potential changes by (H − ½[τ]×) δθ, H its second derivative (assembled above); the
    // dissipation Jacobian of the residual modes is already that of the world torque.
    const bool dissipationIsPotential = IsPotential();
    for (size_t i = 0; i < models_.size(); ++i) {
      const int o = dofOffset_[i];
      if (o < 0) continue;
      Eigen::Vector3d tau = r->segment<3>(o + 3);
      if (dissipationIsPotential) tau += scratch_.segment<3>(o + 3);
      const Eigen::Matrix3d S = -0.5 * Skew(tau);
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k)
          if (S(k, c) != 0.0) triplets_.emplace_back(o + 3 + k, o + 3 + c, S(k, c));
    }
    J->resize(numDofs_, numDofs_);
    J->setFromTriplets(triplets_.begin(), triplets_.end());
  }
  *r += scratch_;
}

void RigidStageProblem::MoveInChart(const Eigen::VectorXd& d) {
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    (*poses_)[i] = origin_[i];
    if (o < 0) continue;
    (*poses_)[i].p += d.segment<3>(o);
    (*poses_)[i].R = ExpSo3(d.segment<3>(o + 3)) * origin_[i].R;
  }
}

Eigen::MatrixXd RigidStageProblem::ChartTangentMap(const Eigen::VectorXd& d) const {
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(numDofs_, numDofs_);
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    if (o >= 0) T.block<3, 3>(o + 3, o + 3) = LeftJacobianSo3(d.segment<3>(o + 3));
  }
  return T;
}

void RigidStageProblem::Commit(const Eigen::VectorXd& d) {
  Retract(d, &trial_);
  *poses_ = trial_;
}

double RigidStageProblem::StepNorm(const Eigen::VectorXd& d) const {
  double norm = 0.0;
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    if (o < 0) continue;
    // RMS distance of the body's material points from its centre of mass.
    const double radius = std::sqrt(models_[i].secondMoment.trace() / models_[i].mass);
    norm = std::max(norm, d.segment<3>(o).lpNorm<Eigen::Infinity>());
    norm = std::max(norm, d.segment<3>(o + 3).norm() * radius);
  }
  return norm;
}

}  // namespace superdex
