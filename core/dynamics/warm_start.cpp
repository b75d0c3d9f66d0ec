#include "core/dynamics/warm_start.h"

#include "core/model/rigid_kind.h"
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
    if (!models[i].dynamic) {
      out[i] = {s.p, s.R};
      continue;
    }
    const bool staged = stageStart && i < stageStart->size();
    out[i] = PredictRigidPose(s, history ? &(*previous)[i] : nullptr, hPrevious, tau,
                              staged ? &(*stageStart)[i].p : nullptr, stageDt);
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
  const double bound = SteadyBound(gravity);
  for (size_t i = 0; i < current.size() && i < models.size(); ++i) {
    const RigidBodyModel& m = models[i];
    if (!m.dynamic || !(m.mass > 0.0)) continue;
    out[i] = RigidForceChange(m, current[i], (*previous)[i], hPrevious, (*before)[i], hBefore) <=
             bound;
  }
}

bool WarmStart(StageProblem& problem, const std::vector<int>& dofOffset,
               const std::vector<char>& steady, Eigen::VectorXd* step,
               Eigen::VectorXd* scratch, double negligibleStep,
               const std::vector<std::vector<int>>* kindDofs,
               const std::vector<char>* kindSteady) {
  Eigen::VectorXd& d = *step;
  const int n = problem.NumDofs();
  if (n == 0 || d.size() != n || !d.allFinite() || problem.StepNorm(d) <= negligibleStep)
    return false;
  // `bounded` holds the moves of the units that did not move steadily and zero elsewhere (a zero
  // block lies inside any trust region), so that TrustStep shortens those units only.
  const size_t kinds = kindDofs && kindSteady ? kindDofs->size() : 0;
  auto unsteadyBody = [&](size_t i) {
    const int o = dofOffset[i];
    return o >= 0 && o + 6 <= n && !(i < steady.size() && steady[i]);
  };
  auto unsteadyKind = [&](size_t k) { return k < kindSteady->size() && !(*kindSteady)[k]; };
  Eigen::VectorXd& bounded = *scratch;
  bounded.setZero(n);
  bool any = false;
  for (size_t i = 0; i < dofOffset.size(); ++i) {
    if (!unsteadyBody(i)) continue;
    bounded.segment<6>(dofOffset[i]) = d.segment<6>(dofOffset[i]);
    any = true;
  }
  for (size_t k = 0; k < kinds; ++k) {
    if (!unsteadyKind(k)) continue;
    for (int i : (*kindDofs)[k])
      if (i >= 0) bounded[i] = d[i];
    any = true;
  }
  if (any && problem.TrustStep(&bounded)) {
    for (size_t i = 0; i < dofOffset.size(); ++i)
      if (unsteadyBody(i)) d.segment<6>(dofOffset[i]) = bounded.segment<6>(dofOffset[i]);
    for (size_t k = 0; k < kinds; ++k)
      if (unsteadyKind(k))
        for (int i : (*kindDofs)[k])
          if (i >= 0) d[i] = bounded[i];
  }
  problem.LimitStep(&d);
  problem.Commit(d);
  return true;
}

}  // namespace superdex
