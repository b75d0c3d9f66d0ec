#include "core/dynamics/time_stepper.h"

#include <algorithm>

#include "core/dynamics/integrators.h"

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

}  // namespace

void StepBdf(const StepState& step, double h, IntegrationMethod method, StageHost& host,
             StepBuffers* buffersOut, StepWork* work) {
  StepBuffers& buffers = *buffersOut;
  auto& [softX, softStepStart, softNext, rep] = *work;
  const size_t ns = step.softStates.size();  // soft actors and kinds
  // BDF-k with variable steps.
  const int k = std::min<int>(BdfSteps(method), static_cast<int>(step.softHistory.size()) + 1);
  std::vector<double>& times = buffers.bdfTimes;
  times.assign({step.time + h, step.time});
  for (int j = 0; j + 1 < k; ++j) times.push_back(step.historyTimes[j]);
  std::vector<double>& weights = buffers.bdfWeights;
  const double dt = BdfCoefficients(times, &weights);
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
  SoftStage& soft = buffers.softStage;
  host.MakeSoftStage(dt, step.time + h, softStart, softStepStart, &soft);
  host.SolveStage(dt, soft, &softX, h, &rep);
  for (size_t s = 0; s < ns; ++s) {
    softNext[s].x = softX[s];
    softNext[s].v = (softX[s] - softStart[s].x) / dt;
    if (const ActorKind* kind = host.VectorKind(s))
      EndPrescribed(*kind, step.softStates[s], step.time + h, &softNext[s]);
  }
}

void StepDirk(const StepState& step, double h, IntegrationMethod method, StageHost& host,
              StepBuffers* buffersOut, StepWork* work) {
  StepBuffers& buffers = *buffersOut;
  auto& [softX, softStepStart, softNext, rep] = *work;
  const size_t ns = step.softStates.size();  // soft actors and kinds
  // DIRK stages in material-point form; a kind on a manifold (a rigid body) applies the three
  // rotation rules of core/dynamics/integrators.h in its DIRK hooks.
  const DirkTableau& T = TableauOf(method);
  // Vector states: stage slopes (position, velocity) per actor and stage, as for p and v; the
  // kinds' from their own rule (ActorKind::DirkStageSlope).
  std::vector<std::vector<KindSlope>>& softVK = buffers.vectorSlopes;
  softVK.resize(ns);
  for (std::vector<KindSlope>& slopes : softVK) slopes.resize(T.stages);
  std::vector<Eigen::VectorXd>& softLast = buffers.softLast;
  softLast = softStepStart;
  for (int st = 0; st < T.stages; ++st) {
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
    // Dissipation geometry: the last configuration the actors occupied (x_n, then the last
    // stage's), softLast.
    host.ApplyConstraints(step.time + cStage * h, &softX);
    SoftStage& soft = buffers.softStage;
    host.MakeSoftStage(dt, step.time + cStage * h, softStart, softLast, &soft);
    host.SolveStage(dt, soft, &softX, cStage * h, &rep);
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
    if (const ActorKind* kind = host.VectorKind(s))
      EndPrescribed(*kind, step.softStates[s], step.time + h, &softNext[s]);
  }
}

void EndStep(double h, StepWork* work, StepState* step) {
  // History for the multistep methods: x_n, x_{n−1} with their times.
  if (step->softHistory.size() < 2) {
    step->softHistory.insert(step->softHistory.begin(), step->softStates);
    step->historyTimes.insert(step->historyTimes.begin(), step->time);
  } else {  // the oldest entry's storage takes the current state
    std::swap(step->softHistory[0], step->softHistory[1]);
    std::swap(step->historyTimes[0], step->historyTimes[1]);
    step->softHistory[0] = step->softStates;
    step->historyTimes[0] = step->time;
  }
  step->softStates.swap(work->softNext);  // softNext keeps the former state's storage
  step->time += h;
}

}  // namespace superdex
