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
  auto& [x, stepStart, next, rep] = *work;
  const size_t na = step.vectorStates.size();
  // BDF-k with variable steps.
  const int k = std::min<int>(BdfSteps(method), static_cast<int>(step.vectorHistory.size()) + 1);
  std::vector<double>& times = buffers.bdfTimes;
  times.assign({step.time + h, step.time});
  for (int j = 0; j + 1 < k; ++j) times.push_back(step.historyTimes[j]);
  std::vector<double>& weights = buffers.bdfWeights;
  const double dt = BdfCoefficients(times, &weights);
  std::vector<VectorState>& start = buffers.start;
  start.resize(na);
  for (size_t a = 0; a < na; ++a) {
    start[a].x = weights[0] * step.vectorStates[a].x;
    start[a].v = weights[0] * step.vectorStates[a].v;
    for (int j = 1; j < k; ++j) {
      start[a].x += weights[j] * step.vectorHistory[j - 1][a].x;
      start[a].v += weights[j] * step.vectorHistory[j - 1][a].v;
    }
  }
  host.ApplyConstraints(step.time + h, &x);
  KindStage& stage = buffers.stage;
  host.MakeStage(dt, step.time + h, start, stepStart, &stage);
  host.SolveStage(dt, stage, &x, h, &rep);
  for (size_t a = 0; a < na; ++a) {
    next[a].x = x[a];
    next[a].v = (x[a] - start[a].x) / dt;
    EndPrescribed(host.KindOf(a), step.vectorStates[a], step.time + h, &next[a]);
  }
}

void StepDirk(const StepState& step, double h, IntegrationMethod method, StageHost& host,
              StepBuffers* buffersOut, StepWork* work) {
  StepBuffers& buffers = *buffersOut;
  auto& [x, stepStart, next, rep] = *work;
  const size_t na = step.vectorStates.size();
  // DIRK stages in material-point form; a kind on a manifold (a rigid body) applies the three
  // rotation rules of core/dynamics/integrators.h in its DIRK hooks.
  const DirkTableau& T = TableauOf(method);
  // Stage slopes (position, velocity) per actor and stage, each kind's from its own rule
  // (ActorKind::DirkStageSlope).
  std::vector<std::vector<KindSlope>>& slopes = buffers.vectorSlopes;
  slopes.resize(na);
  for (std::vector<KindSlope>& actorSlopes : slopes) actorSlopes.resize(T.stages);
  std::vector<Eigen::VectorXd>& last = buffers.last;
  last = stepStart;
  for (int st = 0; st < T.stages; ++st) {
    std::vector<VectorState>& start = buffers.start;
    start = step.vectorStates;
    double cStage = 0.0;  // the stage's abscissa c_i = Σ_j a_ij
    for (int j = 0; j <= st; ++j) cStage += T.a[st][j];
    for (size_t a = 0; a < na; ++a)
      for (int j = 0; j < st; ++j) {
        const double c = h * T.a[st][j];
        start[a].x += c * slopes[a][j].slope.x;
        start[a].v += c * slopes[a][j].slope.v;
      }
    const double dt = h * T.a[st][st];
    // Dissipation geometry: the last configuration the actors occupied (x_n, then the last
    // stage's).
    host.ApplyConstraints(step.time + cStage * h, &x);
    KindStage& stage = buffers.stage;
    host.MakeStage(dt, step.time + cStage * h, start, last, &stage);
    host.SolveStage(dt, stage, &x, cStage * h, &rep);
    for (size_t a = 0; a < na; ++a)
      host.KindOf(a).DirkStageSlope(x[a], start[a], dt, &slopes[a][st]);
    last = x;
  }
  std::vector<double>& hb = buffers.stageWeights;  // h b_i
  hb.resize(T.stages);
  for (int st = 0; st < T.stages; ++st) hb[st] = h * T.b[st];
  for (size_t a = 0; a < na; ++a) {
    next[a] = step.vectorStates[a];
    for (int st = 0; st < T.stages; ++st) {
      next[a].x += hb[st] * slopes[a][st].slope.x;
      next[a].v += hb[st] * slopes[a][st].slope.v;
    }
    host.KindOf(a).DirkStepEnd(step.vectorStates[a], last[a], T.stifflyAccurate, slopes[a], hb,
                               &next[a]);
  }
  // Prescribed dofs sit exactly on their path at the step's end.
  std::vector<Eigen::VectorXd>& endX = buffers.end;
  endX.resize(na);
  for (size_t a = 0; a < na; ++a) endX[a] = next[a].x;
  host.ApplyConstraints(step.time + h, &endX);
  for (size_t a = 0; a < na; ++a) {
    next[a].x = endX[a];
    EndPrescribed(host.KindOf(a), step.vectorStates[a], step.time + h, &next[a]);
  }
}

void EndStep(double h, StepWork* work, StepState* step) {
  // History for the multistep methods: x_n, x_{n−1} with their times.
  if (step->vectorHistory.size() < 2) {
    step->vectorHistory.insert(step->vectorHistory.begin(), step->vectorStates);
    step->historyTimes.insert(step->historyTimes.begin(), step->time);
  } else {  // the current state moves to the front; the oldest entry's storage goes to `next`
    std::swap(step->vectorHistory[0], step->vectorHistory[1]);
    std::swap(step->historyTimes[0], step->historyTimes[1]);
    step->vectorHistory[0].swap(step->vectorStates);
    step->historyTimes[0] = step->time;
  }
  step->vectorStates.swap(work->next);  // next keeps storage to be written at the next step
  step->time += h;
}

}  // namespace superdex
