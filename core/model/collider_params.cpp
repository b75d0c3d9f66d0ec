#include "core/model/collider_params.h"

#include <cmath>
#include <cstdio>

namespace superdex {

SUPERDEX_ENUM_NAMES(GridSdfResolutionMode,
    {GridSdfResolutionMode::MeanEdgeLength, "MeanEdgeLength", "the shape mesh's mean edge length"},
    {GridSdfResolutionMode::BoundingExtent, "BoundingExtent",
     "the longest side of the shape's bounding box, divided by 64"})

std::shared_ptr<GridSdf> BuildGridSdf(const TriangleMesh& mesh,
                                      const std::function<double(const Eigen::Vector3d&)>& phi,
                                      const GridSdfParams& g, std::string* error) {
  if (std::string m = Validate(g); !m.empty()) {
    *error = m;
    return nullptr;
  }
  const Aabb bounds = mesh.Bounds();
  const Eigen::Vector3d extent = bounds.max - bounds.min;
  double reference = extent.maxCoeff() / 64.0;
  if (g.resolutionMode == GridSdfResolutionMode::MeanEdgeLength && !mesh.faces.empty()) {
    double sum = 0.0;
    for (const Eigen::Vector3i& f : mesh.faces)
      for (int k = 0; k < 3; ++k) sum += (mesh.vertices[f[k]] - mesh.vertices[f[(k + 1) % 3]]).norm();
    reference = sum / (3.0 * mesh.faces.size());
  }
  double h = g.resolutionDelta * reference;
  const Eigen::Vector3d padded = extent + Eigen::Vector3d::Constant(2 * g.boundaryPaddingDist);
  h = std::min(h, padded.minCoeff() / g.minGridResolution);  // >= minGridResolution voxels/axis
  Eigen::Vector3d perAxis;  // in double: a huge padding must not wrap an int
  for (int a = 0; a < 3; ++a) perAxis[a] = std::ceil(padded[a] / h) + 1;
  const double count = perAxis.prod();
  if (!(count <= 64e6)) {  // also NaN and infinity
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", count);
    *error = std::string("the grid would hold ") + text +
             " nodes (limit 64e6); raise resolution_delta";
    return nullptr;
  }
  const Eigen::Vector3i nodes = perAxis.cast<int>();
  const Eigen::Vector3d origin = bounds.min - Eigen::Vector3d::Constant(g.boundaryPaddingDist);
  return std::make_shared<GridSdf>(GridSdf::Build(phi, origin, h, nodes));
}

}  // namespace superdex
