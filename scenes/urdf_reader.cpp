// URDF robots as articulated actors (urdf_reader.h).
#include "scenes/urdf_reader.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include "geometry/mesh_io.h"

namespace superdex {
namespace {

/// Collects the parser's error messages instead of printing them.
class CollectErrors : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && message.empty()) message = text;
  }
  std::string message;
};

RigidPose PoseOf(const urdf::Pose& p) {
  RigidPose out;
  out.p = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  const urdf::Rotation& r = p.rotation;
  out.R = Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
  return out;
}

Eigen::Vector3d VectorOf(const urdf::Vector3& v) { return Eigen::Vector3d(v.x, v.y, v.z); }

/// Link `link`'s description without its joint: its inertial in its own frame.
bool ReadInertial(const urdf::Link& link, ArticulatedLinkDesc* d, std::string* problem) {
  d->name = link.name;
  d->mass = 0.0;
  d->inertia.setZero();
  if (!link.inertial) return true;
  const urdf::Inertial& in = *link.inertial;
  if (!(std::isfinite(in.mass) && in.mass >= 0.0)) {
    std::ostringstream s;
    s << "<inertial> mass must be finite and >= 0, got " << in.mass;
    *problem = s.str();
    return false;
  }
  const RigidPose frame = PoseOf(in.origin);
  Eigen::Matrix3d I;
  I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  d->mass = in.mass;
  d->centerOfMass = frame.p;
  d->inertia = frame.R * I * frame.R.transpose();  // the tensor in the link frame
  return true;
}

/// The link's joint from URDF joint `j` (parent index given); false with *problem.
bool ReadJoint(const urdf::Joint& j, ArticulatedLinkDesc* d, std::string* problem) {
  d->joint.origin = PoseOf(j.parent_to_joint_origin_transform);
  switch (j.type) {
    case urdf::Joint::REVOLUTE:
    case urdf::Joint::CONTINUOUS: d->joint.type = JointType::Revolute; break;
    case urdf::Joint::PRISMATIC: d->joint.type = JointType::Prismatic; break;
    case urdf::Joint::FIXED: d->joint.type = JointType::Fixed; break;
    case urdf::Joint::FLOATING:
      *problem = "floating joints are supported only as the base (\"base\": \"free\" in the "
                 "scene file), not below a link";
      return false;
    case urdf::Joint::PLANAR: *problem = "planar joints are not supported"; return false;
    default: *problem = "a joint of unknown type"; return false;
  }
  if (j.mimic) {
    *problem = "mimic joints are not supported";
    return false;
  }
  if (d->joint.type == JointType::Fixed) return true;
  const Eigen::Vector3d axis = VectorOf(j.axis);
  if (!(axis.norm() > 0.0)) {
    *problem = "<axis> must be a non-zero vector";
    return false;
  }
  d->joint.axis = axis.normalized();
  if (j.type != urdf::Joint::CONTINUOUS && j.limits) {
    if (!(j.limits->lower <= j.limits->upper)) {
      std::ostringstream s;
      s << "<limit> lower " << j.limits->lower << " must be <= upper " << j.limits->upper;
      *problem = s.str();
      return false;
    }
    d->jointParams.lowerLimit = j.limits->lower;
    d->jointParams.upperLimit = j.limits->upper;
  }
  if (j.dynamics) d->jointParams.damping = j.dynamics->damping;
  return true;
}

/// Sample divisions along an edge of length `edge` [m] at spacing at most `spacing` [m].
int Divisions(double edge, double spacing) {
  return std::clamp(static_cast<int>(std::ceil(edge / spacing - 1e-9)), 1, 64);
}

/// One <collision>'s geometry as a shape; false with *problem.
bool ReadGeometry(const urdf::Geometry& g, const UrdfPlacement& placement, RigidShape* shape,
                  std::string* problem) {
  switch (g.type) {
    case urdf::Geometry::SPHERE:
      shape->kind = RigidShapeKind::Sphere;
      shape->radius = static_cast<const urdf::Sphere&>(g).radius;
      shape->surfaceResolution = 3;
      if (!(shape->radius > 0.0)) return *problem = "<sphere> radius must be > 0", false;
      return true;
    case urdf::Geometry::BOX: {
      const urdf::Vector3& dim = static_cast<const urdf::Box&>(g).dim;
      shape->kind = RigidShapeKind::Box;
      shape->halfExtents = 0.5 * Eigen::Vector3d(dim.x, dim.y, dim.z);
      if (!(shape->halfExtents.minCoeff() > 0.0)) return *problem = "<box> size must be > 0", false;
      shape->surfaceResolution = Divisions(2.0 * shape->halfExtents.maxCoeff(), placement.sampleSpacing);
      return true;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(g);
      if (!(c.radius > 0.0 && c.length > 0.0))
        return *problem = "<cylinder> radius and length must be > 0", false;
      if (placement.cylindersAsCapsules) {
        if (!(c.length > 2.0 * c.radius)) {
          std::ostringstream s;
          s << "<cylinder> length " << c.length << " is not longer than its diameter "
            << 2.0 * c.radius << ": no capsule of that length (read cylinders as meshes)";
          return *problem = s.str(), false;
        }
        shape->kind = RigidShapeKind::Capsule;
        shape->radius = c.radius;
        shape->halfLength = 0.5 * c.length - c.radius;
        shape->surfaceResolution = 8;
        return true;
      }
      // Along z, as URDF's (the mesh maker's is along x).
      auto mesh = std::make_shared<TriangleMesh>(MakeCylinderMesh(
          c.radius, 0.5 * c.length, 24, Divisions(c.length, placement.sampleSpacing)));
      for (Eigen::Vector3d& v : mesh->vertices) v = Eigen::Vector3d(v.y(), v.z(), v.x());
      shape->kind = RigidShapeKind::Mesh;
      shape->mesh = mesh;
      shape->meshSource = "<cylinder>";
      return true;
    }
    case urdf::Geometry::MESH: {
      const auto& m = static_cast<const urdf::Mesh&>(g);
      if (m.filename.rfind("package://", 0) == 0)
        return *problem = "<mesh> '" + m.filename + "': package:// URIs are not resolved (give a "
                          "path relative to the URDF file)", false;
      std::string file = m.filename.rfind("file://", 0) == 0 ? m.filename.substr(7) : m.filename;
      if (!file.empty() && file[0] != '/' && !placement.meshDirectory.empty())
        file = (std::filesystem::path(placement.meshDirectory) / file).string();
      auto mesh = std::make_shared<TriangleMesh>();
      std::string err;
      if (!ReadMeshFile(file, mesh.get(), &err)) return *problem = "<mesh> " + err, false;
      const Eigen::Vector3d scale(m.scale.x, m.scale.y, m.scale.z);
      if (!(scale.minCoeff() > 0.0)) return *problem = "<mesh> scale must be > 0", false;
      for (Eigen::Vector3d& v : mesh->vertices) v = v.cwiseProduct(scale);
      shape->kind = RigidShapeKind::Mesh;
      shape->mesh = mesh;
      shape->meshSource = file;
      return true;
    }
  }
  return *problem = "a <collision> geometry of unknown type", false;
}

/// Link `link`'s <collision> elements as its shapes; false with *problem.
bool ReadCollisions(const urdf::Link& link, const UrdfPlacement& placement,
                    ArticulatedLinkDesc* d, std::string* problem) {
  if (!placement.collisions) return true;
  for (const urdf::CollisionSharedPtr& c : link.collision_array) {
    if (!c || !c->geometry) continue;
    LinkShapeDesc shape;
    if (!ReadGeometry(*c->geometry, placement, &shape.shape, problem)) return false;
    const RigidPose at = PoseOf(c->origin);
    shape.position = at.p;
    shape.orientation = Eigen::Quaterniond(at.R);
    shape.contact = placement.contact;
    shape.colliderType = placement.colliderType;
    shape.boundaryElementType = placement.boundaryElementType;
    d->shapes.push_back(std::move(shape));
  }
  return true;
}

bool Fail(Error* error, const std::string& source, const std::string& what,
          const std::string& problem) {
  if (error) error->message = source + ": " + what + ": " + problem;
  return false;
}

}  // namespace

bool ReadUrdf(const std::string& text, const std::string& source, const UrdfPlacement& placement,
              ArticulatedActorDesc* out, Error* error) {
  urdf::ModelInterfaceSharedPtr model;
  std::string parseError;
  {
    static std::mutex handlerMutex;  // the parser's output handler is process-wide
    std::lock_guard<std::mutex> lock(handlerMutex);
    CollectErrors errors;
    console_bridge::useOutputHandler(&errors);
    model = urdf::parseURDF(text);
    console_bridge::restorePreviousOutputHandler();
    parseError = errors.message;
  }
  if (!model)
    return Fail(error, source, "not a valid URDF",
                parseError.empty() ? std::string("the parser refused it") : parseError);
  ArticulatedActorDesc d;
  d.name = model->getName();
  // Parents first: breadth first from the root.
  std::vector<urdf::LinkConstSharedPtr> order{model->getRoot()};
  std::map<std::string, int> index;
  for (size_t k = 0; k < order.size(); ++k) {
    index[order[k]->name] = static_cast<int>(k);
    for (const urdf::LinkSharedPtr& child : order[k]->child_links) order.push_back(child);
  }
  std::map<std::string, int> dofOfJoint;  // 1-dof joints: their link index
  for (size_t k = 0; k < order.size(); ++k) {
    const urdf::Link& link = *order[k];
    ArticulatedLinkDesc l;
    std::string problem;
    if (!ReadInertial(link, &l, &problem) || !ReadCollisions(link, placement, &l, &problem))
      return Fail(error, source, "link '" + link.name + "'", problem);
    if (k == 0) {
      l.joint.type = placement.freeBase ? JointType::Free : JointType::Fixed;
      l.joint.origin = placement.base;
    } else {
      const urdf::Joint& j = *link.parent_joint;
      if (!ReadJoint(j, &l, &problem)) return Fail(error, source, "joint '" + j.name + "'", problem);
      l.joint.parent = index.at(j.parent_link_name);
      if (l.joint.type != JointType::Fixed) dofOfJoint[j.name] = static_cast<int>(k);
      if (auto p = placement.jointParams.find(j.name); p != placement.jointParams.end())
        l.jointParams = p->second;
    }
    d.links.push_back(l);
  }
  // Initial values by joint name.
  for (const auto* values : {&placement.jointPositions, &placement.jointVelocities})
    for (const auto& [name, value] : *values)
      if (!dofOfJoint.count(name))
        return Fail(error, source, "joint '" + name + "'",
                    "no revolute, continuous or prismatic joint of that name");
  for (const auto& [name, p] : placement.jointParams)
    if (!dofOfJoint.count(name))
      return Fail(error, source, "joint '" + name + "'",
                  "no revolute, continuous or prismatic joint of that name");
  const KinematicTree tree([&] {
    std::vector<KinematicJoint> joints;
    for (const ArticulatedLinkDesc& l : d.links) joints.push_back(l.joint);
    return joints;
  }());
  d.jointPositions = tree.ZeroConfiguration();
  d.jointVelocities = Eigen::VectorXd::Zero(tree.NumTangentDofs());
  for (const auto& [name, value] : placement.jointPositions)
    d.jointPositions[tree.CoordinateOffset(dofOfJoint[name])] = value;
  for (const auto& [name, value] : placement.jointVelocities)
    d.jointVelocities[tree.TangentOffset(dofOfJoint[name])] = value;
  *out = std::move(d);
  return true;
}

bool ReadUrdfFile(const std::string& path, const UrdfPlacement& placement,
                  ArticulatedActorDesc* out, Error* error) {
  std::ifstream in(path);
  if (!in) {
    if (error) error->message = path + ": cannot open the URDF file";
    return false;
  }
  std::stringstream text;
  text << in.rdbuf();
  UrdfPlacement withMeshes = placement;
  if (withMeshes.meshDirectory.empty())
    withMeshes.meshDirectory = std::filesystem::path(path).parent_path().string();
  return ReadUrdf(text.str(), path, withMeshes, out, error);
}

}  // namespace superdex
