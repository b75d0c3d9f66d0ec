// The stage policy: how one implicit stage is solved (SceneSettings). In order: a recording
// policy may supply the solution (core/dynamics/stage_recorder.h); a stage of kinds without
// an active contact sample at the minimizer of inertia and gravity takes that minimizer in closed
// form; otherwise the chosen solver runs, warm-started from the motion's prediction
// (core/dynamics/warm_start.h): projected Newton on potential stages, residual Newton on the
// others, which start from the explicit-normals minimizer after a slow stage and fall back to it
// when the residual solve fails. Owns the linear solvers and buffers kept from stage to stage.
#pragma once

#include <memory>
#include <vector>

#include "core/contact/contact_pipeline.h"
#include "core/dynamics/scene_settings.h"
#include "core/dynamics/scene_stage.h"
#include "core/dynamics/stage_recorder.h"
#include "optim/linear_solver.h"
#include "optim/newton_solver.h"

namespace superdex {

/// What the stage policy reads of the scene: the stage's dof count, the contact pipeline, and the
/// actors' vector states with their history (the warm start's prediction).
struct StageScene {
  int numDofs = 0;
  ContactPipeline* pipeline = nullptr;
  /// A kind refuses the warm start (ActorKind::Shortcuts): no warm start, no closed-form stage.
  bool coldStages = false;
  bool hasDissipation = false;
  const std::vector<VectorState>* vectorStates = nullptr;             ///< x_n, v_n
  const std::vector<std::vector<VectorState>>* vectorHistory = nullptr;
  const std::vector<double>* historyTimes = nullptr;
  double time = 0.0;  ///< t_n [s]
};

class StageDriver {
 public:
  /// Residual modes: stages that start from the explicit-normals minimizer after a slow one.
  static constexpr int kExplicitFirstStages = 20;
  /// Potential modes: a warm start after a stage of at most kLocalStageIterations Newton
  /// iterations (a step, a step, the passing test) is taken to lie in the local regime: its first
  /// iteration tries the exact Hessian (NewtonStart). The stage after a slower one keeps the
  /// projected first iteration: on the incline's settling steps the exact one cost iterations.
  static constexpr int kLocalStageIterations = 3;
  static constexpr int kNoLocalStage = 1 << 30;

  /// The policy's state carried from stage to stage (part of a scene's snapshot).
  struct State {
    int explicitFirstStages = 0;             ///< stages left that start explicit-first
    int explicitFirstRun = kExplicitFirstStages;  ///< the length of the next such run
    int lastPotentialIterations = kNoLocalStage;  ///< of the last warm-started converged stage
    bool lastStageInContact = false;         ///< the closed form is tried only where it was not
  };

  StageDriver() = default;
  // A copied scene gets its own solvers and buffers, and the policy's state.
  StageDriver(const StageDriver& other) : state_(other.state_) {}
  StageDriver& operator=(const StageDriver& other) {
    state_ = other.state_;
    return *this;
  }

  /// Solves one stage of step dt [s] over the actors of `stage` (their stage data: targets x̂,
  /// x⁰ and the last configuration x_n), from the initial guess in *x; on return it holds
  /// the stage's solution. `predictTime` > 0, the stage's time after t_n [s], allows the warm
  /// start.
  SolverStats Solve(const SceneSettings& settings, const StageScene& scene, double dt,
                    ContactStats* contact, const KindStage& stage,
                    std::vector<Eigen::VectorXd>* x, double predictTime,
                    StageRecorder* recorder);

  const State& GetState() const { return state_; }
  void SetState(const State& state) { state_ = state; }

 private:
  // The closed-form stage of SceneSettings::closedFormFreeStages: true, with the kinds'
  // configurations in *x set to their FreeStageMinimizer, and *stats, *contact filled, when
  // every kind has it and no contact sample is active there (penalty or dissipation); false
  // (nothing changed) otherwise.
  bool FreeStage(const StageScene& scene, const StageDissipation& dissipation, double dt,
                 const KindStage& stage, std::vector<Eigen::VectorXd>* x, SolverStats* stats,
                 ContactStats* contact);
  // The warm start's tangent step to the kinds' predicted solution into warmStep_, with their
  // steady flags, and its application to `problem`.
  void WarmStartStage(const SceneSettings& settings, const StageScene& scene, double dt,
                      const KindStage& stage, const std::vector<Eigen::VectorXd>& x,
                      double predictTime, SceneStageProblem* problem);
  // The residual modes' Newton solve with its explicit-normals start and fallback. Returns true
  // when the fallback's outcome stands (its contact statistics then in *contact, recorded).
  bool SolveResidual(const SceneSettings& settings, const StageInputs& inputs,
                     SceneStageProblem& problem, const StageDissipation& dissipation, double dt,
                     std::vector<Eigen::VectorXd>* x, ContactStats* contact,
                     StageRecorder* recorder, SolverStats* st);

  State state_;
  StageWorkspace workspace_;  // buffers reused from stage to stage
  // Linear solvers kept from stage to stage (their symbolic analyses).
  std::unique_ptr<SymmetricSolver> symmetric_ = std::make_unique<SymmetricSolver>();
  std::unique_ptr<UnsymmetricSolver> unsymmetric_ = std::make_unique<UnsymmetricSolver>();
  NewtonWorkspace newton_;  // the Newton solvers' buffers, from stage to stage
  // Scratch kept from stage to stage, so that a stage does not allocate once it has run.
  Eigen::VectorXd warmStep_, warmScratch_;
  std::vector<char> kindSteady_;  // per kind: moved steadily over the last two steps (ForceChange)
  std::vector<Eigen::VectorXd> freeX_;       // the kinds' free-stage configurations
  std::vector<Eigen::VectorXd> guess_, explicit_;  // SolveResidual's vector states
  Eigen::VectorXd kindPredicted_, kindDelta_;   // one kind's prediction and its tangent step
};

}  // namespace superdex
