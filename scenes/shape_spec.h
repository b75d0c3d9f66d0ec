// A rigid shape, contact parameters and grid SDF settings in a scene file (docs/scene-format.md),
// shared by rigid actors and by articulated links' shapes. Internal to scenes/: errors are thrown
// as LoadError "<json path>: <rule>".
#pragma once

#include <string>

#include "core/model/rigid_body.h"
#include "scenes/json_fields.h"

namespace superdex::scene_json {

/// {"type": "sphere" | "box" | "plane" | "mesh", ...}; a mesh file is relative to baseDir.
RigidShape ReadShape(const json& j, const std::string& path, const std::string& baseDir);
/// The contact parameters' fields (kContactParamsFields).
ContactParams ReadContact(const json& j, const std::string& path);
/// The grid SDF fields (kGridSdfFields), validated.
GridSdfParams ReadGridSdf(const json& g, const std::string& gp);

}  // namespace superdex::scene_json
