// A soft actor's "mesh", "constraints" and "skin" in a scene file (docs/scene-format.md). Internal to
// scenes/: errors are thrown as LoadError "<json path>: <rule>".
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "scenes/json_fields.h"

namespace superdex::scene_json {

/// {"type": "file" | "box" | "sphere" | "cylinder" | "surface", ...}: the tet mesh; *source
/// names where it came from (the file, or "tet box", ...). A mesh of more than `tetBudget` tets
/// (counted, or estimated before meshing) is refused: what the scene has left of
/// limits::kMaxSoftTets.
std::shared_ptr<TetMesh> ReadTetMeshSpec(const json& j, const std::string& path,
                                         const std::string& baseDir, double tetBudget,
                                         std::string* source);

/// [{"nodes": [...] | "region": {...}, "force": [[t, fx, fy, fz], ...]}, ...]: dead loads [N]
/// per node (NodeLoad).
std::vector<NodeLoad> ReadNodeLoads(const json& list, const std::string& path,
                                    const MeshVertices& mesh, const Eigen::Vector3d& position,
                                    const Eigen::Quaterniond& orientation);

/// [{"nodes": [...] | "region": {...}, "path": [[t, dx, dy, dz], ...]}, ...]
std::vector<NodeConstraint> ReadConstraints(const json& list, const std::string& path,
                                            const MeshVertices& mesh, const Eigen::Vector3d& position,
                                            const Eigen::Quaterniond& orientation);

/// [{"link": NAME, "nodes": [...], "region": {"min", "max"} (link frame), "shape_distance": d},
/// ...]: a soft skin's bindings (SoftActorDesc::skin), each with at least one selector.
std::vector<SkinBinding> ReadSkin(const json& list, const std::string& path, const TetMesh& mesh);

}  // namespace superdex::scene_json
