// Reading triangle meshes from files: OBJ, OFF, STL (ASCII, binary) and PLY (ASCII, binary), each
// by its own reader with errors that name the line (or the binary item) and the defect, and
// counts checked against geometry/mesh_limits.h. The format is chosen by the extension.
#pragma once

#include <string>

#include "geometry/triangle_mesh.h"

namespace superdex {

/// Reads `path` into *mesh (polygons with more than three corners are fan-triangulated). Returns
/// false with "<path>: <place>: <what is wrong>" in *error: missing file, unknown extension,
/// malformed or truncated content, a count beyond its limit, no faces, a face index out of range.
bool ReadMeshFile(const std::string& path, TriangleMesh* mesh, std::string* error);

}  // namespace superdex
