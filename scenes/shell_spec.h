// A shell actor in a scene file (`"type": "shell"`, docs/scene-format.md). Internal to scenes/:
// errors are thrown as LoadError "<json path>: <rule>".
#pragma once

#include <string>

#include "core/model/shell_body.h"
#include "scenes/json_fields.h"

namespace superdex::scene_json {

/// The description of the shell actor object `a` at JSON path `path` (mesh files relative to
/// baseDir): name, mesh ({"type": "file", "file", "scale"} or {"type": "rectangle", "size":
/// [a, b], "cells": [nx, ny]}), material, bending, placement, velocity, contact,
/// contact_element_type, collider_type, point_cloud (PointCloudColliderParams' fields),
/// contact_layer, constraints, loads and clamped nodes.
ShellActorDesc ReadShellDesc(const json& a, const std::string& path, const std::string& baseDir);

}  // namespace superdex::scene_json
