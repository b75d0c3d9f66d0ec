// The scene, the front door: owns the actors, their states, the contact filter and pipeline; a
// step is the time stepper's (core/dynamics/time_stepper.h), whose stages the scene solves with
// the stage policy (core/dynamics/stage_driver.h).
#pragma once

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/contact/contact_filter.h"
#include "core/contact/contact_pipeline.h"
#include "core/dynamics/scene_settings.h"
#include "core/dynamics/scene_stage.h"
#include "core/dynamics/stage_driver.h"
#include "core/dynamics/stage_recorder.h"
#include "core/dynamics/step_report.h"
#include "core/dynamics/step_state.h"
#include "core/dynamics/time_stepper.h"
#include "core/model/actor_kind.h"
#include "core/model/articulated_kind.h"
#include "core/model/enums.h"
#include "core/model/error.h"
#include "core/model/eval_params.h"
#include "core/model/reset_on_copy.h"
#include "core/model/rigid_body.h"
#include "core/model/rigid_kind.h"
#include "core/model/soft_body.h"
#include "core/model/soft_kind.h"

namespace superdex {

struct ActorHandle {
  int index = -1;
  bool IsValid() const { return index >= 0; }
};

class Scene : private StageHost {
 public:
  explicit Scene(const SceneSettings& settings = SceneSettings());

  /// Adds a rigid actor; returns an invalid handle and fills *error on bad input (also a name
  /// another actor has). A valid `parent` nests the actor under it (IncludeNestedActors::Yes).
  ActorHandle AddRigidActor(const RigidActorDesc& desc, Error* error,
                            ActorHandle parent = ActorHandle());
  /// Adds a soft (tet FEM) actor; returns an invalid handle and fills *error on bad input. With
  /// skin bindings (SoftActorDesc::skin) it is a soft-skinned actor: `parent` must be its
  /// skeleton, an articulated actor, whose links then carry the bound nodes at the skeleton's
  /// current configuration; contact between the skin and the shapes and skins of the links it
  /// binds and their adjacent links is disabled (DisableAdjacentContact).
  ActorHandle AddSoftActor(const SoftActorDesc& desc, Error* error,
                           ActorHandle parent = ActorHandle());
  /// Adds an actor of any kind of the generic actor layer (core/model/actor_kind.h); returns an
  /// invalid handle and fills *error on bad input (ValidateKindLayout).
  ActorHandle AddActor(std::unique_ptr<ActorKind> actor, Error* error,
                       const std::string& contactLayer = "default",
                       ActorHandle parent = ActorHandle());

  /// Adds an articulated actor (core/model/articulated_kind.h) and, nested under it, one attached
  /// actor per link shape (BuildLinkShapes), each colliding and a collider with its own
  /// parameters; contact between the shapes of a link and of its parent link (and among one
  /// link's shapes) is disabled (DisableAdjacentContact; a later actor-contact setting overrides
  /// it). Returns the articulation's handle, or an invalid one with *error (nothing added).
  ActorHandle AddArticulatedActor(const ArticulatedActorDesc& desc, Error* error,
                                  const std::string& contactLayer = "default",
                                  ActorHandle parent = ActorHandle());
  /// The attached actors of an actor (its link shapes), in creation order.
  std::vector<ActorHandle> AttachedActors(ActorHandle carrier) const;
  /// An articulated actor's link mass [kg] (its second moment scales with it) and joint
  /// parameters (validated); false with *error naming the link and the rule.
  bool SetLinkMass(ActorHandle a, int link, double mass, Error* error);
  bool SetLinkJointParams(ActorHandle a, int link, const JointParams& params, Error* error);
  /// Whether a is an attached actor wholly carried by its carrier (ActorKind::FullyCarried; a
  /// link's shape); a soft skin has unknowns of its own and is not.
  bool IsAttached(ActorHandle a) const {
    return actors_[a.index].carrier >= 0 && kinds_[a.index]->FullyCarried();
  }
  /// The actor that carries parts of a (a link shape's or a skin's articulation; invalid: none).
  ActorHandle Carrier(ActorHandle a) const { return {actors_[a.index].carrier}; }
  /// The rigid body of a rigid actor or of an attached one (its shape, samples and field), null
  /// for other actors; and its state (an attached body's pose and velocity, its carrier's).
  const RigidBodyModel* BodyModel(ActorHandle a) const;
  RigidBodyState BodyState(ActorHandle a) const;

  // --- Contact filtering (spec: "Contact Filtering"): false, with *error, for a bad handle.
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
  /// reported in *report (status Stopped or Diverged), never silently accepted. `recorder` (may
  /// be null): the stages' recording policy (core/dynamics/stage_recorder.h; sensitivities).
  bool Step(double dt, StepReport* report, Error* error, StageRecorder* recorder = nullptr);

  double Time() const { return step_.time; }
  /// Every actor, rigid and soft; handles index this range in the order of creation.
  int NumActors() const { return static_cast<int>(actors_.size()); }
  bool IsSoft(ActorHandle a) const { return actors_[a.index].soft; }
  /// Whether a was added by AddActor (it is neither a rigid nor a soft actor).
  bool IsKind(ActorHandle a) const { return !actors_[a.index].rigid && !actors_[a.index].soft; }
  /// Every actor's kind (rigid actors are RigidKinds, soft ones SoftKinds) and state (x = q).
  const ActorKind& Kind(ActorHandle a) const { return *kinds_[a.index]; }
  const KindState& KindStateOf(ActorHandle a) const;
  /// Replaces a kind's state (its NumDofs entries in x and v, finite); clears BDF history.
  bool SetKindState(ActorHandle a, const KindState& state, Error* error);
  /// Rigid actors (a must be one).
  const RigidBodyModel& Model(ActorHandle a) const { return RigidOf(a).Model(); }
  /// The description a rigid (soft) actor was created from, with its parameters' setters' changes
  /// since (not its state's; the scene writer, scenes/scene_writer.h, reads both).
  const RigidActorDesc& RigidDesc(ActorHandle a) const { return rigidDescs_[actors_[a.index].desc]; }
  const SoftActorDesc& SoftDesc(ActorHandle a) const;
  /// The actor a is nested under (invalid handle: none).
  ActorHandle Parent(ActorHandle a) const { return {filter_.Parent(a.index)}; }
  const ContactFilter& Filter() const { return filter_; }
  /// A rigid actor's state (a must be one), formed from its kind's.
  RigidBodyState State(ActorHandle a) const;
  /// Soft actors (a must be one).
  const SoftBodyModel& SoftModel(ActorHandle a) const;
  const SoftBodyState& SoftState(ActorHandle a) const;
  /// The rigid actors' handles, in creation order.
  std::vector<ActorHandle> RigidActors() const { return ActorsWhere(&ActorRef::rigid); }
  /// Centre of mass [m] and its velocity [m/s] of any actor (soft: of the lumped node masses).
  Eigen::Vector3d CenterOfMass(ActorHandle a) const;
  Eigen::Vector3d CenterOfMassVelocity(ActorHandle a) const;
  std::vector<ActorHandle> SoftActors() const { return ActorsWhere(&ActorRef::soft); }
  /// Per boundary face of soft actor a, the contact traction on it averaged over the face's
  /// reference area, Σ_q w_q t_q / A_f [Pa] (world frame; zero for faces out of contact), from
  /// ContactSamples: normal, and the last step's friction and damping.
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
  /// Replaces a dynamic rigid actor's mass [kg] (finite, > 0); its second moment J scales with it
  /// (the same shape, uniformly denser).
  bool SetRigidMass(ActorHandle a, double mass, Error* error);
  /// Replaces a soft actor's Young's modulus and density (validated); Lamé parameters and the
  /// lumped masses follow. Poisson's ratio and stiffness damping are kept.
  bool SetSoftMaterial(ActorHandle a, double youngsModulus, double density, Error* error);
  /// Whether the scene holds multistep history (any step since the last state change).
  bool HasStepHistory() const { return !step_.historyTimes.empty(); }
  /// The smallest V_f over the actors [m/s].
  double MinFrictionFalloffVel() const;
  /// The actor of that name (invalid handle if none).
  ActorHandle FindActor(const std::string& name) const;
  const std::string& ActorName(ActorHandle a) const;

  // --- The dynamic state as one vector (core/sensitivity/sensitivity.h differentiates the step map on it).
  // Per dynamic actor, in creation order, its kind's x then v (a rigid actor: p, R column-major,
  // v, Ṙ, 24 entries; a soft actor: 6 per node); then, for the multistep methods, the same
  // blocks for each state of the history a step reads (zeros where the history is not filled yet).
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
  /// Every active contact sample now, its normal traction and the last step's dissipation (world).
  std::vector<ContactSampleRecord> ContactSamples();
  /// One-time notes (a collider not supported yet, a coefficient that combines to 0).
  std::vector<std::string> Notices() const;

  /// A point of the run with the stage policy's state, to return to (checkpoints, replays).
  struct Snapshot { StepState step; StageDriver::State driver; };
  Snapshot Save() const;
  void Restore(const Snapshot& s);

  // --- The stage's unknowns (valid once the scene has stepped): the actors' free tangent dofs in
  // creation order (6 per dynamic rigid actor, [δp, δθ]; 3 per free soft node).
  int StageDofs() const { return numDofs_; }
  /// First stage dof of actor a (−1 for an actor without free dofs).
  int StageDofOffset(ActorHandle a) const;
  const std::vector<int>& KindStageDofs(ActorHandle a) const;  ///< per tangent dof; −1: prescribed
  /// The history blocks of PackState's layout (multistep methods: 0 to 2).
  int HistoryBlocks() const;

 private:
  // Per actor (the index of kinds_ and step_.vectorStates): its role among the kinds.
  struct ActorRef {
    bool rigid = false;  ///< a rigid actor (a RigidKind)
    bool soft = false;   ///< a soft actor (a SoftKind)
    int desc = -1;       ///< a rigid (soft) actor's index into rigidDescs_ (softDescs_)
    int carrier = -1;    ///< an attached actor's carrier (ActorKind::Attachment), else −1
  };
  const RigidKind& RigidOf(ActorHandle a) const { return static_cast<const RigidKind&>(Kind(a)); }
  std::vector<ActorHandle> ActorsWhere(bool ActorRef::*flag) const;  // in creation order
  // Solves one stage by the stage policy (StageDriver::Solve), accounted in *rep.
  void SolveStage(double dt, const KindStage& stage, std::vector<Eigen::VectorXd>* x,
                  double predictTime, StepReport* rep) override;
  // The packed-state layout: calls visit(block, offset, actor index) for every dynamic
  // actor in each of the first `blocks` blocks (0: the current state, b >= 1: history b − 1).
  template <typename Visit>
  void VisitStateLayout(int blocks, Visit&& visit) const;
  // Changes actor a's kind by change(kind) on a copy (scenes copied from this one share the kind
  // and keep theirs); the scene prepares again.
  template <typename Change>
  void ChangeKind(int a, Change&& change);
  // Applies edit(kind) (returning "" or why not) to articulated actor a's link: checked on a copy
  // of its kind, then on the kind through ChangeKind; false with *error naming the link.
  template <typename Edit>
  bool EditLink(ActorHandle a, int link, Error* error, Edit&& edit);
  // A static rigid actor a is held at `state` from now on (its kind copied first if it changes).
  void HoldStatic(int a, const RigidBodyState& state);
  std::vector<int> RigidDescs() const;  // per actor: its index into rigidDescs_, −1 if not rigid
  int BlockSize(int a) const { return 2 * kinds_[a]->NumDofs(); }  // its entries in PackState
  int FilledStateBlocks() const;  // 1 + the history blocks that hold a state

  void ClearHistory();
  /// Writes every attached actor's state (now and in the history) from its carrier's.
  void SyncAttachedStates();
  bool ValidParent(ActorHandle parent, Error* error) const;  // no parent, or an existing actor
  bool UniqueName(const std::string& name, Error* error) const;  // empty, or no actor's yet
  // Carried actors (ActorKind::CarriedParts): whether `parent` can carry kind's parts, and, once
  // registered as h, h's carrier, its state from the carrier's and its adjacency with the
  // carrier's other actors on the same or adjacent frames (core/scene_skin.cpp).
  bool CheckCarried(const ActorKind& kind, ActorHandle parent, Error* error) const;
  void AttachToCarrier(ActorHandle h, ActorHandle parent);
  // A soft skin's carried parts: its bindings resolved on skeleton's links at its current
  // configuration; false with *error naming the binding's field and the rule.
  bool SkinParts(const SoftActorDesc& desc, const SoftKind& kind, ActorHandle skeleton,
                 std::vector<CarriedPart>* parts, Error* error) const;
  // Enters an actor into the kinds, the actor list and the filter.
  ActorHandle Register(std::shared_ptr<ActorKind> k, const std::string& layer, ActorHandle parent);
  void Prepare();
  void CurrentPositions(std::vector<Eigen::VectorXd>* x) const;  // into kept storage
  // The actors' stage data at stage time t [s]: targets from the stage start, geometry from the
  // last configuration.
  void MakeStage(double dt, double t, const std::vector<VectorState>& start,
                 const std::vector<Eigen::VectorXd>& last, KindStage* out) const override;
  const ActorKind& KindOf(size_t a) const override { return *kinds_[a]; }
  void ApplyConstraints(double t, std::vector<Eigen::VectorXd>* x) const override;  // Prescribe
  KindView CurrentKindView(const std::vector<Eigen::VectorXd>& x) const;  // contact view at x

  SceneSettings settings_;
  std::string settingsError_;  ///< Validate(settings_), kept with every change of settings_
  std::vector<RigidActorDesc> rigidDescs_;  // per model: as given to AddRigidActor
  std::vector<SoftActorDesc> softDescs_;    // per soft actor: as given to AddSoftActor
  /// SamplesHash → indices into kinds_ of the rigid actors' distinct sample sets (ShareSamples).
  std::unordered_multimap<std::size_t, int> sampleSets_;
  // The actors' kinds in creation order (copies of a scene share them; ChangeKind copies first).
  std::vector<std::shared_ptr<ActorKind>> kinds_;
  std::vector<const ActorKind*> kindPtrs_;           // for the pipeline and the stage
  std::vector<std::vector<int>> kindStageDof_;       // per kind: stage dof of each local dof
  // With attached actors: the contact's numbering (KindStage::contactDof), the attached actors.
  std::vector<std::vector<int>> kindContactDof_;
  int numContactDofs_ = 0;
  std::vector<KindStage::Attached> attached_;
  std::vector<ActorRef> actors_;
  StepState step_;  // what a step advances (vectorStates: the actors' vector states)
  StepBuffers buffers_;  // Step's storage kept from step to step (core/dynamics/step_state.h)
  // The pipeline is configured for these actors (it points at them; a copy configures its own).
  ResetOnCopy prepared_;
  bool hasDissipation_ = false;  // HasDissipation(), cached by Prepare
  bool coldStages_ = false;      // a kind refuses the warm start (ActorKind::Shortcuts); Prepare
  int numDofs_ = 0;
  ContactPipeline pipeline_;
  ContactFilter filter_;
  StageDriver driver_;              // the stage policy, its solvers and buffers
  StageRecorder* recorder_ = nullptr;  // the step under way's recording policy (or none)
};

}  // namespace superdex
