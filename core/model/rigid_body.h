// Rigid actors: their description (what a user gives), model (fixed during a run) and state.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/model/contact_params.h"
#include "core/model/enums.h"
#include "core/model/error.h"
#include "core/model/keyframes.h"
#include "core/model/shared_array.h"
#include "geometry/aabb.h"
#include "core/model/collider_params.h"
#include "geometry/analytic_sdf.h"
#include "geometry/grid_sdf.h"
#include "geometry/mesh_sdf.h"
#include "geometry/triangle_mesh.h"

namespace superdex {

/// Pose of a rigid body: centre of mass p [m] and rotation R (body → world).
struct RigidPose {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
};

enum class RigidShapeKind { Sphere, Box, Mesh, Plane, Capsule };
/// "sphere", "box", "mesh", "plane", "capsule"
EnumNames<RigidShapeKind> NamesOf(RigidShapeKind);

/// Geometry of a rigid actor in its own frame. Sphere, Box and Capsule are centred at the frame
/// origin; a Capsule's straight part lies along z (URDF's cylinder axis).
/// A Plane (static actors only) is the half space {X : n·X <= 0} of its frame. A Mesh is a closed,
/// outward-oriented triangle mesh in the frame given by its file.
struct RigidShape {
  RigidShapeKind kind = RigidShapeKind::Sphere;
  double radius = 0.5;                                      ///< Sphere, Capsule [m]
  double halfLength = 0.5;  ///< Capsule: half the length of its straight part [m] (> 0)
  Eigen::Vector3d halfExtents = Eigen::Vector3d::Constant(0.5);  ///< Box [m]
  Eigen::Vector3d planeNormal = Eigen::Vector3d::UnitZ();   ///< Plane (unit after creation)
  std::shared_ptr<const TriangleMesh> mesh;                 ///< Mesh
  std::string meshSource;                                   ///< Mesh: its file, for messages
  /// Surface resolution of the colliding samples: icosphere subdivisions for a Sphere, grid
  /// divisions per box edge for a Box, for a Capsule latitude rings per end cap (6 × that
  /// around, side rows at about the same spacing); ignored for Mesh (its own faces) and Plane
  /// (no samples).
  int surfaceResolution = 3;
};

/// A keyframe of a kinematic actor's path: the pose of its shape frame at time t [s].
struct PoseKeyframe {
  double t = 0.0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< shape frame origin [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

/// What a user gives to create a rigid actor.
struct RigidActorDesc {
  std::string name;
  bool dynamic = true;
  RigidShape shape;
  double density = 1000.0;                    ///< [kg/m³], used when mass is not given
  std::optional<double> mass;                 ///< [kg]; overrides density
  std::optional<Eigen::Matrix3d> inertia;     ///< inertia tensor about the centre of mass in the
                                              ///< shape frame [kg·m²]; default from the shape
  Eigen::Vector3d position = Eigen::Vector3d::Zero();        ///< shape frame origin [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();  ///< of the centre of mass [m/s]
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero(); ///< world frame [rad/s]
  ContactParams contact;
  ColliderType colliderType = ColliderType::Auto;
  ActorBoundaryElementType boundaryElementType = ActorBoundaryElementType::P1Q3;
  /// The penalty's surface integral (core/model/enums.h); ExactSphere needs a sphere shape.
  SurfaceIntegral surfaceIntegral = SurfaceIntegral::Quadrature;
  std::string contactLayer = "default";
  GridSdfParams gridSdf;  ///< used when the collider resolves to Sdf
  /// A kinematic actor (dynamic must be false) follows a prescribed motion: it collides as a
  /// dynamic actor does (colliding samples and collider field) but nothing it touches moves it.
  /// Its shape frame follows `path`, or without a path it moves from position/orientation at the
  /// constant linearVelocity (of the centre of mass) and angularVelocity.
  bool kinematic = false;
  /// Keyframes with increasing times: the origin moves linearly and the orientation along the
  /// shortest rotation between keyframes; the first pose holds before the first keyframe, the
  /// last after the last. A path replaces position and orientation (its pose at time 0 is the
  /// initial one).
  std::vector<PoseKeyframe> path;
  /// Dynamic actors: a force at the centre of mass [N] and a torque [N·m], world frame, piecewise
  /// linear in time (VectorKeyframes; one keyframe: constant). The force enters each stage as the
  /// potential −F(t_i)·p, the torque as the generalized force τ(t_i) on the rotation (not a
  /// potential: a stage with a torque is solved on its residual, docs/solver.md).
  VectorKeyframes appliedForce, appliedTorque;
};

/// A node of a body's sample tree: a contiguous range [begin, end) of its samples with a
/// bounding sphere in the body frame, so that a narrow phase can skip whole groups: with a
/// collider field of Lipschitz constant L, every sample of the node has φ >= φ(centre) − L radius.
/// Internal nodes split their range in two halves (children `left`, `right`); leaves (left = −1)
/// hold at most kSamplesPerLeaf samples.
struct SampleNode {
  int begin = 0, end = 0;
  int left = -1, right = -1;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< [m]
  double radius = 0.0;                               ///< [m]
};
constexpr int kSamplesPerLeaf = 16;

/// One colliding quadrature sample in the body frame (origin at the centre of mass).
struct SurfaceSample {
  Eigen::Vector3d X;       ///< reference position [m]
  Eigen::Vector3d normal;  ///< outward unit normal n_A in the body frame
  double weight;           ///< reference-area weight w_q [m²]
};

/// The analytic field of a rigid collider, in the body frame.
struct RigidCollider {
  ColliderType type = ColliderType::None;  ///< resolved: None, Sphere, Box, Plane, Capsule, Mesh or Sdf
  SphereSdf sphere;
  BoxSdf box;
  CapsuleSdf capsule;
  PlaneSdf plane;
  std::shared_ptr<const MeshSdf> mesh;     ///< Mesh: exact distance to the shape's mesh
  std::shared_ptr<const GridSdf> grid;     ///< Sdf: trilinear grid
  /// Bound on |∇Φ| used by the culling tests: 1 for exact distance fields, √3 for a trilinear
  /// grid (each partial derivative of the interpolant is a node difference over h).
  double lipschitz = 1.0;
  double boundingRadius = 0.0;  ///< max |X| over the shape (infinite for a plane) [m]
  SdfSample Evaluate(const Eigen::Vector3d& X) const;
  /// Φ(X) alone (culling tests and inactive samples): the analytic fields skip their gradient
  /// and Hessian; mesh and grid fields evaluate in full.
  double Value(const Eigen::Vector3d& X) const;
  /// Φ(X), with ∇Φ and ∇∇Φ unless Φ >= bound: fills *s (its value always) and returns false
  /// only where Φ >= bound (a NaN is evaluated in full and returns true, as Evaluate would pass
  /// it on). For the per-sample loops, where most samples lie beyond the contact threshold.
  bool EvaluateBelow(const Eigen::Vector3d& X, double bound, SdfSample* s) const;
  /// EvaluateBelow without the sphere's Hessian (s->hessian not written; the other fields
  /// evaluate in full: a box's or plane's Hessian costs little), for the tests that read Φ and ∇Φ
  /// alone, which on a sphere field mostly reject the sample; CompleteHessian at the same X adds
  /// it where a sample turns out to need it (the same operations: value and gradient unchanged).
  bool EvaluateFirstOrderBelow(const Eigen::Vector3d& X, double bound, SdfSample* s) const {
    return type == ColliderType::Sphere ? sphere.EvaluateBelow(X, bound, s, false)
                                        : EvaluateBelow(X, bound, s);
  }
  void CompleteHessian(const Eigen::Vector3d& X, SdfSample* s) const {
    if (type == ColliderType::Sphere) sphere.EvaluateBelow(X, INFINITY, s);
  }
  /// A lower bound of the first-order model Φ(X) + ∇Φ(X)·D over the ball |X − C| <= r [m] (the
  /// reconstructed load of points that were at X + D at x_n): for a sphere field,
  /// |C| − r − ρ + Ĉ·D − c|D| with c = 2 sin(½ asin(r/|C|)) the largest |X̂ − Ĉ| over the ball
  /// (|C| > r); for a plane, Φ(C + D) − r; otherwise Φ(C) − L (r + |D|).
  double FirstOrderLowerBound(const Eigen::Vector3d& C, double r, const Eigen::Vector3d& D) const;
};

/// Everything about a rigid actor that stays fixed during a run. The body frame has its origin at
/// the centre of mass; `shapeOffset` is the centre of mass in the user's shape frame.
struct RigidBodyModel {
  std::string name;
  bool dynamic = true;
  RigidShape shape;
  double mass = 0.0;                                        ///< [kg] (0 for static actors)
  double volume = 0.0;                                      ///< of the shape [m³] (0: plane)
  Eigen::Matrix3d secondMoment = Eigen::Matrix3d::Zero();   ///< J = ∫ X Xᵀ dm [kg·m²]
  Eigen::Vector3d shapeOffset = Eigen::Vector3d::Zero();    ///< [m]
  /// Colliding role (empty if none); shared with the models of identical shapes (ShareSamples).
  SharedArray<SurfaceSample> samples;
  double samplesRadius = 0.0;                               ///< max |X| over the samples [m]
  /// Bounding-sphere tree over the samples (node 0 the root; samples stored in leaf order), built
  /// by median splits along the longest side of each node's box.
  SharedArray<SampleNode> sampleTree;
  Aabb localBounds;                                         ///< body-frame bounds of the shape
  RigidCollider collider;                                   ///< collider role
  ColliderType requestedCollider = ColliderType::Auto;
  ContactParams contact;
  ActorBoundaryElementType boundaryElementType = ActorBoundaryElementType::P1Q3;
  SurfaceIntegral surfaceIntegral = SurfaceIntegral::Quadrature;
  std::string contactLayer;
  std::string notice;  ///< a one-time note for the run log (e.g. a collider not supported yet)
  bool kinematic = false;  ///< a prescribed motion (dynamic false): KinematicStateAt
  /// Kinematic: the path, with the centre of mass's offset from the shape frame (shapeOffset);
  /// without keyframes the motion from p0, R0 at velocity v0 (centre of mass) and spin omega0.
  std::vector<PoseKeyframe> path;
  Eigen::Vector3d p0 = Eigen::Vector3d::Zero(), v0 = Eigen::Vector3d::Zero(),
                  omega0 = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R0 = Eigen::Matrix3d::Identity();
  VectorKeyframes appliedForce, appliedTorque;  ///< dynamic: see RigidActorDesc
  /// Whether the body moves in contact: dynamic or kinematic (colliding samples, moving field).
  bool Moves() const { return dynamic || kinematic; }
};


/// Makes `m` share `other`'s samples and sample tree (one buffer for both models) when they are
/// equal element for element; returns whether they were. Models from the same description
/// (a grid of identical spheres) then read one copy in the contact sweeps.
bool ShareSamples(const RigidBodyModel& other, RigidBodyModel* m);
/// A hash of a model's samples (equal samples, equal hash), to find candidates for ShareSamples.
std::size_t SamplesHash(const RigidBodyModel& m);

/// Pose and velocity. Velocities are kept in material-point form: the velocity of body point X
/// is v + Ṙ X, so that BDF combinations of states are plain affine combinations.
struct RigidBodyState {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();      ///< centre of mass [m]
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  ///< rotation body → world
  Eigen::Vector3d v = Eigen::Vector3d::Zero();      ///< centre-of-mass velocity [m/s]
  Eigen::Matrix3d Rdot = Eigen::Matrix3d::Zero();   ///< dR/dt [1/s]

  /// World angular velocity ω = axial(Ṙ Rᵀ) [rad/s].
  Eigen::Vector3d AngularVelocity() const;
};

/// A kinematic body's state at time t [s]: pose (centre of mass, rotation) and the motion's
/// velocity (centre of mass [m/s], Ṙ = [ω]× R) — on a path, the velocity of the segment that
/// ends at or after t (zero after the last keyframe).
RigidBodyState KinematicStateAt(const RigidBodyModel& m, double t);

/// Builds the model and initial state, validating the description. Returns false with a message
/// naming the field (`prefix` + snake_case name) on invalid input.
bool BuildRigidBody(const RigidActorDesc& desc, const std::string& prefix, RigidBodyModel* model,
                    RigidBodyState* state, Error* error);

/// The state BuildRigidBody gives the model m it built from d.
RigidBodyState InitialRigidState(const RigidActorDesc& d, const RigidBodyModel& m);

/// Kinetic energy ½ m|v|² + ½ tr(Ṙ J Ṙᵀ) [J].
double KineticEnergy(const RigidBodyModel& model, const RigidBodyState& state);
/// Linear momentum m v [kg·m/s] and angular momentum about the world origin
/// m p × v + axial(Ṙ J Rᵀ − R J Ṙᵀ) [kg·m²/s] (the integral of x × v dm over material points).
Eigen::Vector3d LinearMomentum(const RigidBodyModel& model, const RigidBodyState& state);
Eigen::Vector3d AngularMomentum(const RigidBodyModel& model, const RigidBodyState& state);
/// Spin angular momentum about the centre of mass of a material-point state (R, Ṙ), world frame:
/// L = axial(Ṙ J Rᵀ − R J Ṙᵀ) [kg·m²/s] for the second moment J (R, Ṙ may be affine).
Eigen::Vector3d SpinMomentum(const Eigen::Matrix3d& R, const Eigen::Matrix3d& Rdot,
                             const Eigen::Matrix3d& J);
/// RMS distance of a body's material points from its centre of mass, √(tr J / m) [m] (0 without
/// mass).
double RmsRadius(const RigidBodyModel& model);
/// World inertia tensor R (tr(J) 1 − J) Rᵀ [kg·m²]: L = I_w ω for Ṙ = [ω]× R.
Eigen::Matrix3d WorldInertia(const Eigen::Matrix3d& R, const Eigen::Matrix3d& J);

/// The trust region of one Newton correction of a rigid body (the stage's TrustStep, core/dynamics/scene_stage.h), as a
/// fraction of the body's radius. The contact step limit bounds how much a sample's depth may
/// grow, as the field reads it; it cannot see a correction that carries a body past the medial
/// plane of a box (where the field's gradient flips and the body is pushed out the far side) or
/// a rotation of many radians along the flat, rippled landscape a sampled sphere has about its
/// centre (the inertia's curvature J/Δt² against the sampling's spurious torques).
constexpr double kCorrectionTrust = 0.25;

/// World AABB of the shape at the given pose (a plane's: its half-space's, all of space unless
/// its normal is parallel to an axis).
Aabb WorldBounds(const RigidBodyModel& model, const Eigen::Vector3d& p, const Eigen::Matrix3d& R);

/// Calls visit(begin, end) for the sample range of every leaf of m's sample tree reached by
/// descending from the root through the nodes that keep(centre, radius) accepts (body frame), in
/// the samples' storage order, so that sums over the visited samples are deterministic.
template <typename Keep, typename Visit>
void ForEachSampleRange(const RigidBodyModel& m, Keep&& keep, Visit&& visit) {
  if (m.sampleTree.empty()) return;
  int stack[64];  // depth <= log2(samples / kSamplesPerLeaf) + 1 for median splits
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const SampleNode& node = m.sampleTree[stack[--top]];
    if (!keep(node.center, node.radius)) continue;
    if (node.left < 0) {
      if constexpr (std::is_invocable_v<Visit&, int, int, const SampleNode&>) {
        visit(node.begin, node.end, node);  // a visit that reads the leaf's ball
      } else {
        visit(node.begin, node.end);
      }
      continue;
    }
    stack[top++] = node.right;
    stack[top++] = node.left;
  }
}

}  // namespace superdex
