// An attached body: a rigid collision shape fixed to a frame its carrier holds (an articulation's
// link, core/model/articulated_kind.h), as an actor of the generic layer (core/model/
// actor_kind.h) nested under the carrier. It collides and is a collider exactly as a rigid
// actor of the same shape (its samples, its sample tree, its field in its body frame), with its
// own colliderType, boundary element type and contact parameters; it has no mass, energy or stage
// unknowns of its own. Its configuration q = [p, vec R] (body → world; the body frame's origin at
// the shape's centroid, as a rigid actor's) is written from the carrier's
// (AttachedConfiguration), and its tangent step [δp, δθ] is the carrier's chart Jacobian times
// the carrier's step: the stage carries the contact on it into the carrier's dofs
// (core/dynamics/scene_stage.h). Units: SI (m, kg, s).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/model/actor_kind.h"
#include "core/model/error.h"
#include "core/model/rigid_body.h"

namespace superdex {

/// A collision shape of a link (URDF's <collision>): its geometry, its pose in the link frame and
/// its contact role.
struct LinkShapeDesc {
  std::string name;  ///< empty: "<articulation>/<link>" (with "#k" for a link's k-th shape, k >= 1)
  RigidShape shape;  ///< Sphere, Box or Mesh (a Plane is static only)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< shape frame origin in the link frame [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< shape frame → link frame
  ContactParams contact;
  ColliderType colliderType = ColliderType::Auto;
  ActorBoundaryElementType boundaryElementType = ActorBoundaryElementType::P1Q3;
  SurfaceIntegral surfaceIntegral = SurfaceIntegral::Quadrature;
  GridSdfParams gridSdf;  ///< used when the collider resolves to Sdf
};

class AttachedBodyKind : public ActorKind {
 public:
  /// The body of `shape` on carried frame `frame`, whose origin is `frameOrigin` in the link
  /// frame [m] (a link's centre of mass); null with *error naming the field (`prefix` + its
  /// snake_case name) on bad input.
  static std::unique_ptr<AttachedBodyKind> Build(const LinkShapeDesc& shape, int frame,
                                                 const Eigen::Vector3d& frameOrigin,
                                                 const std::string& prefix, Error* error);

  const RigidBodyModel& Model() const { return model_; }

  std::string KindName() const override { return "attached body"; }
  std::unique_ptr<ActorKind> Clone() const override;
  int NumDofs() const override { return 12; }
  int NumTangentDofs() const override { return 6; }
  /// The identity pose, at rest (the scene writes it from the carrier when the actor is added).
  KindState InitialState() const override;
  /// No energy of its own: 0.
  double StageEnergy(const KindStageData& stage, const Eigen::VectorXd& q, int order,
                     PsdProjection projection, Eigen::VectorXd* g,
                     std::vector<Eigen::Triplet<double>>* H) const override;
  /// (p + δp, exp([δθ]×) R), as a rigid actor's.
  void Retract(const Eigen::VectorXd& q, const Eigen::VectorXd& delta,
               Eigen::VectorXd* out) const override;
  void TangentBetween(const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                      Eigen::VectorXd* delta) const override;
  int DofBlockSize() const override { return 6; }
  /// One Pose part: the whole body, on its link's frame.
  const std::vector<CarriedPart>* CarriedParts() const override { return &attachment_; }

  /// No mass: zero energies and momenta; the centre of mass reported is the body origin.
  double KineticEnergy(const KindState&) const override { return 0.0; }
  double GravityEnergy(const KindState&, const Eigen::Vector3d&) const override { return 0.0; }
  Eigen::Vector3d LinearMomentum(const KindState&) const override { return Eigen::Vector3d::Zero(); }
  Eigen::Vector3d AngularMomentum(const KindState&) const override { return Eigen::Vector3d::Zero(); }
  Eigen::Vector3d CenterOfMass(const KindState& s) const override { return s.x.head<3>(); }
  Eigen::Vector3d CenterOfMassVelocity(const KindState& s) const override { return s.v.head<3>(); }
  /// Its state follows its carrier's: no groups of its own.
  void DifferenceGroups(const KindState&, std::vector<KindDifferenceGroup>* groups) const override {
    groups->clear();
  }
  Aabb Bounds(const Eigen::VectorXd& q) const override;

  /// Colliding and collider roles as a rigid actor's (RigidKind).
  int NumSampleBodies() const override { return model_.samples.empty() ? 0 : 1; }
  const RigidBodyModel* SampleBody(int /*b*/) const override { return &model_; }
  RigidPose SampleBodyPose(int /*b*/, const Eigen::VectorXd& q) const override;
  void SampleBodyDofs(int /*b*/, int dof[2]) const override {
    dof[0] = 0;
    dof[1] = 3;
  }
  const RigidCollider* Collider() const override;
  KindFrame ColliderFrame(const Eigen::VectorXd& q) const override;

 private:
  AttachedBodyKind() = default;
  RigidBodyModel model_;
  std::vector<CarriedPart> attachment_;  ///< one Pose part at entry 0, dof 0
};

}  // namespace superdex
