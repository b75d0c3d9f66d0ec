// Reading triangle meshes from files: OBJ by our own reader (line-numbered errors), OFF, STL and
// PLY through CGAL's polygon-soup readers. The format is chosen by the extension.
#pragma once

#include <string>

#include "geometry/triangle_mesh.h"

namespace superdex {

/// Reads `path` into *mesh (polygons with more than three corners are fan-triangulated). Returns
/// false with "<path>: <what is wrong>" in *error: missing file, unknown extension, unreadable
/// content, no faces, a face index out of range.
bool ReadMeshFile(const std::string& path, TriangleMesh* mesh, std::string* error);

}  // namespace superdex
