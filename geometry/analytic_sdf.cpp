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
    s.gradient = Eigen::Vector3d::UnitZ();
  }
  return s;
}

SdfSample BoxSdf::Evaluate(const Eigen::Vector3d& X) const {
  SdfSample s;
  const Eigen::Vector3d a = X.cwiseAbs();
  const Eigen::Vector3d d = a - halfExtents;
  const Eigen::Vector3d sign(X.x() < 0 ? -1.0 : 1.0, X.y() < 0 ? -1.0 : 1.0,
                             X.z() < 0 ? -1.0 : 1.0);
  if ((d.array() <= 0.0).all()) {
    // Inside (or on the surface): distance to the nearest face, gradient its outward normal.
    int i;
    s.value = d.maxCoeff(&i);
    s.gradient[i] = sign[i];
    return s;
  }
  // Outside: vector from the closest surface point, q = max(d, 0) componentwise.
  const Eigen::Vector3d q = d.cwiseMax(0.0);
  const double dist = q.norm();
  s.value = dist;
  const Eigen::Vector3d n = q.cwiseProduct(sign) / dist;
  s.gradient = n;
  // Hessian: (P − n nᵀ)/dist with P the projector onto the axes where the point is outside
  // (one axis: face region, zero Hessian; two: edge; three: corner).
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
  SdfSample s;
  s.value = normal.dot(X) - offset;
  s.gradient = normal;
  return s;
}

}  // namespace superdex
