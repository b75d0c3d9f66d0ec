#include "core/model/keyframes.h"

#include <cmath>

namespace superdex {

Eigen::Vector3d PiecewiseLinear(const VectorKeyframes& keys, double t) {
  if (keys.empty()) return Eigen::Vector3d::Zero();
  if (t <= keys.front().first) return keys.front().second;
  for (size_t k = 1; k < keys.size(); ++k) {
    if (t <= keys[k].first) {
      const double t0 = keys[k - 1].first, t1 = keys[k].first;
      const double s = (t - t0) / (t1 - t0);
      return (1.0 - s) * keys[k - 1].second + s * keys[k].second;
    }
  }
  return keys.back().second;
}

std::string CheckKeyframes(const VectorKeyframes& keys, const std::string& field) {
  for (size_t j = 0; j < keys.size(); ++j) {
    if (!std::isfinite(keys[j].first) || !keys[j].second.allFinite())
      return field + ": keyframes must be finite";
    if (j > 0 && !(keys[j].first > keys[j - 1].first))
      return field + ": keyframe times must increase";
  }
  return "";
}

}  // namespace superdex
