// Reading shapes, contact parameters and grid SDF settings (shape_spec.h).
#include "scenes/shape_spec.h"

#include <memory>

#include "geometry/mesh_io.h"
#include "scenes/limits.h"

namespace superdex::scene_json {

ContactParams ReadContact(const json& j, const std::string& path) {
  ContactParams c;
  ReadFields(j, path, kContactParamsFields, &c);
  return c;
}

RigidShape ReadShape(const json& j, const std::string& path, const std::string& baseDir) {
  RigidShape s;
  if (!j.is_object()) Throw(path, std::string("must be an object, got ") + TypeName(j));
  const std::string type = String(j, path, "type");
  if (type == "sphere") {
    CheckObject(j, path, {"type", "radius", "surface_resolution"});
    s.kind = RigidShapeKind::Sphere;
    s.radius = Length(j, path, "radius");
    s.surfaceResolution = Integer(j, path, "surface_resolution", 3, 0, 7);
  } else if (type == "box") {
    CheckObject(j, path, {"type", "half_extents", "size", "surface_resolution"});
    s.kind = RigidShapeKind::Box;
    if (j.contains("size") == j.contains("half_extents"))
      Throw(path, "give exactly one of \"size\" and \"half_extents\"");
    const bool full = j.contains("size");
    const Eigen::Vector3d e = Point(j, path, full ? "size" : "half_extents", Eigen::Vector3d::Zero());
    if (!(e.minCoeff() > 0)) Throw(Join(path, full ? "size" : "half_extents"), "must be > 0");
    s.halfExtents = full ? 0.5 * e : e;
    s.surfaceResolution = Integer(j, path, "surface_resolution", 2, 1, 64);
  } else if (type == "capsule") {
    CheckObject(j, path, {"type", "radius", "half_length", "length", "surface_resolution"});
    s.kind = RigidShapeKind::Capsule;
    s.radius = Length(j, path, "radius");
    if (j.contains("length") == j.contains("half_length"))
      Throw(path, "give exactly one of \"length\" and \"half_length\" (of the straight part)");
    s.halfLength = j.contains("length") ? 0.5 * Length(j, path, "length")
                                        : Length(j, path, "half_length");
    s.surfaceResolution = Integer(j, path, "surface_resolution", 8, 1, 32);
  } else if (type == "plane") {
    CheckObject(j, path, {"type", "normal"});
    s.kind = RigidShapeKind::Plane;
    s.planeNormal = Vector<3>(j, path, "normal", Eigen::Vector3d::UnitZ());
    if (!(s.planeNormal.norm() > 0)) Throw(Join(path, "normal"), "must be a non-zero vector");
  } else if (type == "mesh") {
    CheckObject(j, path, {"type", "file", "scale"});
    s.kind = RigidShapeKind::Mesh;
    std::string file = String(j, path, "file");
    if (!file.empty() && file[0] != '/' && !baseDir.empty()) file = baseDir + "/" + file;
    auto mesh = std::make_shared<TriangleMesh>();
    std::string err;
    if (!ReadMeshFile(file, mesh.get(), &err)) Throw(Join(path, "file"), err);
    const double scale = Positive(j, path, "scale", 1.0);
    for (auto& v : mesh->vertices) v *= scale;
    CheckCoordinates(mesh->vertices, Join(path, j.contains("scale") ? "scale" : "file"));
    s.mesh = mesh;
    s.meshSource = file;
  } else {
    Throw(Join(path, "type"), "unknown value \"" + type + "\" (expected one of: sphere, box, capsule, plane, mesh)");
  }
  return s;
}

GridSdfParams ReadGridSdf(const json& g, const std::string& gp) {
  GridSdfParams d;
  ReadFields(g, gp, kGridSdfFields, &d);
  if (std::string m = Validate(d, gp + "."); !m.empty()) throw LoadError{m};
  if (d.boundaryPaddingDist > limits::kMaxLength)
    Throw(Join(gp, "boundary_padding_dist"), TooLarge(d.boundaryPaddingDist));
  return d;
}

}  // namespace superdex::scene_json
