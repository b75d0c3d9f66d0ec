// Analytic signed distance fields in a body's reference frame: negative inside, positive outside.
#pragma once

#include <Eigen/Core>
#include <algorithm>

namespace superdex {

/// One evaluation of a signed distance field Φ at a reference point X:
/// value Φ [m], gradient ∇Φ (unit where Φ is an exact SDF), Hessian ∇∇Φ [1/m].
struct SdfSample {
  double value = 0.0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
};

/// Sphere of radius r centred at the origin: Φ(X) = |X| - r, ∇Φ = X/|X|,
/// ∇∇Φ = (I - ∇Φ ∇Φ^T)/|X|. At X = 0 the gradient is taken as +z and the Hessian as zero.
struct SphereSdf {
  double radius = 1.0;
  SdfSample Evaluate(const Eigen::Vector3d& X) const;
  double Value(const Eigen::Vector3d& X) const { return X.norm() - radius; }  ///< Φ only
  /// Fills s->value; the gradient and (`hessian`) the Hessian too and returns true unless
  /// Φ >= bound. Without `hessian`, s->hessian is not written.
  bool EvaluateBelow(const Eigen::Vector3d& X, double bound, SdfSample* s,
                     bool hessian = true) const;
};

/// Axis-aligned box centred at the origin with half extents b, exact inside and outside:
/// with d = |X| - b (componentwise), Φ = |max(d, 0)| + min(max_i d_i, 0).
/// Outside, the gradient points from the closest surface point; the Hessian is that of the
/// distance to the closest face (zero), edge ((I - t t^T - n n^T)/Φ with t the edge direction)
/// or corner ((I - n n^T)/Φ). Inside, gradient ±e_i of the nearest face and zero Hessian.
struct BoxSdf {
  Eigen::Vector3d halfExtents = Eigen::Vector3d::Ones();
  SdfSample Evaluate(const Eigen::Vector3d& X) const;
  /// Fills s->value; the gradient and Hessian too and returns true unless Φ >= bound.
  bool EvaluateBelow(const Eigen::Vector3d& X, double bound, SdfSample* s) const;
  double Value(const Eigen::Vector3d& X) const {  ///< Φ only
    const Eigen::Vector3d d = X.cwiseAbs() - halfExtents;
    return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
  }
};

/// Capsule of radius r about the segment from −h ẑ to +h ẑ (h the half length of its straight
/// part): Φ(X) = |X − c(X)| − r, c(X) = clamp(X_z, −h, h) ẑ the closest point of the segment;
/// ∇Φ = n = (X − c)/|X − c|; ∇∇Φ = (P − n nᵀ)/|X − c| with P = I − ẑ ẑᵀ beside the straight
/// part (|X_z| < h) and P = I about the end caps. On the segment itself the gradient is taken as
/// +x and the Hessian as zero.
struct CapsuleSdf {
  double radius = 0.5;
  double halfLength = 0.5;
  SdfSample Evaluate(const Eigen::Vector3d& X) const;
  double Value(const Eigen::Vector3d& X) const {  ///< Φ only
    const double z = std::clamp(X.z(), -halfLength, halfLength);
    return Eigen::Vector3d(X.x(), X.y(), X.z() - z).norm() - radius;
  }
  /// Fills s->value; the gradient and Hessian too and returns true unless Φ >= bound.
  bool EvaluateBelow(const Eigen::Vector3d& X, double bound, SdfSample* s) const;
};

/// Half space {X : n·X <= offset} with unit normal n: Φ = n·X - offset, ∇Φ = n, ∇∇Φ = 0.
struct PlaneSdf {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;
  SdfSample Evaluate(const Eigen::Vector3d& X) const;
  double Value(const Eigen::Vector3d& X) const { return normal.dot(X) - offset; }  ///< Φ only
  /// Fills s->value; the gradient and Hessian too and returns true unless Φ >= bound.
  bool EvaluateBelow(const Eigen::Vector3d& X, double bound, SdfSample* s) const;
};

}  // namespace superdex
