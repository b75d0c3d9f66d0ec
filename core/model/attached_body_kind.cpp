#include "core/model/attached_body_kind.h"

#include "core/model/rigid_kind.h"
#include "core/model/rigid_math.h"

namespace superdex {

std::unique_ptr<AttachedBodyKind> AttachedBodyKind::Build(const LinkShapeDesc& shape, int frame,
                                                          const Eigen::Vector3d& frameOrigin,
                                                          const std::string& prefix,
                                                          Error* error) {
  if (shape.shape.kind == RigidShapeKind::Plane) {
    Fail(error, prefix + "shape: a plane is a static actor's shape, not a link's");
    return nullptr;
  }
  // A rigid actor of the shape, for its samples, sample tree and field (its mass is not used).
  RigidActorDesc d;
  d.name = shape.name;
  d.dynamic = true;
  d.mass = 1.0;
  d.shape = shape.shape;
  d.position = shape.position;
  d.orientation = shape.orientation;
  d.contact = shape.contact;
  d.colliderType = shape.colliderType;
  d.boundaryElementType = shape.boundaryElementType;
  d.surfaceIntegral = shape.surfaceIntegral;
  d.gridSdf = shape.gridSdf;
  std::unique_ptr<AttachedBodyKind> k(new AttachedBodyKind());
  RigidBodyState unused;
  if (!BuildRigidBody(d, prefix, &k->model_, &unused, error)) return nullptr;
  // The body frame's origin is the shape's centroid (shapeOffset in the shape frame).
  const Eigen::Matrix3d Ro = shape.orientation.normalized().toRotationMatrix();
  CarriedPart part;
  part.kind = CarriedPart::Kind::Pose;
  part.frame = frame;
  part.rotation = Ro;
  part.offset = shape.position + Ro * k->model_.shapeOffset - frameOrigin;
  k->attachment_.assign(1, part);
  k->contact = k->model_.contact;
  k->name = shape.name;
  return k;
}

std::unique_ptr<ActorKind> AttachedBodyKind::Clone() const {
  return std::unique_ptr<ActorKind>(new AttachedBodyKind(*this));
}

KindState AttachedBodyKind::InitialState() const {
  KindState s;
  s.x = Eigen::VectorXd::Zero(12);
  Matrix3At(&s.x, 3) = Eigen::Matrix3d::Identity();
  s.v = Eigen::VectorXd::Zero(12);
  return s;
}

double AttachedBodyKind::StageEnergy(const KindStageData& /*stage*/,
                                     const Eigen::VectorXd& /*q*/, int /*order*/,
                                     PsdProjection /*projection*/, Eigen::VectorXd* /*g*/,
                                     std::vector<Eigen::Triplet<double>>* /*H*/) const {
  return 0.0;
}

void AttachedBodyKind::Retract(const Eigen::VectorXd& q, const Eigen::VectorXd& delta,
                               Eigen::VectorXd* out) const {
  RigidChartRetract(q, delta, out);
}

void AttachedBodyKind::TangentBetween(const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                                      Eigen::VectorXd* delta) const {
  RigidChartBetween(from, to, delta);
}

Aabb AttachedBodyKind::Bounds(const Eigen::VectorXd& q) const {
  return WorldBounds(model_, q.head<3>(), Matrix3At(q, 3));
}

RigidPose AttachedBodyKind::SampleBodyPose(int /*b*/, const Eigen::VectorXd& q) const {
  return RigidKind::PoseOf(q);
}

const RigidCollider* AttachedBodyKind::Collider() const {
  return model_.collider.type == ColliderType::None ? nullptr : &model_.collider;
}

KindFrame AttachedBodyKind::ColliderFrame(const Eigen::VectorXd& q) const {
  return OwnPoseFrame(RigidKind::PoseOf(q));
}

}  // namespace superdex
