#include "core/dynamics/stage_driver.h"

#include <algorithm>
#include <string>

#include "core/dynamics/warm_start.h"
#include "optim/ceres_stage_solver.h"
#include "optim/ipopt_stage_solver.h"
#include "optim/residual_newton.h"

namespace superdex {
namespace {

// Whether a stage's contact statistics show an active sample (penalty or dissipation).
bool InContact(const ContactStats& c) { return c.activeSamples > 0 || c.dissipativeSamples > 0; }

// Adds sign × the work counters and times of one solve to another's statistics.
void AddSolverWork(const SolverStats& from, SolverStats* to, int sign = 1) {
  to->iterations += sign * from.iterations;
  to->lineSearchSteps += sign * from.lineSearchSteps;
  to->regularizations += sign * from.regularizations;
  to->limitedSteps += sign * from.limitedSteps;
  to->assemblySeconds += sign * from.assemblySeconds;
  to->factorizationSeconds += sign * from.factorizationSeconds;
  to->lineSearchSeconds += sign * from.lineSearchSeconds;
  to->krylovIterations += sign * from.krylovIterations;
  to->krylovFallbacks += sign * from.krylovFallbacks;
}

// Replaces the work counters and times of *to by those of `from` (the rest of *to stays).
void CopySolverWork(const SolverStats& from, SolverStats* to) {
  const SolverStats own = *to;
  AddSolverWork(own, to, -1);
  AddSolverWork(from, to);
}

}  // namespace

SolverStats StageDriver::Solve(const SceneSettings& settings, const StageScene& scene, double dt,
                               ContactStats* contact, const KindStage& stage,
                               std::vector<Eigen::VectorXd>* x, double predictTime,
                               StageRecorder* recorder) {
  StageDissipation dissipation;
  dissipation.enabled = scene.hasDissipation;
  if (dissipation.enabled) {
    dissipation.mode = ModeOf(settings.eval);
    dissipation.fadeFriction = settings.eval.fadeFriction;
  }
  StageInputs inputs;
  inputs.numDofs = scene.numDofs;
  inputs.dt = dt;
  inputs.pipeline = scene.pipeline;
  inputs.stage = &stage;
  inputs.workspace = &workspace_;
  SolverStats st;
  if (recorder && recorder->Supplies()) {
    recorder->Supply(inputs, dissipation, x);
    st.status = StageStatus::Converged;
    return st;
  }
  const bool recording = recorder && recorder->Records();
  // Tried where the last stage had no active contact sample: where it had, contact usually
  // persists, and the check (a value-only contact evaluation) made a sliding box's run 16 %
  // longer for nothing. A stage that leaves contact is solved by Newton, the next one tried again.
  if (settings.closedFormFreeStages && settings.stageSolver == StageSolverKind::Newton &&
      !scene.coldStages && !recording && !state_.lastStageInContact &&
      FreeStage(scene, dissipation, dt, stage, x, &st, contact)) {
    state_.lastPotentialIterations = 0;  // a local stage: the next warm start may try the exact Hessian
    return st;
  }
  SceneStageProblem problem = inputs.Problem(dissipation, x);
  // The warm start (Newton only: Ipopt and Ceres check the cold stage). Kept cold: (1) scenes with
  // a kind that refuses it (ActorKind::Shortcuts: a soft body's, for its collider's piecewise
  // smooth stages). (2) Recorded steps (sensitivities, adjoint): their derivatives are evaluated
  // at the recorded solution, which a start reaches only to the solver's tolerance
  // (docs/solver.md).
  const bool warm = settings.stageSolver == StageSolverKind::Newton && predictTime > 0.0 &&
                    settings.warmStart && !scene.coldStages && !recording;
  if (warm) WarmStartStage(settings, scene, dt, stage, *x, predictTime, &problem);
  switch (settings.stageSolver) {
    case StageSolverKind::Newton:
      if (problem.IsPotential()) {
        NewtonStart hint;
        hint.exactHessian = warm && state_.lastPotentialIterations <= kLocalStageIterations;
        st = MinimizeNewton(problem, settings.solver, dt, symmetric_.get(), &newton_, hint);
        state_.lastPotentialIterations =
            warm && st.status == StageStatus::Converged ? st.iterations : kNoLocalStage;
        break;
      }
      if (SolveResidual(settings, inputs, problem, dissipation, dt, x, contact, recorder, &st))
        return st;
      break;
    case StageSolverKind::Ipopt:
      st = MinimizeIpopt(problem, IpoptStageParams());
      break;
    case StageSolverKind::Ceres:
      st = SolveCeres(problem, CeresStageParams());
      break;
  }
  *contact = problem.LastContactStats();
  state_.lastStageInContact = InContact(*contact);
  if (recording) recorder->Record(inputs, dissipation, *x);
  return st;
}

bool StageDriver::SolveResidual(const SceneSettings& settings, const StageInputs& inputs,
                                SceneStageProblem& problem, const StageDissipation& dissipation,
                                double dt, std::vector<Eigen::VectorXd>* x,
                                ContactStats* contact, StageRecorder* recorder,
                                SolverStats* result) {
  // Residual modes: Newton on r has only the merit ½‖r‖² to globalize with, which is badly scaled
  // where stiff contacts and friction meet (landing and settling contacts: ~20 iterations with many
  // backtracks on a sphere pile). A stage that starts from the explicit-normals minimizer (a
  // potential, globalized by projected Newton) needs only the local residual iterations. That
  // costs about one iteration more on easy stages, so it is switched on whenever a residual-first
  // stage takes more than kResidualFirstIterations iterations, for kExplicitFirstStages stages,
  // then the residual-first start is tried again; each further such probe that fails doubles the
  // run (up to kMaxExplicitFirstStages), one that succeeds resets it. Either start converges to
  // the same residual root; the start needs no more accuracy than the distance between the two
  // roots, so that its minimization stops at a gradient kStartRelativeGradient of its initial
  // one. If the residual solve fails, the explicit-normals minimizer, continued to full accuracy,
  // is the fallback (docs/solver.md).
  constexpr int kResidualFirstIterations = 8;
  constexpr int kMaxExplicitFirstStages = 320;
  constexpr double kStartRelativeGradient = 1e-2;
  SolverStats& st = *result;
  std::vector<Eigen::VectorXd>& guess = guess_;
  guess = *x;
  StageDissipation potential = dissipation;
  potential.mode = DissipationMode::ExplicitNormals;
  ContactStats explicitContact;
  auto minimizeExplicit = [&](const NonlinearSolverParams& params) {  // from *x
    SceneStageProblem stage = inputs.Problem(potential, x);
    const SolverStats out = MinimizeNewton(stage, params, dt, symmetric_.get(), &newton_);
    explicitContact = stage.LastContactStats();
    return out;
  };
  const bool explicitFirst = state_.explicitFirstStages > 0;
  if (explicitFirst) --state_.explicitFirstStages;
  SolverStats first;  // the explicit-normals solve that gave the start (explicitFirst)
  bool haveExplicit = false;
  std::vector<Eigen::VectorXd>& explicitX = explicit_;
  if (explicitFirst) {
    NonlinearSolverParams start = settings.solver;
    start.relativeTolerance = std::max(start.relativeTolerance, kStartRelativeGradient);
    first = minimizeExplicit(start);
    haveExplicit = first.status == StageStatus::Converged;
    if (haveExplicit)
      explicitX = *x;
    else
      *x = guess;
  }
  st = SolveResidualNewton(problem, settings.solver, dt, unsymmetric_.get(), &newton_);
  if (!explicitFirst) {
    if (st.status != StageStatus::Converged || st.iterations > kResidualFirstIterations) {
      state_.explicitFirstStages = state_.explicitFirstRun;
      state_.explicitFirstRun = std::min(2 * state_.explicitFirstRun, kMaxExplicitFirstStages);
    } else {
      state_.explicitFirstRun = kExplicitFirstStages;
    }
  }
  AddSolverWork(first, &st);
  if (st.status == StageStatus::Converged) return false;
  // Fallback: the explicit-normals minimizer to full accuracy (from the start it gave, or from the
  // stage's guess); the report carries its outcome and the work of every solve of the stage.
  SolverStats work = st;
  *x = haveExplicit ? explicitX : guess;
  const SolverStats outcome = minimizeExplicit(settings.solver);
  AddSolverWork(outcome, &work);
  const std::string why = st.Message();
  st = outcome;
  CopySolverWork(work, &st);
  st.message = "residual solve failed (" + why + "); stage re-solved with explicit normals" +
               (outcome.status == StageStatus::Converged ? "" : ": " + outcome.Message());
  st.fallback = true;
  *contact = explicitContact;
  state_.lastStageInContact = InContact(*contact);
  if (recorder && recorder->Records()) recorder->Record(inputs, potential, *x);
  return true;
}

void StageDriver::WarmStartStage(const SceneSettings& settings, const StageScene& scene,
                                 double dt, const KindStage& stage,
                                 const std::vector<Eigen::VectorXd>& x, double predictTime,
                                 SceneStageProblem* problem) {
  const std::vector<double>& historyTimes = *scene.historyTimes;
  const bool one = !historyTimes.empty();
  const bool two = historyTimes.size() >= 2;
  const double hPrevious = one ? scene.time - historyTimes[0] : 0.0;
  const double hBefore = two ? historyTimes[0] - historyTimes[1] : 0.0;
  warmStep_.setZero(scene.numDofs);
  const KindStage& kinds = stage;
  const std::vector<VectorState>& states = *scene.vectorStates;
  const std::vector<std::vector<VectorState>>& history = *scene.vectorHistory;
  const double bound = SteadyBound(settings.gravity);
  kindSteady_.assign(kinds.Size(), 1);
  for (size_t k = 0; k < kinds.Size(); ++k) {
    const ActorKind& kind = *(*kinds.kinds)[k];
    const VectorState* previous = one && history.size() >= 1 ? &history[0][k] : nullptr;
    kind.PredictStage(states[k], previous, hPrevious, predictTime, kinds.q0[k], dt,
                      &kindPredicted_);
    kind.TangentBetween(x[k], kindPredicted_, &kindDelta_);
    const std::vector<int>& dof = kinds.stageDof[k];
    for (size_t j = 0; j < dof.size(); ++j)
      if (dof[j] >= 0) warmStep_[dof[j]] = kindDelta_[j];
    if (two && history.size() >= 2)
      kindSteady_[k] = kind.ForceChange(states[k], history[0][k], hPrevious, history[1][k],
                                        hBefore) <= bound;
  }
  WarmStart(*problem, &warmStep_, &warmScratch_, settings.solver.stepTolerance * dt,
            kinds.stageDof, kindSteady_);
}

bool StageDriver::FreeStage(const StageScene& scene, const StageDissipation& dissipation,
                            double dt, const KindStage& stage, std::vector<Eigen::VectorXd>* x,
                            SolverStats* stats, ContactStats* contact) {
  const KindStage& kinds = stage;
  freeX_ = *x;
  for (size_t k = 0; k < kinds.Size(); ++k) {
    Eigen::VectorXd& q = freeX_[k];
    if (!(*kinds.kinds)[k]->FreeStageMinimizer(kinds.data[k], &q) || !q.allFinite()) return false;
  }
  // The contact terms as SceneStageProblem evaluates them there (value only): each pair adds its
  // value, gradient and residual only through samples it counts active.
  const DissipationContext context = ContextOf(dissipation, dt);
  const KindView view = KindViewOf(stage, freeX_);
  ContactStats found;
  scene.pipeline->Evaluate(0, PsdProjection::None, nullptr, nullptr, nullptr, &found,
                           dissipation.enabled ? &context : nullptr, nullptr,
                           view.q ? &view : nullptr);
  if (InContact(found)) return false;
  x->swap(freeX_);
  *contact = found;
  *stats = SolverStats();
  stats->status = StageStatus::Converged;
  stats->passed.what = "closed-form free stage (no active contact sample)";
  stats->closedForm = true;
  return true;
}

}  // namespace superdex
