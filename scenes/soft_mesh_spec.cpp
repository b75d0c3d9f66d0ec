// Soft actors' tet meshes and node constraints in scene files (see soft_mesh_spec.h).
#include "scenes/soft_mesh_spec.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geometry/mesh_io.h"
#include "geometry/tet_mesh.h"

namespace superdex::scene_json {

namespace {

std::string ResolvePath(std::string file, const std::string& baseDir) {
  if (!file.empty() && file[0] != '/' && !baseDir.empty()) file = baseDir + "/" + file;
  return file;
}

// Refuses `tets` (counted or estimated) beyond the `budget` the scene has left of
// limits::kMaxSoftTets, naming `path`.
void CheckTetBudget(double tets, double budget, const std::string& path, const std::string& what) {
  if (tets <= budget) return;
  std::ostringstream s;
  s << what << " has " << (std::floor(tets) == tets ? "" : "about ")
    << static_cast<long long>(std::ceil(tets))
    << " tets, beyond the " << budget << " left of the scene's soft-tet limit "
    << limits::kMaxSoftTets << " (about " << limits::kBytesPerSoftTet * tets / 1e9
    << " GB to simulate at " << limits::kBytesPerSoftTet / 1e3 << " KB per tet)";
  Throw(path, s.str());
}

// {"type": "file", "file": F (.msh, .node/.ele), "scale"}
void ReadFileMesh(const json& j, const std::string& path, const std::string& baseDir,
                  double budget, TetMesh* mesh, std::string* source) {
  CheckObject(j, path, {"type", "file", "scale"});
  const std::string file = ResolvePath(String(j, path, "file"), baseDir);
  std::string err;
  if (!ReadTetMeshFile(file, mesh, &err)) Throw(Join(path, "file"), err);
  CheckTetBudget(mesh->NumTets(), budget, Join(path, "file"), file);
  const double scale = Positive(j, path, "scale", 1.0);
  for (auto& v : mesh->vertices) v *= scale;
  CheckCoordinates(mesh->vertices, Join(path, j.contains("scale") ? "scale" : "file"));
  *source = file;
}

// {"type": "box", "half_extents" | "size", "cells": [nx, ny, nz]}
void ReadBoxMesh(const json& j, const std::string& path, double budget, TetMesh* mesh) {
  CheckObject(j, path, {"type", "half_extents", "size", "cells"});
  if (j.contains("size") == j.contains("half_extents"))
    Throw(path, "give exactly one of \"size\" and \"half_extents\"");
  const bool full = j.contains("size");
  const char* key = full ? "size" : "half_extents";
  const Eigen::Vector3d e = Point(j, path, key, Eigen::Vector3d::Zero());
  if (!(e.minCoeff() > 0)) Throw(Join(path, key), "must be > 0");
  const Eigen::Vector3d c = Vector<3>(j, path, "cells", Eigen::Vector3d(4, 4, 4));
  Eigen::Vector3i cells;
  for (int k = 0; k < 3; ++k) {
    if (c[k] < 1 || c[k] > 200 || c[k] != std::floor(c[k]))
      Throw(Join(path, "cells"), "must hold integers in [1, 200]");
    cells[k] = static_cast<int>(c[k]);
  }
  CheckTetBudget(6 * c.prod(), budget, Join(path, "cells"), "the box (6 tets per cell)");
  *mesh = MakeTetBox(full ? Eigen::Vector3d(0.5 * e) : e, cells);
}

// The mesher's estimate for a solid of `volume` (geometry/mesher_input.cpp: regular tets).
double EstimatedTets(double volume, double h) { return volume / (h * h * h / 8.485); }

// {"type": "sphere", "radius", "edge_length"} and {"type": "cylinder", "radius", "length",
// "edge_length"}: a surface resolved at half the edge length, meshed by CGAL's Mesh_3.
void ReadSphereOrCylinder(const json& j, const std::string& path, const std::string& type,
                          double budget, TetMesh* mesh) {
  const bool sphere = type == "sphere";
  if (sphere) CheckObject(j, path, {"type", "radius", "edge_length"});
  else CheckObject(j, path, {"type", "radius", "length", "edge_length"});
  const double r = Length(j, path, "radius");
  const double len = sphere ? 2 * r : Length(j, path, "length");
  const double h = Length(j, path, "edge_length");
  if ((sphere ? r : std::max(r, len)) / h > 60)
    Throw(Join(path, "edge_length"), std::string("too small for the ") + type +
                                         " (size/edge_length > 60)");
  const double volume = sphere ? 4.0 / 3.0 * M_PI * r * r * r : M_PI * r * r * len;
  CheckTetBudget(EstimatedTets(volume, h), budget, Join(path, "edge_length"), "the " + type);
  MeshingLimits bounds;
  bounds.maxTets = budget;
  std::string err;
  bool ok;
  if (sphere) {
    ok = MeshTetSphere(r, h, mesh, &err, bounds);
  } else {
    const int segments = std::max(12, static_cast<int>(std::ceil(2 * M_PI * r / (0.5 * h))));
    const int rings = std::max(2, static_cast<int>(std::ceil(len / (0.5 * h))));
    ok = MeshTetsFromSurface(MakeCylinderMesh(r, 0.5 * len, segments, rings), h, mesh, &err,
                             bounds);
  }
  if (!ok) Throw(path, "meshing the " + type + " failed: " + err);
}

// {"type": "surface", "file": F (closed surface mesh), "edge_length", "scale"}
void ReadSurfaceMesh(const json& j, const std::string& path, const std::string& baseDir,
                     double budget, TetMesh* mesh, std::string* source) {
  CheckObject(j, path, {"type", "file", "edge_length", "scale"});
  const std::string file = ResolvePath(String(j, path, "file"), baseDir);
  TriangleMesh surface;
  std::string err;
  if (!ReadMeshFile(file, &surface, &err)) Throw(Join(path, "file"), err);
  const double scale = Positive(j, path, "scale", 1.0);
  for (auto& v : surface.vertices) v *= scale;
  CheckCoordinates(surface.vertices, Join(path, j.contains("scale") ? "scale" : "file"));
  const double h = Length(j, path, "edge_length");
  MeshingLimits bounds;
  bounds.maxTets = budget;
  if (!MeshTetsFromSurface(surface, h, mesh, &err, bounds)) Throw(path, file + ": " + err);
  *source = file;
}

}  // namespace

std::shared_ptr<TetMesh> ReadTetMeshSpec(const json& j, const std::string& path,
                                         const std::string& baseDir, double tetBudget,
                                         std::string* source) {
  if (!j.is_object()) Throw(path, std::string("must be an object, got ") + TypeName(j));
  auto mesh = std::make_shared<TetMesh>();
  const std::string type = String(j, path, "type");
  if (type == "file") {
    ReadFileMesh(j, path, baseDir, tetBudget, mesh.get(), source);
  } else if (type == "box") {
    ReadBoxMesh(j, path, tetBudget, mesh.get());
    *source = "tet box";
  } else if (type == "sphere" || type == "cylinder") {
    ReadSphereOrCylinder(j, path, type, tetBudget, mesh.get());
    *source = "tet " + type;
  } else if (type == "surface") {
    ReadSurfaceMesh(j, path, baseDir, tetBudget, mesh.get(), source);
  } else {
    Throw(Join(path, "type"), "unknown value \"" + type +
                                  "\" (expected one of: file, box, sphere, cylinder, surface)");
  }
  CheckTetBudget(mesh->NumTets(), tetBudget, path, "the mesh");
  return mesh;
}

// "constraints": [{"nodes": [i, ...] | "region": {"min": [..], "max": [..]} (world coordinates at
// creation), "path": [[t, dx, dy, dz], ...] (omitted: pinned)}, ...]
namespace {

// The node indices of field "nodes" of object c, each a node of the mesh.
std::vector<int> ReadNodes(const json& c, const std::string& p, const MeshVertices& mesh) {
  std::vector<int> nodes;
  auto readNode = [&](const json& v, const std::string& np) {
    if (!v.is_number_integer()) Throw(np, "must be a node index (an integer)");
    // Checked before narrowing: a huge index must not wrap to an existing node.
    if (v.is_number_unsigned() ? v.get<unsigned long long>() >= unsigned(mesh.NumVertices())
                               : (v.get<long long>() < 0 ||
                                  v.get<long long>() >= mesh.NumVertices()))
      Throw(np, "node " + v.dump() + " does not exist (the mesh has " +
                    std::to_string(mesh.NumVertices()) + " nodes)");
    nodes.push_back(v.get<int>());
  };
  ForEachItem(c, p, "nodes", "must be an array of node indices", readNode);
  return nodes;
}

}  // namespace

std::vector<SkinBinding> ReadSkin(const json& list, const std::string& path, const TetMesh& mesh) {
  if (!list.is_array() || list.empty()) Throw(path, "must be a non-empty array of bindings");
  std::vector<SkinBinding> out;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string p = path + "[" + std::to_string(i) + "]";
    const json& c = list[i];
    CheckObject(c, p, {"link", "nodes", "region", "shape_distance"});
    SkinBinding b;
    if (!c.contains("link")) Throw(Join(p, "link"), "missing required field");
    b.link = String(c, p, "link");
    if (!c.contains("nodes") && !c.contains("region") && !c.contains("shape_distance"))
      Throw(p, "give at least one of \"nodes\", \"region\" and \"shape_distance\"");
    if (c.contains("nodes")) b.nodes = ReadNodes(c, p, mesh);
    if (c.contains("region")) {
      const json& r = c.at("region");
      const std::string rp = Join(p, "region");
      CheckObject(r, rp, {"min", "max"});
      if (!r.contains("min") || !r.contains("max")) Throw(rp, "needs \"min\" and \"max\"");
      b.hasRegion = true;
      b.regionMin = Vector<3>(r, rp, "min", Eigen::Vector3d::Zero());
      b.regionMax = Vector<3>(r, rp, "max", Eigen::Vector3d::Zero());
    }
    if (c.contains("shape_distance")) {
      b.shapeDistance = Number(c, p, "shape_distance", -1.0);
      if (!(b.shapeDistance >= 0.0)) Throw(Join(p, "shape_distance"), "must be >= 0 [m]");
    }
    out.push_back(b);
  }
  return out;
}

// The nodes of entry c at p: its "nodes" or the placed mesh's nodes in its "region".
std::vector<int> ReadNodeSelection(const json& c, const std::string& p, const MeshVertices& mesh,
                                   const Eigen::Vector3d& position,
                                   const Eigen::Quaterniond& orientation) {
  if (c.contains("nodes") == c.contains("region"))
    Throw(p, "give exactly one of \"nodes\" and \"region\"");
  if (c.contains("nodes")) return ReadNodes(c, p, mesh);
  const Eigen::Matrix3d R = orientation.normalized().toRotationMatrix();
  const json& r = c.at("region");
  const std::string rp = Join(p, "region");
  CheckObject(r, rp, {"min", "max"});
  const Eigen::Vector3d lo = Vector<3>(r, rp, "min", Eigen::Vector3d::Zero());
  const Eigen::Vector3d hi = Vector<3>(r, rp, "max", Eigen::Vector3d::Zero());
  std::vector<int> nodes;
  for (int v = 0; v < mesh.NumVertices(); ++v) {
    const Eigen::Vector3d x = position + R * mesh.vertices[v];
    if ((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()) nodes.push_back(v);
  }
  if (nodes.empty()) Throw(rp, "selects no node");
  return nodes;
}

std::vector<NodeLoad> ReadNodeLoads(const json& list, const std::string& path,
                                    const MeshVertices& mesh, const Eigen::Vector3d& position,
                                    const Eigen::Quaterniond& orientation) {
  if (!list.is_array()) Throw(path, "must be an array");
  std::vector<NodeLoad> out;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string p = path + "[" + std::to_string(i) + "]";
    const json& c = list[i];
    CheckObject(c, p, {"nodes", "region", "force"});
    NodeLoad load;
    load.nodes = ReadNodeSelection(c, p, mesh, position, orientation);
    if (!c.contains("force")) Throw(Join(p, "force"), "missing required field");
    ForEachItem(c, p, "force", "must be an array of [t, fx, fy, fz]",
                [&](const json& f, const std::string& fp) {
                  if (!f.is_array() || f.size() != 4) Throw(fp, "must be [t, fx, fy, fz]");
                  for (const json& v : f)
                    if (!v.is_number()) Throw(fp, "must be [t, fx, fy, fz] (numbers)");
                  load.force.push_back(
                      {f[0].get<double>(),
                       Eigen::Vector3d(f[1].get<double>(), f[2].get<double>(), f[3].get<double>())});
                });
    out.push_back(std::move(load));
  }
  return out;
}

std::vector<NodeConstraint> ReadConstraints(const json& list, const std::string& path,
                                            const MeshVertices& mesh, const Eigen::Vector3d& position,
                                            const Eigen::Quaterniond& orientation) {
  if (!list.is_array()) Throw(path, "must be an array");
  std::vector<NodeConstraint> out;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string p = path + "[" + std::to_string(i) + "]";
    const json& c = list[i];
    CheckObject(c, p, {"nodes", "region", "path"});
    NodeConstraint k;
    k.nodes = ReadNodeSelection(c, p, mesh, position, orientation);
    auto readStep = [&](const json& f, const std::string& fp) {  // one [t, dx, dy, dz]
      if (!f.is_array() || f.size() != 4) Throw(fp, "must be [t, dx, dy, dz]");
      for (const json& v : f)
        if (!v.is_number()) Throw(fp, "must be [t, dx, dy, dz] (numbers)");
      const Eigen::Vector3d d(f[1].get<double>(), f[2].get<double>(), f[3].get<double>());
      if (d.cwiseAbs().maxCoeff() > limits::kMaxLength)
        Throw(fp, "the displacement " + TooLarge(d.cwiseAbs().maxCoeff()));
      k.path.push_back({f[0].get<double>(), d});
    };
    if (c.contains("path"))
      ForEachItem(c, p, "path", "must be an array of [t, dx, dy, dz]", readStep);
    out.push_back(std::move(k));
  }
  return out;
}

}  // namespace superdex::scene_json
