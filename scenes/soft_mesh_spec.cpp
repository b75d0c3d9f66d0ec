// Soft actors' tet meshes and node constraints in scene files (see soft_mesh_spec.h).
#include "scenes/soft_mesh_spec.h"

#include <algorithm>
#include <cmath>

#include "geometry/mesh_io.h"
#include "geometry/tet_mesh.h"

namespace superdex::scene_json {

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

}  // namespace superdex::scene_json
