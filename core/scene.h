// The scene: actors, settings, and time stepping. Kept thin: actor data, the contact pipeline, the
// stage problem and the integrator formulas live in their own files.
#pragma once

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/contact/contact_pipeline.h"
#include "core/model/enums.h"
#include "core/model/error.h"
#include "core/model/eval_params.h"
#include "core/model/rigid_body.h"
#include "core/dynamics/scene_stage.h"
#include "core/model/soft_body.h"
#include "optim/linear_solver.h"
#include "optim/newton_solver.h"

namespace superdex {

struct ActorHandle {
  int index = -1;
  bool IsValid() const { return index >= 0; }
};

/// Which solver runs each implicit stage. Newton is the production solver (projected Newton for
/// potential stages, residual Newton otherwise); Ipopt (potential stages only) and Ceres (every
/// stage) are independent checks for small scenes (dense, at most 600 degrees of freedom).
enum class StageSolverKind { Newton, Ipopt, Ceres };
const char* ToString(StageSolverKind kind);
/// "newton", "ipopt" or "ceres" (also the CamelCase names); false for anything else.
bool ParseStageSolver(const std::string& name, StageSolverKind* kind);

struct SceneSettings {
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81);  ///< [m/s²]
  IntegrationMethod integrator = IntegrationMethod::BDF2;
  NonlinearSolverParams solver;
  StageSolverKind stageSolver = StageSolverKind::Newton;
  ExperimentalEvalParams eval;
  /// Newton stage solves of rigid bodies start from the motion's prediction (the last step's
  /// acceleration continued, each body's move limited by the contact step limit;
  /// core/dynamics/warm_start.h). Changes the path to each stage's solution, not the solution or the
  /// convergence tests.
  bool warmStart = true;
  /// A Newton stage of rigid bodies whose contact terms all vanish at the minimizer of inertia and
  /// gravity (no contact sample active there, penalty or dissipation) is solved in closed form,
  /// per body (MinimizeRigidInertia, energies/rigid_inertia.h), with 0 Newton iterations: free
  /// flight pays no Newton iteration. That point is the stage's exact global minimizer (the
  /// contact energies are >= 0 and vanish there) and the root of the residual modes' equations
  /// (their contact terms vanish there too); Newton reaches the same point to its tolerance.
  /// Not for scenes with soft actors, nor for the Ipopt and Ceres checks, nor for recorded steps.
  bool closedFormFreeStages = true;
};
/// "" when valid, else a message naming the field.
std::string Validate(const SceneSettings& settings, const std::string& prefix = "");

/// What one step did.
struct StepReport {
  double time = 0.0;           ///< simulated time at the end of the step [s]
  double dt = 0.0;             ///< [s]
  int stages = 0;
  int newtonIterations = 0;    ///< summed over stages
  int lineSearchSteps = 0;
  StageStatus status = StageStatus::Converged;  ///< worst over the stages
  std::string message;         ///< the solver's message for a non-converged stage
  int freeStages = 0;          ///< stages solved in closed form (no active contact sample;
                               ///< SceneSettings::closedFormFreeStages)
  int fallbacks = 0;           ///< stages re-solved with explicit normals after a failed
                               ///< residual solve (see Scene::SolveStage)
  std::string fallbackMessage; ///< the first such stage's message
  double finalGradientNorm = 0.0;  ///< largest over the stages
  ContactStats contact;        ///< at the end of the step (penalty only)
  /// The stages' contact evaluations at their last iterates (with dissipation): largest
  /// ‖T_C‖/(μ λ̂_n) and most dissipative samples over the stages; the dissipation Δt_i Σ w R [J]
  /// summed over the stages.
  double maxCoulombRatio = 0.0;
  int dissipativeSamples = 0;
  double dissipation = 0.0;
  double wallSeconds = 0.0;
  double assemblySeconds = 0.0;       ///< stage solvers: energy/residual and derivative assembly
  double factorizationSeconds = 0.0;  ///< stage solvers: linear solves (Cholesky / LU)
  double lineSearchSeconds = 0.0;     ///< stage solvers: line-search evaluations
  int krylovIterations = 0;           ///< iterative linear solves (LinearSolverKind): iterations
  int krylovFallbacks = 0;            ///< iterative linear solves that fell back to the direct one
  double minDetF = INFINITY;          ///< smallest det F over the soft tets at the end of the step
                                      ///< (<= 0: an inverted tet); +∞ without soft actors
};

/// Energies of the current state [J].
struct EnergyReport {
  double kinetic = 0.0;
  double gravity = 0.0;  ///< Σ −m g·p
  double contact = 0.0;  ///< penalty energy Σ Π_{A,B}
  double elastic = 0.0;  ///< soft actors: Σ V Ψ(F)
  double Total() const { return kinetic + gravity + contact + elastic; }
};

/// One step's stages as core/sensitivity/sensitivity.h needs them: each stage's accepted solution, the
/// dissipation mode it was solved in, the stage Jacobian ∂r/∂δ there and its LU factors.
struct StageTapeEntry {
  std::vector<RigidPose> poses;
  std::vector<Eigen::VectorXd> softX;
  DissipationMode mode = DissipationMode::ExplicitNormals;
  Eigen::SparseMatrix<double> jacobian;
  std::unique_ptr<UnsymmetricSolver> lu = std::make_unique<UnsymmetricSolver>();
  bool factored = false;
  /// Inject mode (core/sensitivity/step_linearization.h): the stage's solution is taken as poses ⊕ inject
  /// (the stage's chart, δ = [δp, δθ] per dynamic body, δx per free soft node; empty = 0), and
  /// the stage residual there, with the inputs of the perturbed step, is kept in `residual`.
  Eigen::VectorXd inject, residual;
  /// The dissipative samples' slips at the solution (core/contact/slip_tape.h): the replays and injected
  /// runs evaluate the friction force about them.
  StageSlips slips;
};
struct StepTape {
  std::vector<StageTapeEntry> stages;  ///< kept from step to step (symbolic analyses reused)
  int used = 0;                        ///< stages of the last recorded step
};

class Scene {
 public:
  explicit Scene(const SceneSettings& settings = SceneSettings());

  /// Adds a rigid actor; returns an invalid handle and fills *error on bad input. A valid
  /// `parent` nests the actor under it (for IncludeNestedActors::Yes).
  ActorHandle AddRigidActor(const RigidActorDesc& desc, Error* error,
                            ActorHandle parent = ActorHandle());
  /// Adds a soft (tet FEM) actor; returns an invalid handle and fills *error on bad input.
  ActorHandle AddSoftActor(const SoftActorDesc& desc, Error* error,
                           ActorHandle parent = ActorHandle());

  // --- Contact filtering (spec: "Contact Filtering"; core/contact/contact_filter.h). Each returns false
  // and fills *error for an invalid handle.
  /// Actor::SetContactLayer: an arbitrary string.
  bool SetContactLayer(ActorHandle actor, const std::string& layer, Error* error);
  const std::string& ContactLayer(ActorHandle actor) const;
  /// The ordered interaction layerA (colliding) against layerB (collider); not the reverse.
  bool EnableLayerContactAsymmetric(const std::string& layerA, const std::string& layerB,
                                    bool enable, Error* error);
  bool EnableLayerContactSymmetric(const std::string& layerA, const std::string& layerB,
                                   bool enable, Error* error);
  /// The actor-pair gate for A colliding against B, over the cross-product of the resolved sets.
  bool EnableActorContactAsymmetric(ActorHandle a, ActorHandle b, bool enable,
                                    IncludeNestedActors includeNestedActors, Error* error);
  bool EnableActorContactSymmetric(ActorHandle a, ActorHandle b, bool enable,
                                   IncludeNestedActors includeNestedActors, Error* error);
  /// The automatic disabling of adjacent links / skinned parts: the same actor gate, so that a
  /// later setting overrides it.
  void DisableAdjacentContact(ActorHandle a, ActorHandle b);
  /// Whether the ordered pair (a colliding, b collider) passes both gates.
  bool ContactAllowed(ActorHandle a, ActorHandle b) const;

  /// Advances by dt [s] (> 0; may differ from step to step) with the scene's integrator.
  /// Returns false (and fills *error) only for invalid input; a stage that did not converge is
  /// reported in *report (status Stopped or Diverged), never silently accepted.
  bool Step(double dt, StepReport* report, Error* error);

  double Time() const { return time_; }
  /// Every actor, rigid and soft; handles index this range in the order of creation.
  int NumActors() const { return static_cast<int>(actors_.size()); }
  bool IsSoft(ActorHandle a) const { return actors_[a.index].soft; }
  /// Rigid actors (a must be one).
  const RigidBodyModel& Model(ActorHandle a) const { return models_[actors_[a.index].local]; }
  const RigidBodyState& State(ActorHandle a) const { return states_[actors_[a.index].local]; }
  /// Soft actors (a must be one).
  const SoftBodyModel& SoftModel(ActorHandle a) const {
    return softModels_[actors_[a.index].local];
  }
  const SoftBodyState& SoftState(ActorHandle a) const {
    return softStates_[actors_[a.index].local];
  }
  /// The rigid actors' models and states, in creation order among rigid actors; RigidActors()[i]
  /// is the handle of Models()[i].
  const std::vector<RigidBodyModel>& Models() const { return models_; }
  const std::vector<RigidBodyState>& States() const { return states_; }
  std::vector<ActorHandle> RigidActors() const;
  /// Centre of mass [m] and its velocity [m/s] of any actor (soft: of the lumped node masses).
  Eigen::Vector3d CenterOfMass(ActorHandle a) const;
  Eigen::Vector3d CenterOfMassVelocity(ActorHandle a) const;
  std::vector<ActorHandle> SoftActors() const;
  /// Per boundary face of soft actor a, the contact traction on it averaged over the face's
  /// reference area, Σ_q w_q t_q / A_f [Pa] (world frame; zero for faces out of contact), from the
  /// active penalty samples at the current state.
  bool SoftFaceTractions(ActorHandle a, std::vector<Eigen::Vector3d>* tractions, Error* error);
  const SceneSettings& Settings() const { return settings_; }
  /// Changes the stage solver. Ipopt is refused for a scene whose stages are not a potential
  /// (dissipation without explicit normals), with the reason.
  bool SetStageSolver(StageSolverKind kind, Error* error);
  /// Changes the integrator (validated); the next step starts without BDF history.
  bool SetIntegrator(IntegrationMethod method, Error* error);
  /// Replaces the nonlinear stage solver's settings (validated, field names with "solver.").
  bool SetSolverParams(const NonlinearSolverParams& params, Error* error);
  /// Replaces the state of an actor (e.g. to restart from a recorded state); clears BDF history.
  bool SetState(ActorHandle a, const RigidBodyState& state, Error* error);
  /// Replaces a soft actor's state (x, v: 3 entries per node); clears BDF history.
  bool SetSoftState(ActorHandle a, const SoftBodyState& state, Error* error);
  /// Replaces an actor's contact parameters (validated, field names with "contact.").
  bool SetContactParams(ActorHandle a, const ContactParams& params, Error* error);
  const ContactParams& GetContactParams(ActorHandle a) const;
  /// Replaces a soft actor's Young's modulus and density (validated); Lamé parameters and the
  /// lumped masses follow. Poisson's ratio and stiffness damping are kept.
  bool SetSoftMaterial(ActorHandle a, double youngsModulus, double density, Error* error);
  /// Whether the scene holds multistep history (any step since the last state change).
  bool HasStepHistory() const { return !history_.empty(); }
  /// The smallest V_f over the actors [m/s].
  double MinFrictionFalloffVel() const;
  /// The actor of that name (invalid handle if none).
  ActorHandle FindActor(const std::string& name) const;
  const std::string& ActorName(ActorHandle a) const;

  // --- The dynamic state as one vector (core/sensitivity/sensitivity.h differentiates the step map on it).
  // Per dynamic rigid actor p, R (column-major), v, Ṙ (24 entries), per soft actor x then v
  // (6 per node), in creation order; then, for the multistep methods, the same blocks for each
  // state of the history a step reads (zeros where the history is not filled yet).
  int StateSize();
  /// First entry of actor a's block in the current state (−1 for a static actor).
  int StateOffset(ActorHandle a);
  Eigen::VectorXd PackState();
  /// 1 at the velocity entries (v, Ṙ, soft v) of PackState's layout, 0 at the positions.
  Eigen::VectorXd PackedVelocityMask();
  /// Writes a vector of PackState's layout back (history blocks only where history exists).
  void UnpackState(const Eigen::VectorXd& s);

  EnergyReport Energies();
  Eigen::Vector3d TotalLinearMomentum() const;
  Eigen::Vector3d TotalAngularMomentum() const;
  /// Contact statistics at the current state (one value-only pass of the pipeline).
  ContactStats ContactState();
  /// True when some actor has a nonzero friction or damping coefficient (stages then carry
  /// Δt_i R in the mode ExperimentalEvalParams selects).
  bool HasDissipation() const;
  /// Every active contact sample at the current state, with its normal traction (world frame).
  std::vector<ContactSampleRecord> ContactSamples();
  /// One-time notes about the scene (e.g. a collider type not supported yet).
  std::vector<std::string> Notices() const;

 private:
  // Solves one stage: minimizes the incremental potential with step dt, inertial target
  // x̂ = x⁰ + dt v⁰ taken from `start` (x⁰, v⁰ in material-point form), from the initial guess in
  // *poses; on return *poses holds the stage solution.
  // `last` is the last configuration the bodies occupied (the dissipation geometry).
  // `predictTime` > 0 is the stage's time after t_n [s]: the Newton solvers then start from the
  // predicted poses, limited by the contact step limit (core/dynamics/warm_start.h).
  SolverStats SolveStage(double dt, const std::vector<RigidBodyState>& start,
                         const std::vector<RigidPose>& last, std::vector<RigidPose>* poses,
                         ContactStats* contact, const SoftStage* soft = nullptr,
                         std::vector<Eigen::VectorXd>* softX = nullptr, double predictTime = 0.0);
  // The closed-form stage of SceneSettings::closedFormFreeStages: true, with *poses set to every
  // dynamic body's MinimizeRigidInertia and *stats, *contact filled, when no contact sample is
  // active there (penalty or dissipation); false (nothing changed) otherwise.
  bool FreeStage(const StageTargets& targets, const StageDissipation& dissipation,
                 std::vector<RigidPose>* poses, SolverStats* stats, ContactStats* contact);
  friend class ForwardSensitivity;
  friend class StepLinearizer;
  friend class AdjointSensitivity;
  // Differentiation support: Record keeps each stage's solution and factored Jacobian in *tape_;
  // Replay replaces each stage solve by one Newton step from the recorded solution with the
  // recorded factors, r evaluated with the current (perturbed) inputs; Inject takes each stage's
  // solution as the recorded one moved by the entry's `inject` and keeps the residual there.
  enum class TapeMode { Off, Record, Replay, Inject };
  TapeMode tapeMode_ = TapeMode::Off;
  StepTape* tape_ = nullptr;
  int tapeStage_ = 0;
  // Steps by dt recording every stage in *tape (TapeMode::Record). False, with the reason, for
  // invalid input, a stage that did not converge or a singular stage Jacobian at the solution:
  // the derivative of such a step is not defined. The step's report in *report either way.
  bool StepAndRecord(double dt, StepTape* tape, StepReport* report, Error* error);
  void RecordStage(const StageTargets& targets, const StageDissipation& dissipation,
                   const std::vector<RigidPose>& poses, const SoftStage* soft,
                   std::vector<Eigen::VectorXd>* softX);
  // Replay or Inject in place of a stage solve.
  void TapedStage(const StageTargets& targets, const StageDissipation& dissipation,
                  std::vector<RigidPose>* poses, const SoftStage* soft,
                  std::vector<Eigen::VectorXd>* softX);
  struct Snapshot {
    std::vector<RigidBodyState> states;
    std::vector<SoftBodyState> softStates;
    std::vector<std::vector<RigidBodyState>> history;
    std::vector<std::vector<SoftBodyState>> softHistory;
    std::vector<double> historyTimes;
    double time = 0.0;
    int explicitFirstStages = 0;
    int explicitFirstRun = kExplicitFirstStages;
    int lastPotentialIterations = kNoLocalStage;
    bool lastStageInContact = false;
  };
  Snapshot Save() const {
    return {states_, softStates_, history_, softHistory_, historyTimes_, time_,
            explicitFirstStages_, explicitFirstRun_, lastPotentialIterations_,
            lastStageInContact_};
  }
  void Restore(const Snapshot& s) {
    states_ = s.states;
    softStates_ = s.softStates;
    history_ = s.history;
    softHistory_ = s.softHistory;
    historyTimes_ = s.historyTimes;
    time_ = s.time;
    explicitFirstStages_ = s.explicitFirstStages;
    explicitFirstRun_ = s.explicitFirstRun;
    lastPotentialIterations_ = s.lastPotentialIterations;
    lastStageInContact_ = s.lastStageInContact;
  }
  int HistoryBlocks() const;
  // The packed-state layout: calls visit(block, offset, actor ref, actor index) for every dynamic
  // actor in each of the first `blocks` blocks (block 0: the current state, b >= 1: history_[b−1]).
  template <typename Visit>
  void VisitStateLayout(int blocks, Visit&& visit) const;
  // 1 + the history blocks that hold a state.
  int FilledStateBlocks() const;

  void ClearHistory() {
    history_.clear();
    softHistory_.clear();
    historyTimes_.clear();
  }
  void Prepare();
  std::vector<RigidPose> CurrentPoses() const;
  void CurrentPoses(std::vector<RigidPose>* poses) const;
  std::vector<Eigen::VectorXd> CurrentSoftPositions() const;
  struct ActorRef {
    bool soft = false;
    int local = 0;  ///< index into models_/states_ or softModels_/softStates_
  };
  // Soft stage data: targets from the stage start, geometry from the last configuration.
  SoftStage MakeSoftStage(double dt, const std::vector<SoftBodyState>& start,
                          const std::vector<Eigen::VectorXd>& last) const;
  // Prescribed node positions at time t written into x.
  void ApplyConstraints(double t, std::vector<Eigen::VectorXd>* x) const;
  double MinDetF() const;

  SceneSettings settings_;
  std::string settingsError_;  ///< Validate(settings_), kept with every change of settings_
  std::vector<RigidBodyModel> models_;
  /// SamplesHash → indices into models_ of the distinct sample sets so far (ShareSamples).
  std::unordered_multimap<std::size_t, int> sampleSets_;
  std::vector<RigidBodyState> states_;
  std::vector<SoftBodyModel> softModels_;
  std::vector<SoftBodyState> softStates_;
  std::vector<Eigen::VectorXd> softInitial_;  // positions at creation (node constraints)
  std::vector<ActorRef> actors_;
  std::vector<int> softDofOffset_;
  std::vector<std::vector<SoftBodyState>> softHistory_;
  // Multistep history: history_[j] = state at step n−1−j, at time historyTimes_[j] (at most 2).
  std::vector<std::vector<RigidBodyState>> history_;
  std::vector<double> historyTimes_;
  double time_ = 0.0;
  // Storage of Step and SolveStage kept from step to step, so that a rigid step does not allocate
  // once it has run (scratch: every use overwrites it first).
  struct StepBuffers {
    std::vector<RigidPose> poses, stepStart, predicted, guess, reportPoses;
    std::vector<RigidBodyState> next, start;
    std::vector<std::vector<RigidBodyState>> stageSlopes;  // a DIRK step's V_i, K_i per body
    std::vector<std::vector<Eigen::Vector3d>> stageTorques;
    std::vector<std::vector<RigidPose>> stagePoses;       // Q_i
    std::vector<double> bdfTimes, bdfWeights;
    StageTargets targets;
    Eigen::VectorXd warmStep, warmScratch;
    std::vector<char> steady;  // per body: moved steadily over the last two steps (SteadyMotion)
    std::vector<RigidPose> free;  // the closed-form free stage's poses (FreeStage)
  };
  StepBuffers buffers_;
  // Whether the pipeline is configured for the current actors; a copied scene configures its own
  // (the pipeline holds pointers to the scene's models).
  struct ResetOnCopy {
    bool value = false;
    ResetOnCopy() = default;
    ResetOnCopy(const ResetOnCopy&) {}
    ResetOnCopy& operator=(const ResetOnCopy&) {
      value = false;
      return *this;
    }
    ResetOnCopy& operator=(bool v) {
      value = v;
      return *this;
    }
    operator bool() const { return value; }
  };
  ResetOnCopy prepared_;
  bool hasDissipation_ = false;  // HasDissipation(), cached by Prepare
  // Residual modes: stages left that start from the explicit-normals minimizer, and the length of
  // the next such run (SolveStage).
  static constexpr int kExplicitFirstStages = 20;
  int explicitFirstStages_ = 0;
  int explicitFirstRun_ = kExplicitFirstStages;
  // Potential modes: Newton iterations of the last warm-started stage that converged (else
  // kNoLocalStage). A warm start after a stage of at most kLocalStageIterations (a step, a step,
  // the passing test) is taken to lie in the local regime: its first iteration tries the exact
  // Hessian (NewtonStart). The stage after a slower one keeps the projected first iteration: on
  // the incline's settling steps the exact one cost iterations (8 instead of 6).
  static constexpr int kLocalStageIterations = 3;
  static constexpr int kNoLocalStage = 1 << 30;
  int lastPotentialIterations_ = kNoLocalStage;
  // Whether the last stage solved ended with an active contact sample (the closed-form free
  // stage is tried only where it did not).
  bool lastStageInContact_ = false;
  std::vector<int> dofOffset_;
  int numDofs_ = 0;
  ContactPipeline pipeline_;
  ContactFilter filter_;
  StageWorkspace workspace_;  // buffers reused from stage to stage
  // Linear solvers kept from stage to stage (their symbolic analyses); a copied scene gets its
  // own.
  struct Solvers {
    std::unique_ptr<SymmetricSolver> symmetric = std::make_unique<SymmetricSolver>();
    std::unique_ptr<UnsymmetricSolver> unsymmetric = std::make_unique<UnsymmetricSolver>();
    NewtonWorkspace newton;  ///< the Newton solvers' buffers, from stage to stage
    Solvers() = default;
    Solvers(const Solvers&) : Solvers() {}
    Solvers& operator=(const Solvers&) { return *this; }
  };
  Solvers solvers_;
};

}  // namespace superdex
