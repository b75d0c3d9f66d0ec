// Analytic signed distance fields (see analytic_sdf.h).
#include "geometry/analytic_sdf.h"

#include <cmath>

namespace superdex {

SdfSample SphereSdf::Evaluate(const Eigen::Vector3d& X) const {
  SdfSample s;
  const double r = X.norm();
  s.value = r - radius;
  if (r > 0.0) {
    s.gradient = X / r;
    s.hessian = (Eigen::Matrix3d::Identity() - s.gradient * s.gradient.transpose()) / r;
  } else {
    s.gradient = Eigen::Vector3d::UnitZ();  // any direction is a closest one; Hessian left zero
  }
  return s;
}

SdfSample BoxSdf::Evaluate(const Eigen::Vector3d& X) const {
  SdfSample s;
  const Eigen::Vector3d d = X.cwiseAbs() - halfExtents;  // per-axis distance past the slab
  const Eigen::Vector3d sign(X.x() < 0.0 ? -1.0 : 1.0, X.y() < 0.0 ? -1.0 : 1.0,
                             X.z() < 0.0 ? -1.0 : 1.0);
  if ((d.array() <= 0.0).all()) {
    // Inside or on the surface: Φ = max_i d_i <= 0, the (negated) distance to the nearest face;
    // ∇Φ = ±e_i of that face; piecewise linear, so ∇∇Φ = 0 (ties: the lowest axis).
    int i = 0;
    s.value = d.maxCoeff(&i);
    s.gradient[i] = sign[i];
    return s;
  }
  // Outside: q = max(d, 0) is the offset from the closest surface point (in the octant of X);
  // Φ = |q|, ∇Φ = n = sign ∘ q/|q|. The Hessian is (P − n nᵀ)/Φ with P the projector onto the
  // axes on which X lies outside the slab: one axis (face region) gives zero, two (edge region)
  // give (I − t tᵀ − n nᵀ)/Φ with t the edge direction, three (corner region) (I − n nᵀ)/Φ.
  const Eigen::Vector3d q = d.cwiseMax(0.0);
  const double dist = q.norm();
  s.value = dist;
  const Eigen::Vector3d n = q.cwiseProduct(sign) / dist;
  s.gradient = n;
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  int outside = 0;
  for (int k = 0; k < 3; ++k)
    if (d[k] > 0.0) {
      P(k, k) = 1.0;
      ++outside;
    }
  if (outside > 1) s.hessian = (P - n * n.transpose()) / dist;
  return s;
}

SdfSample PlaneSdf::Evaluate(const Eigen::Vector3d& X) const {
  // normal is used as given (the header requires it to be a unit vector).
  SdfSample s;
  s.value = normal.dot(X) - offset;
  s.gradient = normal;
  return s;
}

}  // namespace superdex
