// The generic actor layer: what an actor kind writes so that the stage, the integrators and the
// contact assembler can carry it without knowing it (docs/architecture.md, "Adding an actor
// kind").
//
// A kind's actor has a configuration q ∈ Rⁿ and a velocity v = q̇ ∈ Rⁿ (a vector-state kind: the
// integrators combine states affinely, exactly as for soft nodes). Each implicit stage adds the
// kind's own stage energy
//   Φ_a(q) = 1/(2Δt_i²) (q − q̂)ᵀ M (q − q̂) + U(q) [J],   q̂ = q⁰ + Δt_i v⁰,
// (inertia with the kind's mass matrix M, plus gravity and internal energies U), and the contact
// assembler (core/contact/kind_contact.h) adds the pair terms through the kind's two contact roles:
//   colliding: quadrature samples y(q) with their SamplePointMap (core/model/sample_map.h) and
//              weights w [m²];
//   collider:  a field Φ_B in a frame (p_B(q), R_B(q)) that follows the kind's dofs through a
//              constant frame Jacobian F = ∂(δp_B, δθ_B)/∂q (translation-only frames, as a
//              particle's, or frames that are a subset of the dofs).
// Units: SI (m, kg, s, N, J).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

#include "core/model/contact_params.h"
#include "core/model/enums.h"
#include "core/model/rigid_body.h"
#include "core/model/sample_map.h"
#include "core/model/vector_state.h"
#include "energies/psd_projection.h"
#include "geometry/aabb.h"

namespace superdex {

/// A kind's state: x is its configuration q, v = q̇.
using KindState = VectorState;

/// The integrator's data for one stage of one actor.
struct KindStageData {
  double dt = 0.0;                  ///< Δt_i [s]
  double time = 0.0;                ///< the stage's time [s]
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  ///< [m/s²]
  Eigen::VectorXd qHat;             ///< inertial target q⁰ + Δt_i v⁰
  Eigen::VectorXd q0;               ///< stage start q⁰ (an affine combination of states)
  Eigen::VectorXd qLast;            ///< last actual configuration (q_n, then Q_{i−1})
};

/// One colliding sample at a configuration: its world point, weight and point map. A Nodes map
/// reads the 3-dof blocks starting at the kind's local dofs `dof[0 .. map.nodes)`.
struct KindSample {
  Eigen::Vector3d y = Eigen::Vector3d::Zero();  ///< world point [m]
  double weight = 0.0;                          ///< quadrature weight w [m²]
  SamplePointMap map;                           ///< must be a Nodes map
  int dof[4] = {0, 0, 0, 0};                    ///< first local dof of each node's block
};

/// Largest number of dofs a kind's collider frame may follow.
constexpr int kMaxFrameDofs = 12;

/// A kind's collider frame at a configuration: pose (body → world), the 3-dof blocks of the
/// kind's local dofs that move it (first dofs `dof[0 .. blocks)`), and the Jacobian F
/// (6 × 3·blocks) of its [δp_B, δθ_B] in those dofs. The frame may only translate with the dofs
/// (F's rotation rows zero; checked when the actor is added): a frame whose rotation follows the
/// dofs needs the curvature of that map, which this layer does not carry yet.
struct KindFrame {
  RigidPose pose;
  int blocks = 0;
  int dof[4] = {0, 0, 0, 0};
  Eigen::Matrix<double, 6, kMaxFrameDofs> F = Eigen::Matrix<double, 6, kMaxFrameDofs>::Zero();
};

class ActorKind {
 public:
  virtual ~ActorKind() = default;

  /// The kind's name, for messages ("point mass", "shell", ...).
  virtual std::string KindName() const = 0;
  /// A copy (scenes are copied; a changed parameter copies the actor first).
  virtual std::unique_ptr<ActorKind> Clone() const = 0;
  /// n, the size of q and v.
  virtual int NumDofs() const = 0;
  /// The state at creation.
  virtual KindState InitialState() const = 0;
  /// Empty when valid; else a message naming the field and the rule (checked when added).
  virtual std::string Validate() const { return {}; }

  /// Φ_a(q) of the stage [J]. order >= 1: adds ∂Φ_a/∂q (size n, local dofs) into *g; order 2:
  /// appends ∂²Φ_a/∂q² in local (row, col) to *H, projected to PSD per `projection` where it
  /// is not PSD already.
  virtual double StageEnergy(const KindStageData& stage, const Eigen::VectorXd& q, int order,
                             PsdProjection projection, Eigen::VectorXd* g,
                             std::vector<Eigen::Triplet<double>>* H) const = 0;

  /// Prescribed dofs: whether dof i is held on a path (it is then no stage unknown), and
  /// Prescribe writes every prescribed dof's value at time t [s] into *q.
  virtual bool IsPrescribed(int /*dof*/) const { return false; }
  virtual void Prescribe(double /*t*/, Eigen::VectorXd* /*q*/) const {}

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

  // --- Collider role (null: not a collider). The field is in the frame's coordinates.
  virtual const RigidCollider* Collider() const { return nullptr; }
  virtual KindFrame ColliderFrame(const Eigen::VectorXd& /*q*/) const { return {}; }

  /// The actor's contact parameters (combined with the other actor's by the spec's rules).
  ContactParams contact;
  std::string name;
};

}  // namespace superdex
