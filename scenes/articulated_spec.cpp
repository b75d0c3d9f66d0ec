// Reading an articulated actor of a scene file (articulated_spec.h).
#include "scenes/articulated_spec.h"

#include <filesystem>
#include <vector>

#include "core/model/rigid_math.h"
#include "scenes/shape_spec.h"
#include "scenes/urdf_reader.h"

namespace superdex::scene_json {
namespace {

// A joint target: a constant number or keyframes [[t, x], ...] (absent: none).
ScalarKeyframes ReadScalarKeyframes(const json& obj, const std::string& path, const char* key) {
  ScalarKeyframes out;
  if (!obj.contains(key)) return out;
  const json& v = obj.at(key);
  if (v.is_number()) {
    out.push_back({0.0, Number(obj, path, key)});
    return out;
  }
  const char* rule = "must be a number or keyframes [[t, x], ...]";
  ForEachItem(obj, path, key, rule, [&](const json& f, const std::string& fp) {
    if (!f.is_array() || f.size() != 2 || !f[0].is_number() || !f[1].is_number()) Throw(fp, rule);
    out.push_back({f[0].get<double>(), f[1].get<double>()});
  });
  return out;
}

JointParams ReadJointParams(const json& p, const std::string& pp) {
  JointParams params;
  ReadFields(p, pp, kJointParamsFields, &params, {"drive_target_position", "drive_target_velocity"});
  params.driveTargetPosition = ReadScalarKeyframes(p, pp, "drive_target_position");
  params.driveTargetVelocity = ReadScalarKeyframes(p, pp, "drive_target_velocity");
  return params;
}

// "inertia": [Ixx, Iyy, Izz] (principal, in the link frame) or [[...], [...], [...]].
Eigen::Matrix3d ReadInertia(const json& l, const std::string& path) {
  if (!l.contains("inertia")) Throw(Join(path, "inertia"), "missing required field");
  const json& v = l.at("inertia");
  if (v.is_array() && v.size() == 3 && v[0].is_number())
    return Vector<3>(l, path, "inertia", Eigen::Vector3d::Zero()).asDiagonal();
  const char* rule = "must be [Ixx, Iyy, Izz] or a 3 x 3 matrix [[...], [...], [...]] (kg·m²)";
  if (!v.is_array() || v.size() != 3) Throw(Join(path, "inertia"), rule);
  Eigen::Matrix3d I;
  for (int r = 0; r < 3; ++r) {
    if (!v[r].is_array() || v[r].size() != 3) Throw(Join(path, "inertia"), rule);
    for (int c = 0; c < 3; ++c) {
      if (!v[r][c].is_number()) Throw(Join(path, "inertia"), rule);
      I(r, c) = v[r][c].get<double>();
    }
  }
  return I;
}

// The link's joint coordinates and tangent velocity (KinematicTree layout) into q and u.
void ReadJointState(const json& l, const std::string& path, JointType type, Eigen::VectorXd* q,
                    Eigen::VectorXd* u) {
  const bool axial = type == JointType::Revolute || type == JointType::Prismatic;
  const bool turning = type == JointType::Spherical || type == JointType::Free;
  for (const char* key : {"position", "velocity"})
    if (l.contains(key) && !(axial || type == JointType::Free))
      Throw(Join(path, key), std::string("a ") + ToString(type) + " joint has no " + key);
  for (const char* key : {"euler_deg", "orientation", "angular_velocity"})
    if (l.contains(key) && !turning)
      Throw(Join(path, key), std::string("a ") + ToString(type) + " joint has no rotation");
  if (axial) {
    *q = Eigen::VectorXd::Constant(1, Number(l, path, "position", 0.0));
    *u = Eigen::VectorXd::Constant(1, Number(l, path, "velocity", 0.0));
    return;
  }
  q->setZero(JointCoordinates(type));
  u->setZero(JointTangentDofs(type));
  if (!turning) return;
  const int r = JointRotationOffset(type);
  Matrix3At(q, r) = ReadOrientation(l, path).normalized().toRotationMatrix();
  u->segment<3>(r) = Vector<3>(l, path, "angular_velocity", Eigen::Vector3d::Zero());
  if (type == JointType::Free) {
    q->head<3>() = Point(l, path, "position", Eigen::Vector3d::Zero());
    u->head<3>() = Vector<3>(l, path, "velocity", Eigen::Vector3d::Zero());
  }
}

// A link's collision shape: {"name", "shape", "position", "euler_deg" | "orientation" (in the
// link frame), "contact", "collider_type", "boundary_element_type", "surface_integral",
// "grid_sdf"}.
LinkShapeDesc ReadLinkShape(const json& j, const std::string& path, const std::string& baseDir) {
  CheckObject(j, path,
              {"name", "shape", "position", "euler_deg", "orientation", "contact",
               "collider_type", "boundary_element_type", "surface_integral", "grid_sdf"});
  LinkShapeDesc d;
  d.name = String(j, path, "name", std::string());
  if (!j.contains("shape")) Throw(Join(path, "shape"), "missing required field");
  d.shape = ReadShape(j.at("shape"), Join(path, "shape"), baseDir);
  d.position = Point(j, path, "position", Eigen::Vector3d::Zero());
  d.orientation = ReadOrientation(j, path);
  if (j.contains("contact")) d.contact = ReadContact(j.at("contact"), Join(path, "contact"));
  d.colliderType = Enum(j, path, "collider_type", ColliderType::Auto);
  d.boundaryElementType = Enum(j, path, "boundary_element_type", ActorBoundaryElementType::P1Q3);
  d.surfaceIntegral = Enum(j, path, "surface_integral", SurfaceIntegral::Quadrature);
  if (j.contains("grid_sdf")) d.gridSdf = ReadGridSdf(j.at("grid_sdf"), Join(path, "grid_sdf"));
  return d;
}

ArticulatedLinkDesc ReadLink(const json& l, const std::string& path,
                             const std::vector<std::string>& earlier, const std::string& baseDir) {
  CheckObject(l, path,
              {"name", "parent", "joint", "origin", "axis", "mass", "center_of_mass", "inertia",
               "position", "velocity", "euler_deg", "orientation", "angular_velocity",
               "joint_params", "shapes"});
  ArticulatedLinkDesc d;
  d.name = String(l, path, "name");
  if (l.contains("parent")) {
    const std::string p = String(l, path, "parent");
    for (size_t k = 0; k < earlier.size(); ++k)
      if (earlier[k] == p) d.joint.parent = static_cast<int>(k);
    if (d.joint.parent < 0) Throw(Join(path, "parent"), "no earlier link named \"" + p + "\"");
  }
  if (!l.contains("joint")) Throw(Join(path, "joint"), "missing required field");
  d.joint.type = Enum(l, path, "joint", JointType::Revolute);
  if (l.contains("origin")) {
    const json& o = l.at("origin");
    const std::string op = Join(path, "origin");
    CheckObject(o, op, {"position", "euler_deg", "orientation"});
    d.joint.origin.p = Point(o, op, "position", Eigen::Vector3d::Zero());
    d.joint.origin.R = ReadOrientation(o, op).normalized().toRotationMatrix();
  }
  const bool axial = d.joint.type == JointType::Revolute || d.joint.type == JointType::Prismatic;
  if (axial && !l.contains("axis")) Throw(Join(path, "axis"), "missing required field");
  if (!axial && l.contains("axis"))
    Throw(Join(path, "axis"), std::string("a ") + ToString(d.joint.type) + " joint has no axis");
  if (axial) {
    const Eigen::Vector3d axis = Vector<3>(l, path, "axis", Eigen::Vector3d::Zero());
    if (!(axis.norm() > 0.0)) Throw(Join(path, "axis"), "must be a non-zero vector");
    d.joint.axis = axis.normalized();
  }
  d.mass = Number(l, path, "mass");
  d.centerOfMass = Point(l, path, "center_of_mass", Eigen::Vector3d::Zero());
  d.inertia = ReadInertia(l, path);
  if (l.contains("joint_params"))
    d.jointParams = ReadJointParams(l.at("joint_params"), Join(path, "joint_params"));
  if (l.contains("shapes"))
    ForEachItem(l, path, "shapes", "must be an array of shapes",
                [&](const json& j, const std::string& jp) {
                  d.shapes.push_back(ReadLinkShape(j, jp, baseDir));
                });
  return d;
}

// {"joint name": number, ...}
std::map<std::string, double> ReadNamedNumbers(const json& a, const std::string& path,
                                               const char* key) {
  std::map<std::string, double> out;
  if (!a.contains(key)) return out;
  const json& m = a.at(key);
  if (!m.is_object()) Throw(Join(path, key), "must be an object {\"joint name\": number, ...}");
  for (auto it = m.begin(); it != m.end(); ++it) out[it.key()] = Number(m, Join(path, key), it.key().c_str());
  return out;
}

ArticulatedActorDesc ReadUrdfActor(const json& a, const std::string& path,
                                   const std::string& baseDir) {
  CheckObject(a, path,
              {"name", "type", "urdf", "base", "position", "euler_deg", "orientation",
               "joint_positions", "joint_velocities", "joint_params", "contact_layer", "parent",
               "collisions", "contact", "collider_type", "boundary_element_type",
               "sample_spacing", "cylinders"});
  UrdfPlacement placement;
  const std::string base = String(a, path, "base", std::string("fixed"));
  if (base != "fixed" && base != "free")
    Throw(Join(path, "base"), "must be \"fixed\" or \"free\", got \"" + base + "\"");
  placement.freeBase = base == "free";
  placement.base.p = Point(a, path, "position", Eigen::Vector3d::Zero());
  placement.base.R = ReadOrientation(a, path).normalized().toRotationMatrix();
  placement.collisions = Bool(a, path, "collisions", true);
  if (a.contains("contact")) placement.contact = ReadContact(a.at("contact"), Join(path, "contact"));
  placement.colliderType = Enum(a, path, "collider_type", ColliderType::Auto);
  placement.boundaryElementType =
      Enum(a, path, "boundary_element_type", ActorBoundaryElementType::P1Q3);
  placement.sampleSpacing = Length(a, path, "sample_spacing", 0.01);
  const std::string cylinders = String(a, path, "cylinders", std::string("mesh"));
  if (cylinders != "mesh" && cylinders != "capsule")
    Throw(Join(path, "cylinders"), "must be \"mesh\" or \"capsule\", got \"" + cylinders + "\"");
  placement.cylindersAsCapsules = cylinders == "capsule";
  placement.jointPositions = ReadNamedNumbers(a, path, "joint_positions");
  placement.jointVelocities = ReadNamedNumbers(a, path, "joint_velocities");
  if (a.contains("joint_params")) {
    const json& m = a.at("joint_params");
    const std::string mp = Join(path, "joint_params");
    if (!m.is_object()) Throw(mp, "must be an object {\"joint name\": {...}, ...}");
    for (auto it = m.begin(); it != m.end(); ++it)
      placement.jointParams[it.key()] = ReadJointParams(it.value(), Join(mp, it.key()));
  }
  const std::string file = String(a, path, "urdf");
  const std::filesystem::path full = std::filesystem::path(baseDir) / file;
  ArticulatedActorDesc d;
  Error error;
  if (!ReadUrdfFile(full.string(), placement, &d, &error))
    Throw(Join(path, "urdf"), error.message);
  d.name = String(a, path, "name");
  return d;
}

}  // namespace

ArticulatedActorDesc ReadArticulatedDesc(const json& a, const std::string& path,
                                         const std::string& baseDir) {
  if (a.contains("urdf")) return ReadUrdfActor(a, path, baseDir);
  CheckObject(a, path, {"name", "type", "links", "contact_layer", "parent"});
  ArticulatedActorDesc d;
  d.name = String(a, path, "name");
  if (!a.contains("links")) Throw(Join(path, "links"), "missing required field");
  std::vector<std::string> names;
  std::vector<Eigen::VectorXd> q, u;
  ForEachItem(a, path, "links", "must be an array of links", [&](const json& l, const std::string& lp) {
    d.links.push_back(ReadLink(l, lp, names, baseDir));
    for (const std::string& n : names)
      if (n == d.links.back().name) Throw(Join(lp, "name"), "duplicate link name \"" + n + "\"");
    names.push_back(d.links.back().name);
    q.emplace_back();
    u.emplace_back();
    ReadJointState(l, lp, d.links.back().joint.type, &q.back(), &u.back());
  });
  Eigen::Index nq = 0, nu = 0;
  for (size_t k = 0; k < q.size(); ++k) nq += q[k].size(), nu += u[k].size();
  d.jointPositions.resize(nq);
  d.jointVelocities.resize(nu);
  nq = nu = 0;
  for (size_t k = 0; k < q.size(); ++k) {
    d.jointPositions.segment(nq, q[k].size()) = q[k];
    d.jointVelocities.segment(nu, u[k].size()) = u[k];
    nq += q[k].size();
    nu += u[k].size();
  }
  return d;
}

}  // namespace superdex::scene_json
