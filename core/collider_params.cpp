#include "core/collider_params.h"

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

}  // namespace superdex
