// The resource limits of mesh files and of the mesher: an input beyond one is refused before
// memory is allocated for it, with the estimate and the limit in the message
// (docs/reliability.md). The scene-level limits are in scenes/limits.h.
#pragma once

#include <cstdio>
#include <string>

namespace superdex::limits {

/// Vertices (nodes, points) of one mesh file. Reading costs about 100 bytes per vertex (the
/// coordinates, the tag map of Gmsh files, the reader's buffers): 1e7 vertices are about 1 GB.
inline constexpr double kMaxMeshVertices = 1e7;
/// Faces (triangles after fan triangulation) of one surface mesh file, and elements (of any type,
/// tets or not) of one volume mesh file: about 50 bytes each while reading.
inline constexpr double kMaxMeshElements = 5e7;

/// Bytes of one surface mesh file (OFF, STL, PLY are read whole): text of 1e7 vertices and 5e7
/// faces fits in 2 GiB.
inline constexpr double kMaxMeshFileBytes = 2.0 * 1024 * 1024 * 1024;

/// Tets the mesher may produce (estimated from the enclosed volume and the edge length before
/// meshing): CGAL Mesh_3 needs about 1 KB and 100 µs per tet, so 1e7 tets are about 10 GB and
/// 20 minutes.
inline constexpr double kMaxMesherTets = 1e7;
/// The mesher's vertex budget as a multiple of its estimated vertices (estimated tets / 5; the
/// meshes made so far have 5 to 6 tets per vertex): a refinement that goes far past its estimate
/// does not converge and is stopped.
inline constexpr double kMesherVertexBudgetFactor = 10.0;
/// The mesher's wall-clock budget: kMesherMinSeconds plus kMesherSecondsPerTet per estimated tet
/// (measured: 100 µs per tet on a loaded 2-core machine, so the budget is ten times that). A
/// meshing stage that does not finish within it makes no progress and is stopped.
inline constexpr double kMesherMinSeconds = 60.0;
inline constexpr double kMesherSecondsPerTet = 1e-3;

/// Rays shot from the surface's bounding-box centre to find the mesher's initial points (CGAL's
/// own search has no bound and never ends on a surface that encloses no volume). A closed surface
/// enclosing the centre is hit by every ray; 8 points are needed.
inline constexpr int kMesherInitialPointRays = 10000;

/// "<what> declares <count> ..." when a count read from a file header exceeds `limit`, or needs
/// more text than the file holds (at least `bytesPerItem` bytes per item); "" when it fits. A
/// negative `fileBytes` means the size is unknown.
inline std::string CheckDeclaredCount(double count, double limit, double bytesPerItem,
                                      double fileBytes, const std::string& what) {
  char text[256];
  if (count > limit) {
    std::snprintf(text, sizeof text, "declares %.0f %s (limit %.0f per file)", count,
                  what.c_str(), limit);
    return text;
  }
  if (fileBytes >= 0 && count * bytesPerItem > fileBytes) {
    std::snprintf(text, sizeof text,
                  "declares %.0f %s, which need at least %.0f bytes (%.0f per line), but the file "
                  "holds %.0f bytes",
                  count, what.c_str(), count * bytesPerItem, bytesPerItem, fileBytes);
    return text;
  }
  return "";
}

}  // namespace superdex::limits
