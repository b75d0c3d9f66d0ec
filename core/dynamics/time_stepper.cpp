#include "core/dynamics/time_stepper.h"

#include <algorithm>

#include "core/dynamics/integrators.h"
#include "core/model/rigid_kind.h"
#include "core/model/rigid_math.h"

namespace superdex {
namespace {

// A kind's state at the step's end where it is prescribed: a static kind's stays as it was (held
// exactly, not through the integrator's combinations of equal states), a moving one's dofs on
// its path (ActorKind::EndPrescribed).
void EndPrescribed(const ActorKind& kind, const KindState& before, double t, KindState* end) {
  if (kind.IsStatic()) {
    end->x = before.x;
    end->v = before.v;
    return;
  }
  kind.EndPrescribed(t, end);
}

// a·x + b·y over every field (poses as matrices: the result's R need not be a rotation).
RigidBodyState Affine(double a, const RigidBodyState& x, double b, const RigidBodyState& y) {
  RigidBodyState s;
  s.p = a * x.p + b * y.p;
  s.R = a * x.R + b * y.R;
  s.v = a * x.v + b * y.v;
  s.Rdot = a * x.Rdot + b * y.Rdot;
  return s;
}

// The kinematic bodies' poses at time t [s]: a stage's configuration holds them there.
void PlaceKinematic(const std::vector<RigidBodyModel>& models, double t,
                    std::vector<RigidPose>* poses) {
  for (size_t i = 0; i < models.size(); ++i)
    if (models[i].kinematic) {
      const RigidBodyState s = KinematicStateAt(models[i], t);
      (*poses)[i] = {s.p, s.R};
    }
}

// The kinematic bodies' states at the step's end time t [s].
void EndKinematic(const std::vector<RigidBodyModel>& models, double t,
                  std::vector<RigidBodyState>* next) {
  for (size_t i = 0; i < models.size(); ++i)
    if (models[i].kinematic) (*next)[i] = KinematicStateAt(models[i], t);
}

}  // namespace

void StepBdf(const std::vector<RigidBodyModel>& models, const StepState& step, double h,
             IntegrationMethod method, StageHost& host, StepBuffers* buffersOut, StepWork* work) {
  StepBuffers& buffers = *buffersOut;
  auto& [poses, stepStart, next, softX, softStepStart, softNext, rep] = *work;
  const size_t n = models.size(), ns = step.softStates.size();  // ns: soft actors and kinds
  // BDF-k with variable steps.
  const int k = std::min<int>(BdfSteps(method), static_cast<int>(step.history.size()) + 1);
  std::vector<double>& times = buffers.bdfTimes;
  times.assign({step.time + h, step.time});
  for (int j = 0; j + 1 < k; ++j) times.push_back(step.historyTimes[j]);
  std::vector<double>& weights = buffers.bdfWeights;
  const double dt = BdfCoefficients(times, &weights);
  std::vector<RigidBodyState>& start = buffers.start;
  start.resize(n);
  for (size_t i = 0; i < n; ++i) {
    start[i] = Affine(weights[0], step.states[i], 0.0, step.states[i]);
    for (int j = 1; j < k; ++j) start[i] = Affine(1.0, start[i], weights[j], step.history[j - 1][i]);
  }
  std::vector<SoftBodyState>& softStart = buffers.softStart;
  softStart.resize(ns);
  for (size_t s = 0; s < ns; ++s) {
    softStart[s].x = weights[0] * step.softStates[s].x;
    softStart[s].v = weights[0] * step.softStates[s].v;
    for (int j = 1; j < k; ++j) {
      softStart[s].x += weights[j] * step.softHistory[j - 1][s].x;
      softStart[s].v += weights[j] * step.softHistory[j - 1][s].v;
    }
  }
  host.ApplyConstraints(step.time + h, &softX);
  PlaceKinematic(models, step.time + h, &poses);
  SoftStage& soft = buffers.softStage;
  host.MakeSoftStage(dt, step.time + h, softStart, softStepStart, &soft);
  host.SolveStage(dt, start, stepStart, &poses, &soft, &softX, h, &rep);
  for (size_t s = 0; s < ns; ++s) {
    softNext[s].x = softX[s];
    softNext[s].v = (softX[s] - softStart[s].x) / dt;
    if (const ActorKind* kind = host.VectorKind(s)) EndPrescribed(*kind, step.softStates[s], step.time + h, &softNext[s]);
  }
  for (size_t i = 0; i < n; ++i) {
    if (!models[i].dynamic) continue;
    next[i].p = poses[i].p;
    next[i].R = poses[i].R;
    next[i].v = (poses[i].p - start[i].p) / dt;
    next[i].Rdot = (poses[i].R - start[i].R) / dt;
  }
  EndKinematic(models, step.time + h, &next);
}

void StepDirk(const std::vector<RigidBodyModel>& models, const StepState& step, double h,
              IntegrationMethod method, StageHost& host, StepBuffers* buffersOut, StepWork* work) {
  StepBuffers& buffers = *buffersOut;
  auto& [poses, stepStart, next, softX, softStepStart, softNext, rep] = *work;
  const size_t n = models.size(), ns = step.softStates.size();  // ns: soft actors and kinds
  // DIRK stages in material-point form, with the three rotation rules of core/dynamics/integrators.h.
  const DirkTableau& T = TableauOf(method);
  // Every entry is written at its stage before it is read.
  std::vector<std::vector<RigidBodyState>>& VK = buffers.stageSlopes;
  std::vector<std::vector<Eigen::Vector3d>>& torque = buffers.stageTorques;
  std::vector<std::vector<RigidPose>>& Q = buffers.stagePoses;
  if (VK.size() < static_cast<size_t>(T.stages)) {
    VK.resize(T.stages);
    torque.resize(T.stages);
    Q.resize(T.stages);
  }
  for (int st = 0; st < T.stages; ++st) {
    VK[st].resize(n);
    torque[st].resize(n);
  }
  // Vector states: stage slopes (position, velocity) per actor and stage, as for p and v; the
  // kinds' from their own rule (ActorKind::DirkStageSlope).
  std::vector<std::vector<KindSlope>>& softVK = buffers.vectorSlopes;
  softVK.resize(ns);
  for (std::vector<KindSlope>& slopes : softVK) slopes.resize(T.stages);
  std::vector<Eigen::VectorXd>& softLast = buffers.softLast;
  softLast = softStepStart;
  for (int st = 0; st < T.stages; ++st) {
    std::vector<RigidBodyState>& start = buffers.start;
    start = step.states;
    for (size_t i = 0; i < n; ++i)
      for (int j = 0; j < st; ++j) {
        const double c = h * T.a[st][j];
        start[i].p += c * VK[j][i].p;
        start[i].R += c * VK[j][i].R;
        start[i].v += c * VK[j][i].v;
        start[i].Rdot += c * VK[j][i].Rdot;
      }
    std::vector<SoftBodyState>& softStart = buffers.softStart;
    softStart = step.softStates;
    double cStage = 0.0;  // the stage's abscissa c_i = Σ_j a_ij
    for (int j = 0; j <= st; ++j) cStage += T.a[st][j];
    for (size_t s = 0; s < ns; ++s)
      for (int j = 0; j < st; ++j) {
        const double c = h * T.a[st][j];
        softStart[s].x += c * softVK[s][j].slope.x;
        softStart[s].v += c * softVK[s][j].slope.v;
      }
    const double dt = h * T.a[st][st];
    // Dissipation geometry: the last configuration the bodies occupied (x_n, then Q_{i−1}).
    const std::vector<RigidPose>& last = st == 0 ? stepStart : Q[st - 1];
    host.ApplyConstraints(step.time + cStage * h, &softX);
    PlaceKinematic(models, step.time + cStage * h, &poses);
    SoftStage& soft = buffers.softStage;
    host.MakeSoftStage(dt, step.time + cStage * h, softStart, softLast, &soft);
    host.SolveStage(dt, start, last, &poses, &soft, &softX, cStage * h, &rep);
    Q[st] = poses;
    for (size_t s = 0; s < ns; ++s) {
      if (const ActorKind* kind = host.VectorKind(s)) {
        kind->DirkStageSlope(softX[s], softStart[s], dt, &softVK[s][st]);
        continue;
      }
      SoftBodyState& vk = softVK[s][st].slope;
      vk.x = (softX[s] - softStart[s].x) / dt;
      vk.v = (vk.x - softStart[s].v) / dt;
    }
    softLast = softX;
    for (size_t i = 0; i < n; ++i) {
      RigidBodyState& vk = VK[st][i];
      vk.p = (poses[i].p - start[i].p) / dt;
      vk.v = (vk.p - start[i].v) / dt;
      if (models[i].kinematic) {  // its stage poses' slope, for the next stages' x⁰
        vk.R = (poses[i].R - start[i].R) / dt;
        vk.Rdot.setZero();
        torque[st][i].setZero();
        continue;
      }
      if (!models[i].dynamic) {
        vk.R.setZero();
        vk.Rdot.setZero();
        torque[st][i].setZero();
        continue;
      }
      const DirkRotationSlope rot = DirkStageRotation(models[i].secondMoment, poses[i].R,
                                                      start[i].R, start[i].Rdot, dt);
      torque[st][i] = rot.torque;
      vk.R = rot.V;
      vk.Rdot = (vk.R - start[i].Rdot) / dt;
    }
  }
  for (size_t i = 0; i < n; ++i) {
    if (!models[i].dynamic) continue;
    const RigidBodyState& s = step.states[i];
    RigidBodyState end = s;  // q_n + h Σ b_i V_i, v_n + h Σ b_i K_i
    Eigen::Vector3d spin = SpinMomentum(s.R, s.Rdot, models[i].secondMoment);
    for (int st = 0; st < T.stages; ++st) {
      end.p += h * T.b[st] * VK[st][i].p;
      end.R += h * T.b[st] * VK[st][i].R;
      end.v += h * T.b[st] * VK[st][i].v;
      end.Rdot += h * T.b[st] * VK[st][i].Rdot;
      spin += h * T.b[st] * torque[st][i];  // L̇ = τ, by the method's own weights
    }
    next[i].p = end.p;
    next[i].v = end.v;
    next[i].R = T.stifflyAccurate ? Q[T.stages - 1][i].R : NearestRotation(end.R);
    next[i].Rdot = SpinCorrectedRate(models[i].secondMoment, next[i].R, end.Rdot, spin);
  }
  std::vector<double>& hb = buffers.stageWeights;  // h b_i
  hb.resize(T.stages);
  for (int st = 0; st < T.stages; ++st) hb[st] = h * T.b[st];
  for (size_t s = 0; s < ns; ++s) {
    softNext[s] = step.softStates[s];
    for (int st = 0; st < T.stages; ++st) {
      softNext[s].x += hb[st] * softVK[s][st].slope.x;
      softNext[s].v += hb[st] * softVK[s][st].slope.v;
    }
    if (const ActorKind* kind = host.VectorKind(s))
      kind->DirkStepEnd(step.softStates[s], softLast[s], T.stifflyAccurate, softVK[s], hb,
                        &softNext[s]);
  }
  // Prescribed nodes sit exactly on their path at the step's end.
  std::vector<Eigen::VectorXd>& endX = buffers.softEnd;
  endX.resize(ns);
  for (size_t s = 0; s < ns; ++s) endX[s] = softNext[s].x;
  host.ApplyConstraints(step.time + h, &endX);
  for (size_t s = 0; s < ns; ++s) {
    softNext[s].x = endX[s];
    if (const ActorKind* kind = host.VectorKind(s)) EndPrescribed(*kind, step.softStates[s], step.time + h, &softNext[s]);
  }
  EndKinematic(models, step.time + h, &next);
}

void EndStep(double h, StepWork* work, StepState* step) {
  // History for the multistep methods: x_n, x_{n−1} with their times.
  if (step->history.size() < 2) {
    step->history.insert(step->history.begin(), step->states);
    step->softHistory.insert(step->softHistory.begin(), step->softStates);
    step->historyTimes.insert(step->historyTimes.begin(), step->time);
  } else {  // the oldest entry's storage takes the current state
    std::swap(step->history[0], step->history[1]);
    std::swap(step->softHistory[0], step->softHistory[1]);
    std::swap(step->historyTimes[0], step->historyTimes[1]);
    step->history[0] = step->states;
    step->softHistory[0] = step->softStates;
    step->historyTimes[0] = step->time;
  }
  step->states.swap(work->next);  // next keeps the former state's storage for the next step
  step->softStates.swap(work->softNext);  // both keep their storage
  step->time += h;
}

}  // namespace superdex
