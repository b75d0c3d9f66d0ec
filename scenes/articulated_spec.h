// An articulated actor in a scene file (docs/scene-format.md, "Articulated actors"). Internal to
// scenes/: errors are thrown as LoadError "<json path>: <rule>".
#pragma once

#include <string>

#include "core/model/articulated_kind.h"
#include "scenes/json_fields.h"

namespace superdex::scene_json {

/// {"name", "type": "articulated", "links": [{"name", "parent", "joint", "origin", "axis", "mass",
///  "center_of_mass", "inertia", "position", "velocity", "euler_deg" | "orientation",
///  "angular_velocity", "joint_params"}, ...]}: the description, its joint coordinates and
/// velocities assembled from the links' in the tree's layout. Or, instead of "links",
/// {"urdf": file (relative to baseDir), "base": "fixed" | "free", "position", "euler_deg" |
///  "orientation", "joint_positions": {joint: value}, "joint_velocities": {...},
///  "joint_params": {joint: {...}}} (scenes/urdf_reader.h).
ArticulatedActorDesc ReadArticulatedDesc(const json& a, const std::string& path,
                                         const std::string& baseDir);

}  // namespace superdex::scene_json
