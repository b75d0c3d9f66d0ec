#include "core/model/collider_params.h"

#include <cmath>
#include <sstream>

namespace superdex {
namespace {

template <typename T>
std::string Rule(const std::string& prefix, const char* field, const char* rule, T value) {
  std::ostringstream s;
  s << prefix << field << ": " << rule << ", got " << value;
  return s.str();
}

bool Positive(double x) { return std::isfinite(x) && x > 0.0; }

}  // namespace

const char* ToString(GridSdfResolutionMode mode) {
  return mode == GridSdfResolutionMode::MeanEdgeLength ? "MeanEdgeLength" : "BoundingExtent";
}

std::string Validate(const GridSdfParams& p, const std::string& prefix) {
  if (p.resolutionMode != GridSdfResolutionMode::MeanEdgeLength &&
      p.resolutionMode != GridSdfResolutionMode::BoundingExtent)
    return Rule(prefix, "resolution_mode", "must be MeanEdgeLength or BoundingExtent",
                static_cast<int>(p.resolutionMode));
  if (!Positive(p.resolutionDelta))
    return Rule(prefix, "resolution_delta", "must be > 0", p.resolutionDelta);
  if (p.minGridResolution < 2)
    return Rule(prefix, "min_grid_resolution", "must be >= 2", p.minGridResolution);
  if (!(std::isfinite(p.boundaryPaddingDist) && p.boundaryPaddingDist >= 0.0))
    return Rule(prefix, "boundary_padding_dist", "must be >= 0", p.boundaryPaddingDist);
  return "";
}

std::string Validate(const PointCloudColliderParams& p, const std::string& prefix) {
  if (!Positive(p.radius)) return Rule(prefix, "radius", "must be > 0", p.radius);
  if (!Positive(p.selfContactExclusionRatio))
    return Rule(prefix, "self_contact_exclusion_ratio", "must be > 0", p.selfContactExclusionRatio);
  if (!Positive(p.spatialHashLoadFactor))
    return Rule(prefix, "spatial_hash_load_factor", "must be > 0", p.spatialHashLoadFactor);
  return "";
}

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
  Eigen::Vector3i nodes;
  for (int a = 0; a < 3; ++a) nodes[a] = static_cast<int>(std::ceil(padded[a] / h)) + 1;
  const double count = double(nodes.x()) * nodes.y() * nodes.z();
  if (count > 64e6) {
    *error = "the grid would hold " + std::to_string(count) +
             " nodes (limit 64e6); raise resolution_delta";
    return nullptr;
  }
  const Eigen::Vector3d origin = bounds.min - Eigen::Vector3d::Constant(g.boundaryPaddingDist);
  return std::make_shared<GridSdf>(GridSdf::Build(phi, origin, h, nodes));
}

}  // namespace superdex
