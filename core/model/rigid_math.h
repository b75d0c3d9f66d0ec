// Rotations: skew matrices (Skew, geometry/skew.h), the SO(3) exponential and logarithm,
// Lie-algebra combinations.
#pragma once

#include <Eigen/Core>

#include "geometry/skew.h"

namespace superdex {

/// The 3 × 3 matrix stored column-major at x[offset .. offset + 8] of a state vector (a rotation
/// or its rate), read or written in place.
template <typename Vector>
Eigen::Map<const Eigen::Matrix3d> Matrix3At(const Vector& x, int offset) {
  return Eigen::Map<const Eigen::Matrix3d>(x.data() + offset);
}
template <typename Vector>
Eigen::Map<Eigen::Matrix3d> Matrix3At(Vector* x, int offset) {
  return Eigen::Map<Eigen::Matrix3d>(x->data() + offset);
}
/// Axial vector of the skew part of A: a with [a]× = ½(A − Aᵀ).
Eigen::Vector3d Axial(const Eigen::Matrix3d& A);
/// exp([θ]×) by Rodrigues' formula (series near θ = 0).
Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& theta);
/// θ with exp([θ]×) = R, |θ| <= π.
Eigen::Vector3d LogSo3(const Eigen::Matrix3d& R);
/// Left Jacobian of SO(3): exp([θ + ε]×) = exp([J_l(θ) ε]×) exp([θ]×) + O(ε²),
///   J_l(θ) = I + (1 − cos t)/t² [θ]× + (t − sin t)/t³ [θ]×²,  t = |θ|   (series near t = 0).
Eigen::Matrix3d LeftJacobianSo3(const Eigen::Vector3d& theta);
/// Nearest rotation to A (polar factor), used to re-orthonormalize after accumulated round-off.
Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& A);

}  // namespace superdex
