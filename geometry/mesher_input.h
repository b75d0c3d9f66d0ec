// The tet mesher's input, checked and prepared before CGAL sees it (geometry/tet_mesher.cpp):
// a closed, consistently oriented surface enclosing a volume, an estimate of the work within the
// limits, and coordinates normalized so that the mesher works at unit scale. Internal to
// geometry/.
#pragma once

#include <Eigen/Core>
#include <string>

#include "geometry/tet_mesh.h"

namespace superdex {

struct MesherInput {
  /// The surface in normalized coordinates x_n = (x − center) · scale, with `scale` a power of
  /// two. Surfaces of moderate size near the origin (the box's longest side within [2⁻¹⁶, 2¹⁶]
  /// m and its centre within 64 sides of the origin) are not moved (center 0, scale 1), so their
  /// meshes are as before; CGAL's Mesh_3 stops converging for sides beyond about 1e9 or below
  /// 1e-15.
  TriangleMesh surface;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double scale = 1.0;
  double edgeLength = 0.0;  ///< uniform size, normalized (0 with a size field)
  MeshSizeField field;      ///< position-dependent size in normalized coordinates (or empty)
  double estimatedTets = 0.0;      ///< from the enclosed volume: V / (h³ / 8.485)
  double estimatedVertices = 0.0;  ///< tets / 5 plus the surface's area / (0.87 h²)
  double seconds = 0.0;            ///< the wall-clock budget
  size_t maxVertices = 0;          ///< the refinement's vertex budget
};

/// Checks `surface` and the size (edgeLength, or *field if not null) and fills *in. False with
/// the defect in *message (no "MeshTetsFromSurface: " prefix).
bool PrepareMesherInput(const TriangleMesh& surface, double edgeLength, const MeshSizeField* field,
                        const MeshingLimits& bounds, MesherInput* in, std::string* message);

/// Short number for messages.
std::string MesherNum(double v);

}  // namespace superdex
