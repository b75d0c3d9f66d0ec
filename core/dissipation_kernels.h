// Kernels shared by the rigid and soft contact dissipation: scalar-generic (double or Ceres jet)
// helpers for the alignment factor and the split direction, so that the residual-mode Jacobians
// are differentiated automatically from the same formulas the residuals use. Include only from
// core/ .cpp files (it pulls in ceres/jet.h).
#pragma once

#include <ceres/jet.h>

#include <Eigen/Core>

#include "core/rigid_dissipation.h"

namespace superdex {
namespace dissipation_kernels {

inline double ValueOf(double x) { return x; }
template <int N>
inline double ValueOf(const ceres::Jet<double, N>& x) {
  return x.a;
}

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Mat3 = Eigen::Matrix<T, 3, 3>;

template <typename T>
Mat3<T> SkewT(const Vec3<T>& v) {
  Mat3<T> S;
  S << T(0.0), -v.z(), v.y(), v.z(), T(0.0), -v.x(), -v.y(), v.x(), T(0.0);
  return S;
}

/// The dissipative alignment factor a = (m − s)/(m + 1) when fading is on and m > −1, else 1
/// (spec: "Normal/Tangential Split"), for doubles and jets alike.
template <typename T>
T AlignmentFactor(const T& s, const DissipationSetup& setup) {
  if (!setup.fadeFriction || !(setup.maxAlignment > -1.0)) return T(1.0);
  return (T(setup.maxAlignment) - s) / (setup.maxAlignment + 1.0);
}

/// The unit split direction: N_B = G_B/|G_B| by default, −N_A/|N_A| with
/// frictionWithColliderNormal = false.
template <typename T>
Vec3<T> SplitDirection(const Vec3<T>& G, const Vec3<T>& NA, const DissipationSetup& setup) {
  using std::sqrt;
  return setup.frictionWithColliderNormal ? Vec3<T>(G / sqrt(G.squaredNorm()))
                                          : Vec3<T>(-NA / sqrt(NA.squaredNorm()));
}

}  // namespace dissipation_kernels
}  // namespace superdex
