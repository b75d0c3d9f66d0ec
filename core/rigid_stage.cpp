#include "core/rigid_stage.h"

#include "core/rigid_math.h"
#include "energies/psd_projection.h"
#include "energies/rigid_inertia.h"

namespace superdex {

RigidStageProblem::RigidStageProblem(const std::vector<RigidBodyModel>& models,
                                     const std::vector<int>& dofOffset, int numDofs,
                                     const StageTargets& targets, const Eigen::Vector3d& gravity,
                                     ContactPipeline* contact, std::vector<RigidPose>* poses)
    : models_(models),
      dofOffset_(dofOffset),
      numDofs_(numDofs),
      targets_(targets),
      gravity_(gravity),
      contact_(contact),
      poses_(poses) {
  trial_ = *poses;
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

double RigidStageProblem::Value(const Eigen::VectorXd& d) {
  Retract(d, &trial_);
  double value = 0.0;
  for (size_t i = 0; i < models_.size(); ++i)
    if (dofOffset_[i] >= 0) value += BodyEnergy(i, trial_[i]);
  value += contact_->Evaluate(trial_, dofOffset_, 0, PsdProjection::None, nullptr, nullptr,
                              nullptr);
  return value;
}

double RigidStageProblem::Evaluate(Eigen::VectorXd* gradient,
                                   Eigen::SparseMatrix<double>* hessian,
                                   PsdProjection projection) {
  const std::vector<RigidPose>& poses = *poses_;
  gradient->setZero(numDofs_);
  triplets_.clear();
  const double w = 1.0 / (targets_.dt * targets_.dt);
  double value = 0.0;
  for (size_t i = 0; i < models_.size(); ++i) {
    const int o = dofOffset_[i];
    if (o < 0) continue;
    const RigidBodyModel& m = models_[i];
    const RigidInertiaTerm t = RigidInertia(m.mass, m.secondMoment, poses[i].p, poses[i].R,
                                            targets_.pHat[i], targets_.RHat[i], true);
    value += w * t.value + GravityPotential(m.mass, gravity_, poses[i].p);
    gradient->segment<6>(o) += w * t.gradient;
    gradient->segment<3>(o) -= m.mass * gravity_;
    if (!hessian) continue;
    StencilMatrix H = w * t.hessian;
    if (projection != PsdProjection::None)
      ProjectToPsd(&H, projection == PsdProjection::Abs);
    for (int c = 0; c < 6; ++c)
      for (int r = 0; r < 6; ++r)
        if (H(r, c) != 0.0) triplets_.emplace_back(o + r, o + c, H(r, c));
  }
  value += contact_->Evaluate(poses, dofOffset_, hessian ? 2 : 1, projection, gradient,
                              &triplets_, nullptr);
  if (hessian) {
    hessian->resize(numDofs_, numDofs_);
    hessian->setFromTriplets(triplets_.begin(), triplets_.end());
  }
  return value;
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
