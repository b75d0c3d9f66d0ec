#include "core/model/keyframes.h"

#include <cmath>

namespace superdex {
namespace {

bool AllFinite(double x) { return std::isfinite(x); }
bool AllFinite(const Eigen::Vector3d& x) { return x.allFinite(); }

template <typename T>
T Interpolate(const std::vector<std::pair<double, T>>& keys, double t, T zero) {
  if (keys.empty()) return zero;
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

template <typename T>
std::string Check(const std::vector<std::pair<double, T>>& keys, const std::string& field) {
  for (size_t j = 0; j < keys.size(); ++j) {
    if (!std::isfinite(keys[j].first) || !AllFinite(keys[j].second))
      return field + ": keyframes must be finite";
    if (j > 0 && !(keys[j].first > keys[j - 1].first))
      return field + ": keyframe times must increase";
  }
  return "";
}

}  // namespace

Eigen::Vector3d PiecewiseLinear(const VectorKeyframes& keys, double t) {
  return Interpolate<Eigen::Vector3d>(keys, t, Eigen::Vector3d::Zero());
}

std::string CheckKeyframes(const VectorKeyframes& keys, const std::string& field) {
  return Check(keys, field);
}

double PiecewiseLinear(const ScalarKeyframes& keys, double t) {
  return Interpolate<double>(keys, t, 0.0);
}

double PiecewiseSlope(const ScalarKeyframes& keys, double t) {
  if (keys.size() < 2 || t < keys.front().first || t > keys.back().first) return 0.0;
  size_t k = 1;
  while (k + 1 < keys.size() && t >= keys[k].first) ++k;
  return (keys[k].second - keys[k - 1].second) / (keys[k].first - keys[k - 1].first);
}

std::string CheckKeyframes(const ScalarKeyframes& keys, const std::string& field) {
  return Check(keys, field);
}

}  // namespace superdex
