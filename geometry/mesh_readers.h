// The surface mesh readers behind ReadMeshFile (geometry/mesh_io.h), one per format, each with
// errors "<path>: <place>: <what>" (place: "line N", or the item of a binary file). Internal to
// geometry/; every count read from a header is checked against geometry/mesh_limits.h and the
// file's size before anything is allocated for it.
#pragma once

#include <string>

#include "geometry/triangle_mesh.h"

namespace superdex {

/// OFF (also COFF, NOFF, CNOFF, STOFF: the extra per-vertex values are ignored; 4OFF, nOFF and
/// binary OFF are refused). Polygons are fan-triangulated; per-face colours are ignored.
bool ReadOff(const std::string& path, TriangleMesh* mesh, std::string* error);

/// STL, ASCII or binary (binary when the size is 84 + 50 n bytes for the n triangles its header
/// declares). Identical points are merged, so that a closed surface comes out closed.
bool ReadStl(const std::string& path, TriangleMesh* mesh, std::string* error);

/// PLY, ASCII or binary (little or big endian): the x, y, z properties of element "vertex" and
/// the list property vertex_indices (or vertex_index) of element "face"; every other element
/// and property is skipped.
bool ReadPly(const std::string& path, TriangleMesh* mesh, std::string* error);

}  // namespace superdex
