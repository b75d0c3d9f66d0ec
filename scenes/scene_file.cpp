#include "scenes/scene_file.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>

#include "geometry/mesh_io.h"
#include "geometry/tet_mesh.h"

namespace superdex {
namespace {

using json = nlohmann::json;

// Internal only: loading stops at the first problem; LoadSceneText turns it into an Error.
struct LoadError {
  std::string message;
};
[[noreturn]] void Throw(const std::string& path, const std::string& rule) {
  throw LoadError{path + ": " + rule};
}

std::string Join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

const char* TypeName(const json& j) { return j.type_name(); }

void CheckObject(const json& j, const std::string& path, std::set<std::string> known) {
  if (!j.is_object()) Throw(path.empty() ? "(top level)" : path, std::string("must be an object, got ") + TypeName(j));
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!known.count(it.key())) Throw(Join(path, it.key()), "unknown field");
}

double Number(const json& obj, const std::string& path, const char* key,
              std::optional<double> def = std::nullopt) {
  const std::string p = Join(path, key);
  if (!obj.contains(key)) {
    if (def) return *def;
    Throw(p, "missing required field");
  }
  const json& v = obj.at(key);
  if (!v.is_number()) Throw(p, std::string("must be a number, got ") + TypeName(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) Throw(p, "must be finite");
  return x;
}

double Positive(const json& obj, const std::string& path, const char* key,
                std::optional<double> def = std::nullopt) {
  const double x = Number(obj, path, key, def);
  if (!(x > 0)) {
    std::ostringstream s;
    s << "must be > 0, got " << x;
    Throw(Join(path, key), s.str());
  }
  return x;
}

int Integer(const json& obj, const std::string& path, const char* key, int def, int lo, int hi) {
  const std::string p = Join(path, key);
  if (!obj.contains(key)) return def;
  const json& v = obj.at(key);
  if (!v.is_number_integer()) Throw(p, std::string("must be an integer, got ") + TypeName(v));
  const long long x = v.get<long long>();
  if (x < lo || x > hi) {
    std::ostringstream s;
    s << "must be in [" << lo << ", " << hi << "], got " << x;
    Throw(p, s.str());
  }
  return static_cast<int>(x);
}

bool Bool(const json& obj, const std::string& path, const char* key, bool def) {
  if (!obj.contains(key)) return def;
  const json& v = obj.at(key);
  if (!v.is_boolean()) Throw(Join(path, key), std::string("must be true or false, got ") + TypeName(v));
  return v.get<bool>();
}

std::string String(const json& obj, const std::string& path, const char* key,
                   std::optional<std::string> def = std::nullopt) {
  if (!obj.contains(key)) {
    if (def) return *def;
    Throw(Join(path, key), "missing required field");
  }
  const json& v = obj.at(key);
  if (!v.is_string()) Throw(Join(path, key), std::string("must be a string, got ") + TypeName(v));
  return v.get<std::string>();
}

template <int N>
Eigen::Matrix<double, N, 1> Vector(const json& obj, const std::string& path, const char* key,
                                   const Eigen::Matrix<double, N, 1>& def) {
  if (!obj.contains(key)) return def;
  const json& v = obj.at(key);
  const std::string p = Join(path, key);
  if (!v.is_array() || v.size() != N)
    Throw(p, "must be an array of " + std::to_string(N) + " numbers");
  Eigen::Matrix<double, N, 1> out;
  for (int i = 0; i < N; ++i) {
    if (!v[i].is_number()) Throw(p + "[" + std::to_string(i) + "]", "must be a number");
    out[i] = v[i].get<double>();
    if (!std::isfinite(out[i])) Throw(p + "[" + std::to_string(i) + "]", "must be finite");
  }
  return out;
}

template <typename E>
E Enum(const json& obj, const std::string& path, const char* key, E def) {
  if (!obj.contains(key)) return def;
  const std::string s = String(obj, path, key);
  E e;
  if (!Parse(s, &e)) Throw(Join(path, key), "unknown value \"" + s + "\" (expected one of: " + AllNames(def) + ")");
  return e;
}

// Reads the fields of a parameter table (optim/field_table.h) from the object j: the keys are the
// rows' names, an absent key keeps the value in *out, any other key is refused. The rules are
// checked where the struct is validated (Validate, Scene::Add...Actor), except integers' range.
template <typename Table, typename Class>
void ReadFields(const json& j, const std::string& path, const Table& table, Class* out) {
  std::set<std::string> known;
  ForEachField(table, [&](const auto& f) { known.insert(f.name); });
  CheckObject(j, path, known);
  ForEachField(table, [&](const auto& f) {
    using T = typename std::decay_t<decltype(f)>::ValueType;
    T& v = f.Of(*out);
    if constexpr (std::is_same_v<T, bool>) {
      v = Bool(j, path, f.name, v);
    } else if constexpr (std::is_enum_v<T>) {
      v = Enum(j, path, f.name, v);
    } else if constexpr (std::is_same_v<T, int>) {
      const int lo = f.rule.kind == Rule::AtLeast ? static_cast<int>(f.rule.lo) : INT_MIN;
      const int hi = f.rule.fileMax > 0
                         ? static_cast<int>(std::min<long long>(f.rule.fileMax, INT_MAX))
                         : INT_MAX;
      v = Integer(j, path, f.name, v, lo, hi);
    } else if constexpr (std::is_same_v<T, double>) {
      v = Number(j, path, f.name, v);
    } else {
      static_assert(sizeof(T) == 0, "no scene-file reader for this field type");
    }
  });
}

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
    s.radius = Positive(j, path, "radius");
    s.surfaceResolution = Integer(j, path, "surface_resolution", 3, 0, 7);
  } else if (type == "box") {
    CheckObject(j, path, {"type", "half_extents", "size", "surface_resolution"});
    s.kind = RigidShapeKind::Box;
    if (j.contains("size") == j.contains("half_extents"))
      Throw(path, "give exactly one of \"size\" and \"half_extents\"");
    const bool full = j.contains("size");
    const Eigen::Vector3d e = Vector<3>(j, path, full ? "size" : "half_extents", Eigen::Vector3d::Zero());
    if (!(e.minCoeff() > 0)) Throw(Join(path, full ? "size" : "half_extents"), "must be > 0");
    s.halfExtents = full ? 0.5 * e : e;
    s.surfaceResolution = Integer(j, path, "surface_resolution", 2, 1, 64);
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
    s.mesh = mesh;
    s.meshSource = file;
  } else {
    Throw(Join(path, "type"), "unknown value \"" + type + "\" (expected one of: sphere, box, plane, mesh)");
  }
  return s;
}

Eigen::Quaterniond ReadOrientation(const json& j, const std::string& path) {
  if (j.contains("orientation") && j.contains("euler_deg"))
    Throw(path, "give at most one of \"orientation\" and \"euler_deg\"");
  if (j.contains("euler_deg")) {
    const Eigen::Vector3d e = Vector<3>(j, path, "euler_deg", Eigen::Vector3d::Zero()) * M_PI / 180.0;
    return Eigen::AngleAxisd(e.z(), Eigen::Vector3d::UnitZ()) *
           Eigen::AngleAxisd(e.y(), Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(e.x(), Eigen::Vector3d::UnitX());
  }
  const Eigen::Vector4d q = Vector<4>(j, path, "orientation", Eigen::Vector4d(0, 0, 0, 1));
  if (!(q.norm() > 0)) Throw(Join(path, "orientation"), "must be a non-zero quaternion [x, y, z, w]");
  return Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized();
}

GridSdfParams ReadGridSdf(const json& g, const std::string& gp) {
  GridSdfParams d;
  ReadFields(g, gp, kGridSdfFields, &d);
  if (std::string m = Validate(d, gp + "."); !m.empty()) throw LoadError{m};
  return d;
}

// A soft actor's tet mesh: {"type": "file", "file": F (.msh, .node/.ele), "scale"},
// {"type": "box", "half_extents" | "size", "cells": [nx, ny, nz]},
// {"type": "sphere", "radius", "edge_length"} or {"type": "surface", "file": F (closed surface
// mesh), "edge_length", "scale"} (tetrahedralized by CGAL's Mesh_3).
std::shared_ptr<TetMesh> ReadTetMeshSpec(const json& j, const std::string& path,
                                         const std::string& baseDir, std::string* source) {
  if (!j.is_object()) Throw(path, std::string("must be an object, got ") + TypeName(j));
  auto mesh = std::make_shared<TetMesh>();
  const std::string type = String(j, path, "type");
  auto resolve = [&](std::string file) {
    if (!file.empty() && file[0] != '/' && !baseDir.empty()) file = baseDir + "/" + file;
    return file;
  };
  if (type == "file") {
    CheckObject(j, path, {"type", "file", "scale"});
    const std::string file = resolve(String(j, path, "file"));
    std::string err;
    if (!ReadTetMeshFile(file, mesh.get(), &err)) Throw(Join(path, "file"), err);
    const double scale = Positive(j, path, "scale", 1.0);
    for (auto& v : mesh->vertices) v *= scale;
    *source = file;
  } else if (type == "box") {
    CheckObject(j, path, {"type", "half_extents", "size", "cells"});
    if (j.contains("size") == j.contains("half_extents"))
      Throw(path, "give exactly one of \"size\" and \"half_extents\"");
    const bool full = j.contains("size");
    const Eigen::Vector3d e =
        Vector<3>(j, path, full ? "size" : "half_extents", Eigen::Vector3d::Zero());
    if (!(e.minCoeff() > 0)) Throw(Join(path, full ? "size" : "half_extents"), "must be > 0");
    const Eigen::Vector3d c = Vector<3>(j, path, "cells", Eigen::Vector3d(4, 4, 4));
    Eigen::Vector3i cells;
    for (int k = 0; k < 3; ++k) {
      if (c[k] < 1 || c[k] > 200 || c[k] != std::floor(c[k]))
        Throw(Join(path, "cells"), "must hold integers in [1, 200]");
      cells[k] = static_cast<int>(c[k]);
    }
    *mesh = MakeTetBox(full ? Eigen::Vector3d(0.5 * e) : e, cells);
    *source = "tet box";
  } else if (type == "sphere") {
    CheckObject(j, path, {"type", "radius", "edge_length"});
    const double r = Positive(j, path, "radius");
    const double h = Positive(j, path, "edge_length");
    if (r / h > 60) Throw(Join(path, "edge_length"), "too small for the radius (radius/edge_length > 60)");
    *mesh = MakeTetSphere(r, h);
    if (mesh->NumTets() == 0) Throw(path, "meshing the sphere failed");
    *source = "tet sphere";
  } else if (type == "cylinder") {
    CheckObject(j, path, {"type", "radius", "length", "edge_length"});
    const double r = Positive(j, path, "radius");
    const double len = Positive(j, path, "length");
    const double h = Positive(j, path, "edge_length");
    if (std::max(r, len) / h > 60) Throw(Join(path, "edge_length"), "too small for the cylinder (size/edge_length > 60)");
    // The surface resolved at half the edge length, so the volume mesh follows it closely.
    const int segments = std::max(12, static_cast<int>(std::ceil(2 * M_PI * r / (0.5 * h))));
    const int rings = std::max(2, static_cast<int>(std::ceil(len / (0.5 * h))));
    std::string err;
    if (!MeshTetsFromSurface(MakeCylinderMesh(r, 0.5 * len, segments, rings), h, mesh.get(), &err))
      Throw(path, "meshing the cylinder failed: " + err);
    *source = "tet cylinder";
  } else if (type == "surface") {
    CheckObject(j, path, {"type", "file", "edge_length", "scale"});
    const std::string file = resolve(String(j, path, "file"));
    TriangleMesh surface;
    std::string err;
    if (!ReadMeshFile(file, &surface, &err)) Throw(Join(path, "file"), err);
    const double scale = Positive(j, path, "scale", 1.0);
    for (auto& v : surface.vertices) v *= scale;
    const double h = Positive(j, path, "edge_length");
    if (!MeshTetsFromSurface(surface, h, mesh.get(), &err)) Throw(path, file + ": " + err);
    *source = file;
  } else {
    Throw(Join(path, "type"), "unknown value \"" + type + "\" (expected one of: file, box, sphere, cylinder, surface)");
  }
  return mesh;
}

// "constraints": [{"nodes": [i, ...] | "region": {"min": [..], "max": [..]} (world coordinates at
// creation), "path": [[t, dx, dy, dz], ...] (omitted: pinned)}, ...]
std::vector<NodeConstraint> ReadConstraints(const json& list, const std::string& path,
                                            const TetMesh& mesh, const Eigen::Vector3d& position,
                                            const Eigen::Quaterniond& orientation) {
  if (!list.is_array()) Throw(path, "must be an array");
  std::vector<NodeConstraint> out;
  const Eigen::Matrix3d R = orientation.toRotationMatrix();
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string p = path + "[" + std::to_string(i) + "]";
    const json& c = list[i];
    CheckObject(c, p, {"nodes", "region", "path"});
    NodeConstraint k;
    if (c.contains("nodes") == c.contains("region"))
      Throw(p, "give exactly one of \"nodes\" and \"region\"");
    if (c.contains("nodes")) {
      const json& n = c.at("nodes");
      if (!n.is_array()) Throw(Join(p, "nodes"), "must be an array of node indices");
      for (const json& v : n) {
        if (!v.is_number_integer()) Throw(Join(p, "nodes"), "must be an array of node indices");
        k.nodes.push_back(v.get<int>());
      }
    } else {
      const json& r = c.at("region");
      const std::string rp = Join(p, "region");
      CheckObject(r, rp, {"min", "max"});
      const Eigen::Vector3d lo = Vector<3>(r, rp, "min", Eigen::Vector3d::Zero());
      const Eigen::Vector3d hi = Vector<3>(r, rp, "max", Eigen::Vector3d::Zero());
      for (int v = 0; v < mesh.NumVertices(); ++v) {
        const Eigen::Vector3d x = position + R * mesh.vertices[v];
        if ((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()) k.nodes.push_back(v);
      }
      if (k.nodes.empty()) Throw(rp, "selects no node");
    }
    if (c.contains("path")) {
      const json& kp = c.at("path");
      if (!kp.is_array()) Throw(Join(p, "path"), "must be an array of [t, dx, dy, dz]");
      for (const json& f : kp) {
        if (!f.is_array() || f.size() != 4) Throw(Join(p, "path"), "must be an array of [t, dx, dy, dz]");
        for (const json& v : f)
          if (!v.is_number()) Throw(Join(p, "path"), "must be an array of [t, dx, dy, dz]");
        k.path.push_back({f[0].get<double>(), Eigen::Vector3d(f[1].get<double>(), f[2].get<double>(),
                                                               f[3].get<double>())});
      }
    }
    out.push_back(std::move(k));
  }
  return out;
}

void ReadSoftActor(const json& a, const std::string& path, const std::string& baseDir,
                   ActorHandle parent, SceneFile* out) {
  CheckObject(a, path,
              {"name", "type", "mesh", "material", "position", "orientation", "euler_deg",
               "velocity", "contact", "collider_type", "boundary_element_type", "contact_layer",
               "parent", "constraints", "grid_sdf"});
  SoftActorDesc d;
  d.name = String(a, path, "name");
  if (!a.contains("mesh")) Throw(Join(path, "mesh"), "missing required field");
  d.mesh = ReadTetMeshSpec(a.at("mesh"), Join(path, "mesh"), baseDir, &d.meshSource);
  if (a.contains("material"))
    ReadFields(a.at("material"), Join(path, "material"), kSoftMaterialFields, &d.material);
  d.position = Vector<3>(a, path, "position", Eigen::Vector3d::Zero());
  d.orientation = ReadOrientation(a, path);
  d.linearVelocity = Vector<3>(a, path, "velocity", Eigen::Vector3d::Zero());
  if (a.contains("contact")) d.contact = ReadContact(a.at("contact"), Join(path, "contact"));
  d.colliderType = Enum(a, path, "collider_type", ColliderType::None);
  if (a.contains("grid_sdf")) d.gridSdf = ReadGridSdf(a.at("grid_sdf"), Join(path, "grid_sdf"));
  d.boundaryElementType = Enum(a, path, "boundary_element_type", ActorBoundaryElementType::P1Q3);
  d.contactLayer = String(a, path, "contact_layer", std::string("default"));
  if (a.contains("constraints"))
    d.constraints = ReadConstraints(a.at("constraints"), Join(path, "constraints"), *d.mesh,
                                    d.position, d.orientation);
  Error err;
  if (!out->scene->AddSoftActor(d, &err, parent).IsValid()) throw LoadError{path + "." + err.message};
  out->actorNames.push_back(d.name);
}

void ReadActors(const json& actors, const std::string& baseDir, SceneFile* out) {
  if (!actors.is_array()) Throw("actors", std::string("must be an array, got ") + TypeName(actors));
  std::set<std::string> names;
  for (size_t i = 0; i < actors.size(); ++i) {
    const std::string path = "actors[" + std::to_string(i) + "]";
    const json& a = actors[i];
    if (a.is_object() && a.contains("type") && a.at("type") == "soft") {
      ActorHandle parent;
      if (a.contains("parent")) {
        const std::string p = String(a, path, "parent");
        for (size_t k = 0; k < out->actorNames.size(); ++k)
          if (out->actorNames[k] == p) parent.index = static_cast<int>(k);
        if (!parent.IsValid()) Throw(Join(path, "parent"), "no earlier actor named \"" + p + "\"");
      }
      const std::string name = String(a, path, "name");
      if (!names.insert(name).second) Throw(Join(path, "name"), "duplicate actor name \"" + name + "\"");
      ReadSoftActor(a, path, baseDir, parent, out);
      continue;
    }
    CheckObject(a, path,
                {"name", "type", "dynamic", "shape", "density", "mass", "inertia", "position",
                 "orientation", "euler_deg", "velocity", "angular_velocity", "contact",
                 "collider_type", "boundary_element_type", "contact_layer", "parent", "grid",
                 "grid_sdf"});
    const std::string type = String(a, path, "type", std::string("rigid"));
    if (type != "rigid")
      Throw(Join(path, "type"), "unknown value \"" + type + "\" (supported: rigid, soft)");
    RigidActorDesc d;
    d.name = String(a, path, "name");
    d.dynamic = Bool(a, path, "dynamic", true);
    if (!a.contains("shape")) Throw(Join(path, "shape"), "missing required field");
    d.shape = ReadShape(a.at("shape"), Join(path, "shape"), baseDir);
    if (a.contains("density")) d.density = Positive(a, path, "density");
    if (a.contains("mass")) d.mass = Positive(a, path, "mass");
    if (a.contains("inertia")) {
      const Eigen::Vector3d I = Vector<3>(a, path, "inertia", Eigen::Vector3d::Zero());
      d.inertia = Eigen::Matrix3d(I.asDiagonal());
    }
    d.position = Vector<3>(a, path, "position", Eigen::Vector3d::Zero());
    d.orientation = ReadOrientation(a, path);
    d.linearVelocity = Vector<3>(a, path, "velocity", Eigen::Vector3d::Zero());
    d.angularVelocity = Vector<3>(a, path, "angular_velocity", Eigen::Vector3d::Zero());
    if (a.contains("contact")) d.contact = ReadContact(a.at("contact"), Join(path, "contact"));
    d.colliderType = Enum(a, path, "collider_type", ColliderType::Auto);
    d.boundaryElementType = Enum(a, path, "boundary_element_type", ActorBoundaryElementType::P1Q3);
    d.contactLayer = String(a, path, "contact_layer", std::string("default"));
    if (a.contains("grid_sdf")) d.gridSdf = ReadGridSdf(a.at("grid_sdf"), Join(path, "grid_sdf"));
    ActorHandle parent;
    if (a.contains("parent")) {
      const std::string p = String(a, path, "parent");
      for (size_t k = 0; k < out->actorNames.size(); ++k)
        if (out->actorNames[k] == p) parent.index = static_cast<int>(k);
      if (!parent.IsValid())
        Throw(Join(path, "parent"), "no earlier actor named \"" + p + "\"");
    }

    // Optional replication on a grid: count [nx, ny, nz], spacing [m], jitter [m] (uniform in
    // [−jitter, jitter] per axis, fixed seed), names "<name>_<k>".
    Eigen::Vector3i count(1, 1, 1);
    Eigen::Vector3d spacing = Eigen::Vector3d::Zero();
    double jitter = 0.0;
    const bool grid = a.contains("grid");
    if (grid) {
      const json& g = a.at("grid");
      const std::string gp = Join(path, "grid");
      CheckObject(g, gp, {"count", "spacing", "jitter", "seed"});
      const Eigen::Vector3d c = Vector<3>(g, gp, "count", Eigen::Vector3d::Ones());
      for (int k = 0; k < 3; ++k) {
        if (c[k] < 1 || c[k] > 1000 || c[k] != std::floor(c[k]))
          Throw(Join(gp, "count"), "must hold integers in [1, 1000]");
        count[k] = static_cast<int>(c[k]);
      }
      spacing = Vector<3>(g, gp, "spacing", Eigen::Vector3d::Zero());
      jitter = Number(g, gp, "jitter", 0.0);
      if (jitter < 0) Throw(Join(gp, "jitter"), "must be >= 0");
    }
    std::mt19937 rng(grid ? Integer(a.at("grid"), Join(path, "grid"), "seed", 1, 0, 1 << 30) : 1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int k = 0;
    for (int z = 0; z < count.z(); ++z)
      for (int y = 0; y < count.y(); ++y)
        for (int x = 0; x < count.x(); ++x, ++k) {
          RigidActorDesc di = d;
          if (grid) {
            di.name = d.name + "_" + std::to_string(k);
            di.position += Eigen::Vector3d(x, y, z).cwiseProduct(spacing) +
                           jitter * Eigen::Vector3d(u(rng), u(rng), u(rng));
          }
          if (!names.insert(di.name).second) Throw(Join(path, "name"), "duplicate actor name \"" + di.name + "\"");
          Error err;
          if (!out->scene->AddRigidActor(di, &err, parent).IsValid())
            throw LoadError{path + "." + err.message};
          out->actorNames.push_back(di.name);
        }
  }
}

// "contact_filter": [{"layers": [a, b] | "actors": [A, B], "enable": bool, "symmetric": bool,
//                     "include_nested": bool (actors only)}, ...], applied in order.
void ReadContactFilter(const json& list, SceneFile* out) {
  if (!list.is_array()) Throw("contact_filter", std::string("must be an array, got ") + TypeName(list));
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = "contact_filter[" + std::to_string(i) + "]";
    const json& f = list[i];
    CheckObject(f, path, {"layers", "actors", "enable", "symmetric", "include_nested"});
    if (f.contains("layers") == f.contains("actors"))
      Throw(path, "give exactly one of \"layers\" and \"actors\"");
    const std::string key = f.contains("layers") ? "layers" : "actors";
    const json& pair = f.at(key);
    if (!pair.is_array() || pair.size() != 2 || !pair[0].is_string() || !pair[1].is_string())
      Throw(Join(path, key), "must be an array of two names");
    const bool enable = Bool(f, path, "enable", false);
    const bool symmetric = Bool(f, path, "symmetric", true);
    Scene& scene = *out->scene;
    Error err;
    if (key == "layers") {
      if (f.contains("include_nested"))
        Throw(Join(path, "include_nested"), "applies to actor pairs only");
      const std::string a = pair[0], b = pair[1];
      if (symmetric) scene.EnableLayerContactSymmetric(a, b, enable, &err);
      else scene.EnableLayerContactAsymmetric(a, b, enable, &err);
      continue;
    }
    ActorHandle h[2];
    for (int k = 0; k < 2; ++k) {
      const std::string name = pair[k];
      for (size_t n = 0; n < out->actorNames.size(); ++n)
        if (out->actorNames[n] == name) h[k].index = static_cast<int>(n);
      if (!h[k].IsValid())
        Throw(Join(path, "actors") + "[" + std::to_string(k) + "]", "no actor named \"" + name + "\"");
    }
    const IncludeNestedActors nested =
        Bool(f, path, "include_nested", false) ? IncludeNestedActors::Yes : IncludeNestedActors::No;
    const bool ok = symmetric ? scene.EnableActorContactSymmetric(h[0], h[1], enable, nested, &err)
                              : scene.EnableActorContactAsymmetric(h[0], h[1], enable, nested, &err);
    if (!ok) Throw(path, err.message);
  }
}

}  // namespace

bool LoadSceneText(const std::string& text, const std::string& baseDir, SceneFile* out,
                   Error* error) {
  // A reused SceneFile starts empty (its path, set by LoadSceneFile, is kept).
  const std::string path = out->path;
  *out = SceneFile();
  out->path = path;
  try {
    json j;
    try {
      j = json::parse(text);
    } catch (const json::parse_error& e) {
      return Fail(error, std::string("(file): not valid JSON: ") + e.what());
    }
    CheckObject(j, "",
                {"format", "description", "settings", "actors", "contact_filter", "output", "expect"});
    const std::string format = String(j, "", "format", std::string("superdex-scene/1"));
    if (format != "superdex-scene/1")
      Throw("format", "unsupported \"" + format + "\" (expected superdex-scene/1)");
    out->description = String(j, "", "description", std::string());

    SceneSettings settings;
    if (j.contains("settings")) {
      const json& s = j.at("settings");
      CheckObject(s, "settings",
                  {"dt", "duration", "integrator", "gravity", "solver", "stage_solver",
                   "warm_start", "closed_form_free_stages", "experimental_eval_params"});
      out->dt = Positive(s, "settings", "dt", out->dt);
      out->duration = Positive(s, "settings", "duration", out->duration);
      settings.integrator = Enum(s, "settings", "integrator", settings.integrator);
      settings.gravity = Vector<3>(s, "settings", "gravity", settings.gravity);
      settings.warmStart = Bool(s, "settings", "warm_start", settings.warmStart);
      settings.closedFormFreeStages = Bool(s, "settings", "closed_form_free_stages",
                                           settings.closedFormFreeStages);
      if (s.contains("solver"))
        ReadFields(s.at("solver"), "settings.solver", kNonlinearSolverFields, &settings.solver);
      if (s.contains("stage_solver")) {
        const std::string name = String(s, "settings", "stage_solver", std::string("newton"));
        if (!ParseStageSolver(name, &settings.stageSolver))
          Throw("settings.stage_solver", "unknown value \"" + name + "\" (expected one of: " +
                                             AllNames(settings.stageSolver) + ")");
      }
      if (s.contains("experimental_eval_params"))
        ReadFields(s.at("experimental_eval_params"), "settings.experimental_eval_params",
                   kExperimentalEvalFields, &settings.eval);
    }
    if (std::string m = Validate(settings, "settings."); !m.empty()) throw LoadError{m};
    out->scene = std::make_unique<Scene>(settings);

    if (!j.contains("actors")) Throw("actors", "missing required field");
    ReadActors(j.at("actors"), baseDir, out);

    if (j.contains("contact_filter")) ReadContactFilter(j.at("contact_filter"), out);

    if (j.contains("output")) {
      const json& o = j.at("output");
      CheckObject(o, "output", {"path", "every", "vtk", "vtk_every", "contacts"});
      out->output.path = String(o, "output", "path", std::string());
      out->output.every = Integer(o, "output", "every", 1, 1, 1 << 30);
      out->output.vtk = String(o, "output", "vtk", std::string());
      out->output.vtkEvery = Integer(o, "output", "vtk_every", 10, 1, 1 << 30);
      out->output.contacts = Bool(o, "output", "contacts", false);
    }
    if (j.contains("expect")) {
      const json& e = j.at("expect");
      CheckObject(e, "expect", {"max_penetration", "max_relative_energy_drift", "all_converged",
                                "final_positions"});
      if (e.contains("max_penetration")) out->expect.maxPenetration = Positive(e, "expect", "max_penetration");
      if (e.contains("max_relative_energy_drift"))
        out->expect.maxRelativeEnergyDrift = Positive(e, "expect", "max_relative_energy_drift");
      out->expect.allConverged = Bool(e, "expect", "all_converged", false);
      if (e.contains("final_positions")) {
        const json& f = e.at("final_positions");
        if (!f.is_array()) Throw("expect.final_positions", "must be an array");
        for (size_t i = 0; i < f.size(); ++i) {
          const std::string p = "expect.final_positions[" + std::to_string(i) + "]";
          CheckObject(f[i], p, {"actor", "position", "tolerance"});
          SceneExpectations::RestingActor r;
          r.actor = String(f[i], p, "actor");
          bool found = false;
          for (const auto& n : out->actorNames) found |= n == r.actor;
          if (!found) Throw(Join(p, "actor"), "no actor named \"" + r.actor + "\"");
          r.position = Vector<3>(f[i], p, "position", Eigen::Vector3d::Zero());
          r.tolerance = Positive(f[i], p, "tolerance");
          out->expect.finalPositions.push_back(r);
        }
      }
    }
  } catch (const LoadError& e) {
    return Fail(error, e.message);
  } catch (const std::exception& e) {
    return Fail(error, std::string("(file): ") + e.what());
  }
  return true;
}

bool LoadSceneFile(const std::string& path, SceneFile* out, Error* error) {
  std::ifstream in(path);
  if (!in) return Fail(error, path + ": cannot open file");
  std::stringstream buf;
  buf << in.rdbuf();
  out->path = path;
  const size_t slash = path.find_last_of('/');
  const std::string baseDir = slash == std::string::npos ? "." : path.substr(0, slash);
  Error local;
  if (!LoadSceneText(buf.str(), baseDir, out, &local)) return Fail(error, path + ": " + local.message);
  return true;
}

}  // namespace superdex
