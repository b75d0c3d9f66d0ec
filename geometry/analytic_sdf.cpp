// Analytic signed distance fields (see analytic_sdf.h).
#include "geometry/analytic_sdf.h"

#include <cmath>

namespace superdex {
namespace {

// Value, gradient and Hessian: EvaluateBelow without a bound.
template <typename Field>
SdfSample EvaluateFully(const Field& field, const Eigen::Vector3d& X) {
  SdfSample s;
  field.EvaluateBelow(X, INFINITY, &s);
  return s;
}

}  // namespace

SdfSample SphereSdf::Evaluate(const Eigen::Vector3d& X) const { return EvaluateFully(*this, X); }

bool SphereSdf::EvaluateBelow(const Eigen::Vector3d& X, double bound, SdfSample* s,
                              bool hessian) const {
  const double r = X.norm();
  s->value = r - radius;
  if (s->value >= bound) return false;
  if (r > 0.0) {
    s->gradient = X / r;
    if (hessian)
      s->hessian = (Eigen::Matrix3d::Identity() - s->gradient * s->gradient.transpose()) / r;
  } else {
    s->gradient = Eigen::Vector3d::UnitZ();  // any direction is a closest one; Hessian zero
    if (hessian) s->hessian.setZero();
  }
  return true;
}

SdfSample CapsuleSdf::Evaluate(const Eigen::Vector3d& X) const { return EvaluateFully(*this, X); }

bool CapsuleSdf::EvaluateBelow(const Eigen::Vector3d& X, double bound, SdfSample* s) const {
  const bool side = std::abs(X.z()) < halfLength;
  const Eigen::Vector3d d(X.x(), X.y(), X.z() - std::clamp(X.z(), -halfLength, halfLength));
  const double r = d.norm();
  s->value = r - radius;
  if (s->value >= bound) return false;
  if (r > 0.0) {
    s->gradient = d / r;
    Eigen::Matrix3d P = Eigen::Matrix3d::Identity();
    if (side) P(2, 2) = 0.0;
    s->hessian = (P - s->gradient * s->gradient.transpose()) / r;
  } else {
    s->gradient = Eigen::Vector3d::UnitX();  // on the segment: any radial direction
    s->hessian.setZero();
  }
  return true;
}

SdfSample BoxSdf::Evaluate(const Eigen::Vector3d& X) const { return EvaluateFully(*this, X); }

bool BoxSdf::EvaluateBelow(const Eigen::Vector3d& X, double bound, SdfSample* out) const {
  SdfSample& s = *out;
  const Eigen::Vector3d d = X.cwiseAbs() - halfExtents;  // per-axis distance past the slab
  int i = 0;
  const double dMax = d.maxCoeff(&i);
  const bool inside = dMax <= 0.0;
  const Eigen::Vector3d q = d.cwiseMax(0.0);
  s.value = inside ? dMax : q.norm();
  if (s.value >= bound) return false;
  const Eigen::Vector3d sign(X.x() < 0.0 ? -1.0 : 1.0, X.y() < 0.0 ? -1.0 : 1.0,
                             X.z() < 0.0 ? -1.0 : 1.0);
  s.gradient.setZero();
  s.hessian.setZero();
  if (inside) {
    // Inside or on the surface: Φ = max_i d_i <= 0, the (negated) distance to the nearest face;
    // ∇Φ = ±e_i of that face; piecewise linear, so ∇∇Φ = 0 (ties: the lowest axis).
    s.gradient[i] = sign[i];
    return true;
  }
  // Outside: q = max(d, 0) is the offset from the closest surface point (in the octant of X);
  // Φ = |q|, ∇Φ = n = sign ∘ q/|q|. The Hessian is (P − n nᵀ)/Φ with P the projector onto the
  // axes on which X lies outside the slab: one axis (face region) gives zero, two (edge region)
  // give (I − t tᵀ − n nᵀ)/Φ with t the edge direction, three (corner region) (I − n nᵀ)/Φ.
  const double dist = s.value;
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
  return true;
}

SdfSample PlaneSdf::Evaluate(const Eigen::Vector3d& X) const { return EvaluateFully(*this, X); }

bool PlaneSdf::EvaluateBelow(const Eigen::Vector3d& X, double bound, SdfSample* s) const {
  // normal is used as given (the header requires it to be a unit vector).
  s->value = normal.dot(X) - offset;
  if (s->value >= bound) return false;
  s->gradient = normal;
  s->hessian.setZero();
  return true;
}

}  // namespace superdex
