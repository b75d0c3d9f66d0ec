#include "core/dynamics/warm_start.h"

#include "core/model/rigid_math.h"

namespace superdex {

namespace {

// PredictPoses, and with `stageStart` PredictStagePoses: the position through the stage's slope.
void Predict(const std::vector<RigidBodyModel>& models, const std::vector<RigidBodyState>& current,
             const std::vector<RigidBodyState>* previous, double hPrevious, double tau,
             const std::vector<RigidBodyState>* stageStart, double stageDt,
             std::vector<RigidPose>* poses) {
  const bool history = previous && previous->size() == current.size() && hPrevious > 0.0;
  std::vector<RigidPose>& out = *poses;
  out.resize(current.size());
  for (size_t i = 0; i < current.size(); ++i) {
    const RigidBodyState& s = current[i];
    out[i].p = s.p;
    out[i].R = s.R;
    if (!models[i].dynamic) continue;
    Eigen::Vector3d dv = Eigen::Vector3d::Zero(), alpha = Eigen::Vector3d::Zero();
    const Eigen::Vector3d omega = s.AngularVelocity();
    if (history) {
      dv = s.v - (*previous)[i].v;
      alpha = (omega - (*previous)[i].AngularVelocity()) / hPrevious;
    }
    if (stageStart && i < stageStart->size()) {
      Eigen::Vector3d v = s.v;
      if (history) v += tau * dv / hPrevious;
      out[i].p = (*stageStart)[i].p + stageDt * v;
    } else {
      const Eigen::Vector3d a = history ? Eigen::Vector3d(dv / hPrevious) : dv;
      out[i].p = s.p + tau * s.v + 0.5 * tau * tau * a;
    }
    out[i].R = ExpSo3(tau * omega + 0.5 * tau * tau * alpha) * s.R;
  }
}

}  // namespace

std::vector<RigidPose> PredictPoses(const std::vector<RigidBodyModel>& models,
                                    const std::vector<RigidBodyState>& current,
                                    const std::vector<RigidBodyState>* previous, double hPrevious,
                                    double tau) {
  std::vector<RigidPose> out;
  Predict(models, current, previous, hPrevious, tau, nullptr, 0.0, &out);
  return out;
}

std::vector<RigidPose> PredictStagePoses(const std::vector<RigidBodyModel>& models,
                                         const std::vector<RigidBodyState>& current,
                                         const std::vector<RigidBodyState>* previous,
                                         double hPrevious, double tau,
                                         const std::vector<RigidBodyState>& stageStart,
                                         double stageDt) {
  std::vector<RigidPose> out;
  PredictStagePoses(models, current, previous, hPrevious, tau, stageStart, stageDt, &out);
  return out;
}

void PredictStagePoses(const std::vector<RigidBodyModel>& models,
                       const std::vector<RigidBodyState>& current,
                       const std::vector<RigidBodyState>* previous, double hPrevious, double tau,
                       const std::vector<RigidBodyState>& stageStart, double stageDt,
                       std::vector<RigidPose>* poses) {
  Predict(models, current, previous, hPrevious, tau, &stageStart, stageDt, poses);
}

Eigen::VectorXd TangentStep(const std::vector<int>& dofOffset, int numDofs,
                            const std::vector<RigidPose>& from, const std::vector<RigidPose>& to) {
  Eigen::VectorXd d;
  TangentStep(dofOffset, numDofs, from, to, &d);
  return d;
}

void TangentStep(const std::vector<int>& dofOffset, int numDofs,
                 const std::vector<RigidPose>& from, const std::vector<RigidPose>& to,
                 Eigen::VectorXd* step) {
  Eigen::VectorXd& d = *step;
  d.setZero(numDofs);
  for (size_t i = 0; i < dofOffset.size() && i < from.size() && i < to.size(); ++i) {
    const int o = dofOffset[i];
    if (o < 0) continue;
    d.segment<3>(o) = to[i].p - from[i].p;
    d.segment<3>(o + 3) = LogSo3(to[i].R * from[i].R.transpose());
  }
}

bool WarmStart(StageProblem& problem, Eigen::VectorXd d, double negligibleStep) {
  return WarmStart(problem, &d, negligibleStep);
}

bool WarmStart(StageProblem& problem, Eigen::VectorXd* step, double negligibleStep) {
  Eigen::VectorXd& d = *step;
  const int n = problem.NumDofs();
  if (n == 0 || d.size() != n || !d.allFinite() || problem.StepNorm(d) <= negligibleStep)
    return false;
  problem.LimitStep(&d);
  problem.Commit(d);
  return true;
}

void SteadyMotion(const std::vector<RigidBodyModel>& models,
                  const std::vector<RigidBodyState>& current,
                  const std::vector<RigidBodyState>* previous, double hPrevious,
                  const std::vector<RigidBodyState>* before, double hBefore,
                  const Eigen::Vector3d& gravity, std::vector<char>* steady) {
  std::vector<char>& out = *steady;
  out.assign(current.size(), 1);
  if (!previous || !before || previous->size() != current.size() ||
      before->size() != current.size() || !(hPrevious > 0.0) || !(hBefore > 0.0))
    return;
  const double bound = kSteadyAcceleration * gravity.norm() + kSteadyFloor;
  for (size_t i = 0; i < current.size() && i < models.size(); ++i) {
    const RigidBodyModel& m = models[i];
    if (!m.dynamic || !(m.mass > 0.0)) continue;
    const RigidBodyState& s2 = current[i];
    const RigidBodyState& s1 = (*previous)[i];
    const RigidBodyState& s0 = (*before)[i];
    const Eigen::Vector3d a2 = (s2.v - s1.v) / hPrevious, a1 = (s1.v - s0.v) / hBefore;
    auto momentum = [&](const RigidBodyState& s) -> Eigen::Vector3d {
      return WorldInertia(s.R, m.secondMoment) * s.AngularVelocity();
    };
    const Eigen::Vector3d L2 = momentum(s2), L1 = momentum(s1), L0 = momentum(s0);
    const Eigen::Vector3d dTorque = (L2 - L1) / hPrevious - (L1 - L0) / hBefore;
    const double rho = RmsRadius(m);
    const double angular = rho > 0.0 ? dTorque.norm() / (m.mass * rho) : 0.0;
    out[i] = (a2 - a1).norm() + angular <= bound;
  }
}

bool WarmStart(StageProblem& problem, const std::vector<int>& dofOffset,
               const std::vector<char>& steady, Eigen::VectorXd* step,
               Eigen::VectorXd* scratch, double negligibleStep) {
  Eigen::VectorXd& d = *step;
  const int n = problem.NumDofs();
  if (n == 0 || d.size() != n || !d.allFinite() || problem.StepNorm(d) <= negligibleStep)
    return false;
  // `bounded` holds the moves of the bodies that did not move steadily and zero elsewhere (a zero
  // block lies inside any trust region), so that TrustStep shortens those bodies only.
  Eigen::VectorXd& bounded = *scratch;
  bounded.setZero(n);
  bool any = false;
  for (size_t i = 0; i < dofOffset.size(); ++i) {
    const int o = dofOffset[i];
    if (o < 0 || o + 6 > n || (i < steady.size() && steady[i])) continue;
    bounded.segment<6>(o) = d.segment<6>(o);
    any = true;
  }
  if (any && problem.TrustStep(&bounded)) {
    for (size_t i = 0; i < dofOffset.size(); ++i) {
      const int o = dofOffset[i];
      if (o >= 0 && o + 6 <= n && !(i < steady.size() && steady[i]))
        d.segment<6>(o) = bounded.segment<6>(o);
    }
  }
  problem.LimitStep(&d);
  problem.Commit(d);
  return true;
}

}  // namespace superdex
