// The generic actor layer: what an actor kind writes so that the stage, the integrators and the
// contact assembler can carry it without knowing it (docs/architecture.md, "Adding an actor
// kind").
//
// A kind's actor has a configuration q ∈ Rⁿ and a velocity v = q̇ ∈ Rⁿ; the integrators combine
// states affinely, exactly as for soft nodes. The stage's unknowns are a tangent step δ ∈ Rᵐ at q,
// applied by the kind's retraction q ⊕ δ: q + δ for a vector kind (m = n, the default); a kind
// whose configuration lies on a manifold embeds it in Rⁿ (a rigid body: q = [p, vec R], n = 12,
// δ = [δp, δθ], m = 6, q ⊕ δ = [p + δp, vec(exp([δθ]×) R)]) and supplies the hooks below (its
// retraction, the residual Jacobian's trivialization, the chart's tangent map, and the DIRK
// stage slope and step end on the manifold). Each implicit stage adds the kind's own stage energy
//   Φ_a(q) = 1/(2Δt_i²) (q − q̂)ᵀ M (q − q̂) + U(q) [J],   q̂ = q⁰ + Δt_i v⁰,
// (inertia with the kind's mass matrix M, plus gravity and internal energies U), and the contact
// assembler (core/contact/kind_contact.h) adds the pair terms through the kind's two contact roles:
//   colliding: quadrature samples y(q) with their SamplePointMap (core/model/sample_map.h) and
//              weights w [m²];
//   collider:  a field Φ_B in a frame (p_B(q), R_B(q)) that follows the kind's dofs through a
//              constant frame Jacobian F = ∂(δp_B, δθ_B)/∂q (translation-only frames, as a
//              particle's), or a frame whose [δp_B, δθ_B] are two 3-dof blocks of δ (a rigid
//              body's own pose, with the rotation retraction's curvature).
// Units: SI (m, kg, s, N, J).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/model/collider_params.h"
#include "core/model/contact_params.h"
#include "core/model/enums.h"
#include "core/model/rigid_body.h"
#include "core/model/sample_map.h"
#include "core/model/soft_body.h"
#include "core/model/vector_state.h"
#include "energies/psd_projection.h"
#include "optim/stage_problem.h"
#include "geometry/aabb.h"

namespace superdex {

/// A kind's state: x is its configuration q, v = q̇.
using KindState = VectorState;

/// A kind's working memory for one actor's stages: what it derives from a stage's data once
/// (ActorKind::PrepareStage; a soft body's damping stiffness at the predictor) and its element
/// scratch. Kinds are shared by copies of a scene, which may evaluate them concurrently (the
/// sensitivities' replays), so a kind keeps no mutable state of its own: this lives in the stage
/// data, which each copy owns.
struct KindScratch {
  virtual ~KindScratch() = default;
};

/// The stage data's slot for a KindScratch of the kind's type T, made on first use. A copy of the
/// slot starts empty (it never shares the memory of another stage's).
class KindScratchSlot {
 public:
  KindScratchSlot() = default;
  KindScratchSlot(const KindScratchSlot&) {}
  KindScratchSlot& operator=(const KindScratchSlot&) {
    scratch_.reset();
    return *this;
  }
  KindScratchSlot(KindScratchSlot&&) = default;
  KindScratchSlot& operator=(KindScratchSlot&&) = default;
  template <typename T>
  T& Get() const {
    if (!scratch_ || !dynamic_cast<T*>(scratch_.get())) scratch_ = std::make_unique<T>();
    return static_cast<T&>(*scratch_);
  }

 private:
  mutable std::unique_ptr<KindScratch> scratch_;
};

/// The integrator's data for one stage of one actor.
struct KindStageData {
  double dt = 0.0;                  ///< Δt_i [s]
  double time = 0.0;                ///< the stage's time [s]
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  ///< [m/s²]
  Eigen::VectorXd qHat;             ///< inertial target q⁰ + Δt_i v⁰
  Eigen::VectorXd q0;               ///< stage start q⁰ (an affine combination of states)
  Eigen::VectorXd qLast;            ///< last actual configuration (q_n, then Q_{i−1})
  KindScratchSlot scratch;          ///< the kind's (PrepareStage, StageEnergy)
};

/// One colliding sample at a configuration: its world point, weight and point map. A Nodes map
/// reads the 3-dof blocks starting at the kind's local tangent dofs `dof[0 .. map.nodes)`; a
/// Rigid map reads [δp] at dof[0] and [δθ] at dof[1]. A sample with a colliding normal n (unit,
/// world) takes part in the alignment rejection and the friction fading (spec: "Normal/Tangential
/// Split"); without one it has neither.
struct KindSample {
  Eigen::Vector3d y = Eigen::Vector3d::Zero();  ///< world point [m]
  double weight = 0.0;                          ///< quadrature weight w [m²]
  SamplePointMap map;
  int dof[4] = {0, 0, 0, 0};                    ///< first local tangent dof of each block
  bool hasNormal = false;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();  ///< colliding normal (world), when hasNormal
  /// The normal is the unit normal of the triangle of the Nodes map's three nodes, which moves
  /// with them (a deforming surface's sample; the assembler differentiates it): their current
  /// positions, and the face's index for reports. Otherwise n is data of the configuration.
  bool faceNormal = false;
  Eigen::Vector3d faceNodes[3];
  int face = -1;
  /// The number of 3-dof blocks the map reads.
  int Blocks() const { return map.kind == SamplePointMap::Kind::Rigid ? 2 : map.nodes; }
};

/// Largest number of dofs a kind's collider frame may follow.
constexpr int kMaxFrameDofs = 12;

/// A kind's collider frame at a configuration: pose (body → world), the 3-dof blocks of the
/// kind's local tangent dofs that move it (first dofs `dof[0 .. blocks)`), and either
///   rigid = false: the Jacobian F (6 × 3·blocks) of its [δp_B, δθ_B] in those dofs; the frame may
///                  only translate with them (F's rotation rows zero; checked when the actor is
///                  added): a frame whose rotation follows a general map needs that map's
///                  curvature, which this layer does not carry yet; or
///   rigid = true:  blocks = 2 and [δp_B, δθ_B] are the dofs at dof[0] and dof[1] themselves,
///                  with the retraction R ← exp([δθ_B]×) R (the kind's own), F unused.
/// At a stage start x⁰ (an affine combination of configurations) the pose's R need not be a
/// rotation; the assembler uses its exact inverse there.
struct KindFrame {
  RigidPose pose;
  bool rigid = false;
  int blocks = 0;
  int dof[4] = {0, 0, 0, 0};
  /// rigid = false: F, 6 × 3·blocks (no storage beyond kMaxFrameDofs columns, none allocated).
  Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxFrameDofs> F;
};

/// A point fixed to a frame a kind carries (ActorKind::NumCarriedFrames): the frame and the
/// point's world position at the configuration in question [m].
struct FramePoint {
  int frame = -1;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

/// A part of an actor's configuration carried by a frame of its carrier (ActorKind::
/// CarriedParts), the frame (p_f, R_f) at the carrier's configuration:
///   Point: a material point of the frame, x = p_f + R_f o (3 entries of q at `entry`, 3 tangent
///          dofs δx at `dof`; a soft skin's node bound to a link);
///   Pose:  a rigid body fixed to the frame, p = p_f + R_f o, R = R_f R_o (body → world; the 12
///          entries [p, vec R] at `entry`, 6 tangent dofs [δp, δθ] at `dof`; a link's shape).
/// Both are linear in the carrier's [p_f, vec R_f], so they follow its velocity by the same map.
struct CarriedPart {
  enum class Kind { Point, Pose };
  Kind kind = Kind::Pose;
  int frame = -1;
  int entry = 0;                                          ///< first entry of q
  int dof = 0;                                            ///< first local tangent dof
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();       ///< o, in the frame [m]
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity(); ///< R_o, body → frame (Pose)
  /// Its tangent dofs: 3 (Point) or 6 (Pose).
  int Size() const { return kind == Kind::Point ? 3 : 6; }
};

/// The collider frame of a body whose pose is the kind's own: [δp_B, δθ_B] its tangent dofs
/// 0 .. 2 and 3 .. 5 (a rigid or attached body).
inline KindFrame OwnPoseFrame(const RigidPose& pose) {
  KindFrame f;
  f.pose = pose;
  f.rigid = true;
  f.blocks = 2;
  f.dof[0] = 0;
  f.dof[1] = 3;
  return f;
}

/// A DIRK stage's slope (V_i, K_i) of one actor, with the kind's own per-stage data (a rigid
/// body's stage torque) for its step end.
struct KindSlope {
  KindState slope;        ///< x: V_i, v: K_i
  Eigen::VectorXd extra;  ///< the kind's (empty for a vector kind)
};

/// Sensitivities (core/sensitivity/step_linearization.h): a group of an actor's coordinates that
/// the step linearization moves together, as a rigid body's pose and velocity or one node's.
struct KindDifferenceGroup {
  /// A direction of the state [q; v] (2n local entries, v from n) along which trajectories vary:
  /// its entries and weights, whether it is a velocity direction (all entries in v), and the
  /// length [m] one unit of it moves the actor's points (1 for a coordinate that is a length, a
  /// radius for a rotation). The directions of a group are mutually orthogonal.
  struct Direction {
    std::vector<std::pair<int, double>> entries;
    bool velocity = false;
    double length = 1.0;
  };
  std::vector<Direction> directions;
  std::vector<int> entries;          ///< the local entries of [q; v] the group owns
  std::vector<int> tangentDofs;      ///< its free local tangent dofs (the stage's unknowns)
  std::vector<double> tangentLength; ///< [m] per unit of each of them
};

/// Sensitivities and fitting: the initial-state parameters of an actor (component c of the
/// centre of mass's position [m], of its velocity [m/s], or of the angular velocity [rad/s]).
enum class KindMotion { Position, Velocity, AngularVelocity };

class ActorKind {
 public:
  virtual ~ActorKind() = default;

  /// The kind's name, for messages ("point mass", "shell", ...).
  virtual std::string KindName() const = 0;
  /// A copy (scenes are copied; a changed parameter copies the actor first).
  virtual std::unique_ptr<ActorKind> Clone() const = 0;
  /// n, the size of q and v.
  virtual int NumDofs() const = 0;
  /// m, the size of a tangent step δ (the kind's stage unknowns). StageEnergy's derivatives,
  /// IsPrescribed and the dof indices of samples and frames count these.
  virtual int NumTangentDofs() const { return NumDofs(); }
  /// The state at creation.
  virtual KindState InitialState() const = 0;
  /// Empty when valid; else a message naming the field and the rule (checked when added).
  virtual std::string Validate() const { return {}; }

  /// Called once per stage after the stage data is filled (and again whenever it changes):
  /// derives what StageEnergy reads at every evaluation into stage->scratch. Default: nothing.
  virtual void PrepareStage(KindStageData* /*stage*/) const {}
  /// Φ_a(q) of the stage [J]. order >= 1: adds ∂Φ_a(q ⊕ δ)/∂δ at δ = 0 (size m, local tangent
  /// dofs) into *g; order 2: appends the second derivative in local (row, col) to *H, projected
  /// to PSD per `projection` where it is not PSD already.
  virtual double StageEnergy(const KindStageData& stage, const Eigen::VectorXd& q, int order,
                             PsdProjection projection, Eigen::VectorXd* g,
                             std::vector<Eigen::Triplet<double>>* H) const = 0;

  /// A static actor (spec: a static collider, held where it was created for the whole run):
  /// pairs on its field take the colliding actor's penalty coefficient and friction falloff
  /// velocity instead of combining them (spec: "Contact Parameter Combination").
  virtual bool IsStatic() const { return false; }
  /// Prescribed dofs: whether tangent dof i is held on a path (it is then no stage unknown), and
  /// Prescribe writes every prescribed part's value at time t [s] into *q.
  virtual bool IsPrescribed(int /*dof*/) const { return false; }
  /// Whether some tangent dof is not prescribed (the actor is dynamic: it has stage unknowns).
  bool HasFreeDof() const;
  virtual void Prescribe(double /*t*/, Eigen::VectorXd* /*q*/) const {}
  /// The state at a step's end time t [s], after the integrator's rule (which gives prescribed
  /// parts their positions by Prescribe and their velocities by its differences): a kind whose
  /// path has an exact velocity writes it (a kinematic rigid body's pose and rates). Default:
  /// kept.
  virtual void EndPrescribed(double /*t*/, KindState* /*s*/) const {}

  /// A generalized force f on the tangent dofs (m entries) that is not the gradient of a stage
  /// energy, as a rigid body's applied world torque is (no function of the rotation has a
  /// constant world torque as its gradient), constant over the stage: written at the stage's
  /// time into *f, returning true; false (the default): none. The stage's residual takes −f, the
  /// stage is then not a potential, and its minimizing solves count f's work along the iterates
  /// they commit, W = Σ f·TangentBetween(q_c, q_next) [J] (core/dynamics/scene_stage.h).
  virtual bool StageLoad(const KindStageData& /*stage*/, Eigen::VectorXd* /*f*/) const {
    return false;
  }

  // --- A configuration on a manifold (defaults: a vector kind).
  /// *out = q ⊕ δ (δ: m entries; zero at prescribed dofs). Must be q + δ to the bit where the
  /// kind is a vector kind, and q itself at δ = 0.
  virtual void Retract(const Eigen::VectorXd& q, const Eigen::VectorXd& delta,
                       Eigen::VectorXd* out) const {
    *out = q + delta;
  }
  /// The residual modes' Jacobian is ∂r(q ⊕ δ)/∂δ of the stage residual r; the stage assembles
  /// the potential terms' second derivatives, exact for a vector kind. Where ⊕ is not additive,
  /// the kind appends (local row, col) the difference (a rigid rotation: −½[τ]× on its δθ block,
  /// τ the potential residual's torque entries, given in `residual`, m entries).
  virtual void AddResidualJacobianCorrection(const Eigen::VectorXd& /*q*/,
                                             const Eigen::VectorXd& /*residual*/,
                                             std::vector<Eigen::Triplet<double>>* /*J*/) const {}
  /// The chart's tangent map ∂(q ⊕ δ)/∂δ expressed back in tangent coordinates at q (m × m), for
  /// the solvers that move in a chart: I for a vector kind, the left Jacobian of SO(3) on a
  /// rotation's δθ.
  virtual Eigen::MatrixXd ChartTangentMap(const Eigen::VectorXd& delta) const {
    return Eigen::MatrixXd::Identity(delta.size(), delta.size());
  }
  /// The size of a step δ at q as a length [m] (the solvers' step tolerance): the largest entry
  /// for a vector kind of lengths; a rotation counts |δθ| times a radius.
  virtual double StepLength(const Eigen::VectorXd& /*q*/, const Eigen::VectorXd& delta) const {
    return delta.size() ? delta.lpNorm<Eigen::Infinity>() : 0.0;
  }
  /// The size (3 or 6) of the blocks of coupled tangent dofs a block preconditioner inverts over
  /// the kind's free dofs in order (optim/block_layout.h): 3 for nodes, 6 for a rigid body.
  virtual int DofBlockSize() const { return 3; }
  /// The fraction (0, 1] of a Newton correction δ the kind trusts (1: all; a rigid body bounds
  /// its move by a quarter of its radius, core/dynamics/scene_stage.h).
  virtual double TrustFraction(const Eigen::VectorXd& /*q*/,
                               const Eigen::VectorXd& /*delta*/) const {
    return 1.0;
  }
  /// DIRK: the stage slope from the stage's solution x = Q_i and its start (x⁰, v⁰) with step
  /// Δt_i [s]. Default (a vector kind): V_i = (x − x⁰)/Δt_i, K_i = (V_i − v⁰)/Δt_i.
  virtual void DirkStageSlope(const Eigen::VectorXd& x, const KindState& start, double dt,
                              KindSlope* out) const {
    out->slope.x = (x - start.x) / dt;
    out->slope.v = (out->slope.x - start.v) / dt;
    out->extra.resize(0);
  }
  /// DIRK: the step's end state. *end arrives as x_n + h Σ b_i V_i, v_n + h Σ b_i K_i; the kind
  /// may bring it back onto its manifold from x_n (`start`), the last stage's solution and the
  /// stages' slopes with their weights h b_i. Default: kept.
  virtual void DirkStepEnd(const KindState& /*start*/, const Eigen::VectorXd& /*lastStage*/,
                           bool /*stifflyAccurate*/, const std::vector<KindSlope>& /*slopes*/,
                           const std::vector<double>& /*hb*/, KindState* /*end*/) const {}

  // --- The stage policy's shortcuts (core/dynamics/stage_driver.h; defaults: a vector kind).
  /// Warm start: the predicted stage solution, the step-start motion continued with the last
  /// step's mean acceleration through the stage's own slope (core/dynamics/warm_start.h):
  ///   q = q⁰ + Δt_i (v_n + τ a),   a = (v_n − v_{n−1}) / h_{n−1}   (a = 0 without `previous`),
  /// τ [s] the stage's time after t_n, q⁰ (`stageStart`) and Δt_i (`stageDt`) the stage's start
  /// and step. A kind on a manifold predicts onto it.
  virtual void PredictStage(const KindState& current, const KindState* previous,
                            double hPrevious, double tau, const Eigen::VectorXd& stageStart,
                            double stageDt, Eigen::VectorXd* q) const {
    Eigen::VectorXd v = current.v;
    if (previous && hPrevious > 0.0) v += tau * (current.v - previous->v) / hPrevious;
    *q = stageStart + stageDt * v;
  }
  /// The tangent step δ (m entries) with from ⊕ δ = to: the inverse of Retract (to − from).
  virtual void TangentBetween(const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                              Eigen::VectorXd* delta) const {
    *delta = to - from;
  }
  /// How much the forces on the actor changed over the last two steps (states `before`,
  /// `previous`, `current`, hBefore and hPrevious seconds apart), as an acceleration [m/s²]; the
  /// warm start bounds the prediction of an actor whose change exceeds kSteadyAcceleration |g|
  /// (core/dynamics/warm_start.h) by its TrustFraction. Default: max over entries of
  /// |a_n − a_{n−1}|, a_n = (v_n − v_{n−1}) / h_{n−1} (a kind whose q is not lengths overrides it).
  virtual double ForceChange(const KindState& current, const KindState& previous,
                             double hPrevious, const KindState& before, double hBefore) const {
    if (current.v.size() == 0) return 0.0;
    return ((current.v - previous.v) / hPrevious - (previous.v - before.v) / hBefore)
        .lpNorm<Eigen::Infinity>();
  }
  /// The closed-form free stage: the minimizer of StageEnergy alone (no contact) into *q, and
  /// true, where the kind has it in closed form; false (the default): Newton solves the stage.
  virtual bool FreeStageMinimizer(const KindStageData& /*stage*/, Eigen::VectorXd* /*q*/) const {
    return false;
  }
  /// The stage policy's shortcuts in stages that hold the kind (all allowed by default):
  ///   warmStart:  predict each stage's solution (PredictStage) and try the closed-form free
  ///               stage (core/dynamics/stage_driver.h); one kind that refuses keeps every stage
  ///               of its scene cold;
  ///   stepLimit:  its contact pairs bound Newton steps (ContactPipeline::StepLimits); a pair
  ///               with a kind that refuses bounds neither actor;
  ///   splitParts: the line search may take the stage by independent parts (StageProblem::
  ///               LastSplit); one kind that refuses keeps its scene's stages whole.
  struct StageShortcuts {
    bool warmStart = true;
    bool stepLimit = true;
    bool splitParts = true;
  };
  virtual StageShortcuts Shortcuts() const { return {}; }

  /// Reporting: kinetic, gravity and internal (elastic, joint) energy [J], linear momentum
  /// [kg·m/s], angular momentum about the world origin [kg·m²/s], centre of mass [m] and its
  /// velocity [m/s].
  virtual double KineticEnergy(const KindState& s) const = 0;
  virtual double GravityEnergy(const KindState& s, const Eigen::Vector3d& gravity) const = 0;
  virtual double InternalEnergy(const KindState& /*s*/) const { return 0.0; }
  virtual Eigen::Vector3d LinearMomentum(const KindState& s) const = 0;
  virtual Eigen::Vector3d AngularMomentum(const KindState& s) const = 0;
  virtual Eigen::Vector3d CenterOfMass(const KindState& s) const = 0;
  virtual Eigen::Vector3d CenterOfMassVelocity(const KindState& s) const = 0;

  /// World bounds of everything that may touch another actor at q (samples and collider shape).
  virtual Aabb Bounds(const Eigen::VectorXd& q) const = 0;

  // --- Colliding role (no samples: not colliding).
  virtual int NumSamples() const { return 0; }
  virtual KindSample Sample(int /*k*/, const Eigen::VectorXd& /*q*/) const { return {}; }
  /// Culling: calls visit(begin, end) for ranges of sample indices, in a fixed order (the sums
  /// over them must be deterministic), skipping only samples inside balls that `keep` rejects:
  /// keep(c, cLast, r) is asked for a ball of radius r [m] holding the samples, centred at c at q
  /// and at cLast at qLast (world, m). The default visits every sample at once; a kind with many
  /// samples descends its own bounding-ball tree (a rigid body's sample tree).
  virtual void ForEachSampleNear(
      const Eigen::VectorXd& /*q*/, const Eigen::VectorXd& /*qLast*/,
      const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&, double)>& /*keep*/,
      const std::function<void(int, int)>& visit) const {
    visit(0, NumSamples());
  }

  /// Colliding samples carried by rigid bodies (instead of Sample's): body b's surface samples
  /// (RigidBodyModel::samples, X in the body frame, with their bounding-ball tree) move with its
  /// pose (p_b, R_b)(q), body → world, and the body's [δp, δθ] are the kind's local tangent dofs
  /// dof[0] .. +2 and dof[1] .. +2 (a rigid body's own pose; a link whose twist follows other dofs
  /// needs the general map, not in this layer yet). The assembler then chains them as a rigid
  /// body's samples (regrouped moments, its sample tree, no per-sample call into the kind).
  virtual int NumSampleBodies() const { return 0; }
  virtual const RigidBodyModel* SampleBody(int /*b*/) const { return nullptr; }
  virtual RigidPose SampleBodyPose(int /*b*/, const Eigen::VectorXd& /*q*/) const { return {}; }
  virtual void SampleBodyDofs(int /*b*/, int dof[2]) const { dof[0] = dof[1] = 0; }
  /// Whether the kind has a colliding role (samples of its own or on bodies).
  bool IsColliding() const { return NumSamples() > 0 || NumSampleBodies() > 0; }

  // --- Collider role (null: not a collider). The field is in the frame's coordinates.
  virtual const RigidCollider* Collider() const { return nullptr; }
  virtual KindFrame ColliderFrame(const Eigen::VectorXd& /*q*/) const { return {}; }
  /// Or a collider role carried by a tet deformation (a soft body's Sdf collider: the grid SDF
  /// over its reference configuration pulled back through its deformed tets, core/contact/
  /// tet_field.h): the model holding the rest tets, their reference data and the grid; node
  /// a's position is q's entries 3a .. 3a+2, its tangent dofs the same. Null: none.
  virtual const SoftBodyModel* TetCollider() const { return nullptr; }
  /// Or a PointCloud collider (spec: "Double-Integral Generalization"; its pairs: core/contact/
  /// point_cloud.h): its parameters (null: none), its points X_B, each a moving sphere of radius
  /// L_B about its current place, given as a sample is (y, a map on the kind's 3-dof blocks, no
  /// normal) with the quadrature weight w_B [m^d] of the outer integral, d = CloudDimension()
  /// (2: points of a surface, 1: of a curve). Self-contact compares the samples' and the points'
  /// places in the reference configuration (ReferenceConfiguration, a q).
  virtual const PointCloudColliderParams* PointCloud() const { return nullptr; }
  virtual int CloudDimension() const { return 2; }
  virtual int NumCloudPoints() const { return 0; }
  virtual KindSample CloudPoint(int /*j*/, const Eigen::VectorXd& /*q*/) const { return {}; }
  virtual const Eigen::VectorXd* ReferenceConfiguration() const { return nullptr; }

  /// Drawing: triangles over the kind's nodes (node a at q's entries 3a .. 3a+2) that show its
  /// surface (a soft body's boundary faces, a shell's triangles), for the trajectory and VTK
  /// writers and the viewer; null: none (drawn as a rigid shape, an articulation, or a marker).
  virtual const std::vector<Eigen::Vector3i>* SurfaceTriangles() const { return nullptr; }

  // --- Carried frames and attached actors (an articulation's links and their collision bodies).
  /// Rigid frames the configuration holds: frame f's origin and rotation (frame → world) are
  /// the 12 entries [p, vec R] of q at CarriedFrameOffset(f), a pose linear in q, so that an
  /// affine combination of states is that of the frame's material points (an articulation's
  /// link: its centre of mass and rotation). Default: none.
  virtual int NumCarriedFrames() const { return 0; }
  virtual int CarriedFrameOffset(int /*f*/) const { return -1; }
  /// The frame that frame f hangs from (an articulation's parent link; −1: none). Actors carried
  /// by the same or adjacent frames do not touch by default (Scene::AddActor).
  virtual int CarriedFrameParent(int /*f*/) const { return -1; }
  /// The chart Jacobians at q (one evaluation for all the points): (*A)[i] (6 × m) maps the
  /// tangent step δ to the move [δp; δθ] of the rigid chart (p + δp, exp([δθ]×) R) of frame
  /// points[i].frame about the world point points[i].point, which moves with the frame.
  virtual void CarriedFrameJacobians(const Eigen::VectorXd& /*q*/,
                                     const std::vector<FramePoint>& /*points*/,
                                     std::vector<Eigen::MatrixXd>* /*A*/) const {}
  /// Adds Σ_i (f_i·∂²p_i/∂δ∂δ + τ_i·∂²θ_i/∂δ∂δ) at δ = 0 into *H (m × m, local tangent dofs):
  /// the second-order part of chart loads [f_i; τ_i] = loads[i] [N; N·m] (the chart gradients
  /// of an energy of the frames' poses) carried into the tangent step.
  virtual void AddCarriedFrameCurvature(const Eigen::VectorXd& /*q*/,
                                        const std::vector<FramePoint>& /*points*/,
                                        const std::vector<Eigen::Matrix<double, 6, 1>>& /*loads*/,
                                        Eigen::MatrixXd* /*H*/) const {}
  /// Carried parts: the parts of the configuration that a frame of the actor's carrier (the
  /// actor it is nested under; Scene::AddActor checks the frames exist) holds, a link's collision
  /// body (one Pose part: all of it) or a soft skin's nodes bound to links (Point parts). Their
  /// entries of q (and v) are written from the carrier's (AttachedConfiguration) wherever the
  /// carrier's change; their tangent dofs are no stage unknowns: what the stage assembles on them
  /// (contact, and the actor's own energy) reaches the carrier's tangent dofs through the chart
  /// Jacobian (core/dynamics/scene_stage.h). Parts do not overlap and are not prescribed. Null or
  /// empty: none (the actor is not attached).
  virtual const std::vector<CarriedPart>* CarriedParts() const { return nullptr; }
  /// Whether the actor has carried parts, and whether they cover every tangent dof (the actor is
  /// then no more than its carrier's: an attached body).
  bool IsCarried() const;
  bool FullyCarried() const;

  // --- Sensitivities (core/sensitivity/; defaults: a vector kind whose q are lengths).
  /// The groups of coordinates the step linearization moves together at state s. Default: one
  /// group of every entry of q and v (each a direction of length 1) and every free tangent dof.
  /// A kind whose state lies on a manifold gives only the directions its trajectories take (a
  /// rotation R varies by [ξ]× R only); a kind of many nodes gives a group per node, so that
  /// nodes far apart are differenced in one run.
  virtual void DifferenceGroups(const KindState& s, std::vector<KindDifferenceGroup>* groups) const;
  /// An initial-state parameter at s: its value, and the direction d (2n entries over [q; v])
  /// along which the state moves per unit of it (the state with the value moved by t is s + t d).
  /// Default: none (false). Position and Velocity move every point of the actor alike.
  virtual bool MotionParameter(KindMotion /*motion*/, int /*component*/, const KindState& /*s*/,
                               double* /*value*/, Eigen::VectorXd* /*direction*/) const {
    return false;
  }
  /// ∂c/∂q (3 × n) of the centre of mass c = CenterOfMass(s) at s. Default: central differences
  /// of CenterOfMass with steps of 1e-6 (1 + |q_i|) m (exact to round-off where c is linear in
  /// q, as it is for a body of nodes).
  virtual Eigen::MatrixXd CenterOfMassJacobian(const KindState& s) const;

  /// The actor's contact parameters (combined with the other actor's by the spec's rules).
  ContactParams contact;
  std::string name;
};

/// Writes the carried parts' entries of q from the carrier's configuration carrierQ (or, the map
/// being linear, their velocities from the carrier's velocity): p_f + R_f o, and R_f R_o for a
/// Pose. q keeps its other entries.
void AttachedConfiguration(const ActorKind& carrier, const std::vector<CarriedPart>& parts,
                           const Eigen::VectorXd& carrierQ, Eigen::VectorXd* q);

/// Empty when an actor of `kind` can be added to a scene with this gravity [m/s²]; else why not
/// (the kind's own Validate and contact parameters, its state sizes, a stage load's size, and
/// that its samples, sample bodies and collider frame read whole 3-dof blocks of its tangent
/// step, prescribed all or none).
std::string ValidateKindLayout(const ActorKind& kind, const Eigen::Vector3d& gravity);

}  // namespace superdex
