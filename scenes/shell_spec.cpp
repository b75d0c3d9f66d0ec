#include "scenes/shell_spec.h"

#include <memory>

#include "geometry/mesh_io.h"
#include "scenes/shape_spec.h"
#include "scenes/soft_mesh_spec.h"

namespace superdex::scene_json {
namespace {

std::shared_ptr<TriangleMesh> ReadShellMesh(const json& j, const std::string& path,
                                            const std::string& baseDir, std::string* source) {
  if (!j.is_object()) Throw(path, "must be an object");
  const std::string type = String(j, path, "type");
  auto mesh = std::make_shared<TriangleMesh>();
  if (type == "file") {
    CheckObject(j, path, {"type", "file", "scale"});
    std::string file = String(j, path, "file");
    if (!file.empty() && file[0] != '/' && !baseDir.empty()) file = baseDir + "/" + file;
    std::string err;
    if (!ReadMeshFile(file, mesh.get(), &err)) Throw(Join(path, "file"), err);
    const double scale = Positive(j, path, "scale", 1.0);
    for (auto& v : mesh->vertices) v *= scale;
    CheckCoordinates(mesh->vertices, Join(path, j.contains("scale") ? "scale" : "file"));
    *source = file;
  } else if (type == "rectangle") {
    CheckObject(j, path, {"type", "size", "cells"});
    const Eigen::Vector2d size = Vector<2>(j, path, "size", Eigen::Vector2d::Ones());
    if (!(size.minCoeff() > 0.0)) Throw(Join(path, "size"), "must be > 0 in both components");
    const Eigen::Vector2d cells = Vector<2>(j, path, "cells", Eigen::Vector2d(10, 10));
    if (!(cells.minCoeff() >= 1.0 && cells.maxCoeff() <= 1000.0) || cells != cells.array().round().matrix())
      Throw(Join(path, "cells"), "must be two integers in [1, 1000]");
    *mesh = MakeRectangleMesh(-0.5 * size, 0.5 * size, cells.cast<int>());
    *source = "rectangle";
  } else if (type == "disk") {
    CheckObject(j, path, {"type", "radius", "rings"});
    const double radius = Positive(j, path, "radius", 0.5);
    const int rings = Integer(j, path, "rings", 8, 1, 500);
    *mesh = MakeDiskMesh(radius, rings);
    *source = "disk";
  } else if (type == "annulus") {
    CheckObject(j, path, {"type", "inner_radius", "outer_radius", "angle_deg", "cells"});
    const double inner = Positive(j, path, "inner_radius", 0.25);
    const double outer = Positive(j, path, "outer_radius", 0.5);
    if (!(outer > inner)) Throw(Join(path, "outer_radius"), "must be > inner_radius");
    const double angle = Positive(j, path, "angle_deg", 360.0);
    if (angle > 360.0) Throw(Join(path, "angle_deg"), "must be in (0, 360]");
    const Eigen::Vector2d cells = Vector<2>(j, path, "cells", Eigen::Vector2d(4, 32));
    if (!(cells.minCoeff() >= 1.0 && cells.maxCoeff() <= 1000.0) || cells != cells.array().round().matrix())
      Throw(Join(path, "cells"), "must be two integers in [1, 1000]");
    *mesh = MakeAnnulusMesh(inner, outer, angle * M_PI / 180.0, cells.cast<int>());
    *source = "annulus";
  } else {
    Throw(Join(path, "type"),
          "unknown value \"" + type + "\" (expected one of: file, rectangle, disk, annulus)");
  }
  return mesh;
}

}  // namespace

ShellActorDesc ReadShellDesc(const json& a, const std::string& path, const std::string& baseDir) {
  CheckObject(a, path,
              {"name", "type", "mesh", "material", "bending", "position", "orientation",
               "euler_deg", "velocity", "contact", "contact_element_type", "collider_type",
               "point_cloud", "contact_layer", "parent", "constraints", "loads", "clamped"});
  ShellActorDesc d;
  d.name = String(a, path, "name");
  if (!a.contains("mesh")) Throw(Join(path, "mesh"), "missing required field");
  d.mesh = ReadShellMesh(a.at("mesh"), Join(path, "mesh"), baseDir, &d.meshSource);
  if (a.contains("material"))
    ReadFields(a.at("material"), Join(path, "material"), kShellMaterialFields, &d.material);
  d.bending = Enum(a, path, "bending", ShellBendingModel::Midedge);
  d.position = Point(a, path, "position", Eigen::Vector3d::Zero());
  d.orientation = ReadOrientation(a, path);
  d.linearVelocity = Vector<3>(a, path, "velocity", Eigen::Vector3d::Zero());
  if (a.contains("contact")) d.contact = ReadContact(a.at("contact"), Join(path, "contact"));
  d.contactElementType = Enum(a, path, "contact_element_type", ActorBoundaryElementType::P1Q3);
  d.colliderType = Enum(a, path, "collider_type", ColliderType::Auto);
  if (a.contains("point_cloud"))
    ReadFields(a.at("point_cloud"), Join(path, "point_cloud"), kPointCloudColliderFields,
               &d.pointCloud);
  d.contactLayer = String(a, path, "contact_layer", std::string("default"));
  if (a.contains("constraints"))
    d.constraints = ReadConstraints(a.at("constraints"), Join(path, "constraints"), *d.mesh,
                                    d.position, d.orientation);
  if (a.contains("loads"))
    d.loads = ReadNodeLoads(a.at("loads"), Join(path, "loads"), *d.mesh, d.position, d.orientation);
  if (a.contains("clamped")) {  // nodes or regions, without paths
    const std::string cp = Join(path, "clamped");
    const std::vector<NodeConstraint> clamped =
        ReadConstraints(a.at("clamped"), cp, *d.mesh, d.position, d.orientation);
    for (size_t i = 0; i < clamped.size(); ++i) {
      if (!clamped[i].path.empty())
        Throw(cp + "[" + std::to_string(i) + "].path", "a clamped edge does not move");
      d.clampedNodes.insert(d.clampedNodes.end(), clamped[i].nodes.begin(), clamped[i].nodes.end());
    }
  }
  return d;
}

}  // namespace superdex::scene_json
