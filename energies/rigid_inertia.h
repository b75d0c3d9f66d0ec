// Inertia of a rigid body in material-point form (DESIGN.md "Degrees of freedom").
#pragma once

#include <Eigen/Core>

namespace superdex {

/// E(p, R) = ½ m ‖p − p̂‖² + ½ tr((R − R̂) J (R − R̂)ᵀ)   [kg·m²]
/// = ½ ∫ ‖x(X) − x̂(X)‖² dm over the body's material points x = p + R X, x̂ = p̂ + R̂ X, with
/// J = ∫ X Xᵀ dm the second-moment matrix about the centre of mass (body frame) [kg·m²].
/// R̂ need not be a rotation (BDF2's affine combinations of poses), R must be.
/// Derivatives are with respect to the tangent step (δp, δθ) of the retraction
/// p ← p + δp, R ← exp([δθ]×) R, at δ = 0. With M = R J R̂ᵀ:
///   ∂E/∂δp = m (p − p̂),   ∂E/∂δθ = −(M₂₃ − M₃₂, M₃₁ − M₁₃, M₁₂ − M₂₁),
///   ∂²E/∂δp² = m I,       ∂²E/∂δθ² = tr(M) I − ½ (M + Mᵀ),   mixed blocks zero.
/// The rotational block is the world inertia tensor when R̂ = R, and is symmetric but may be
/// indefinite far from R̂ (the stage assembly projects it).
/// The stage weight 1/Δt_i² is applied by the caller.
struct RigidInertiaTerm {
  double value = 0.0;
  Eigen::Matrix<double, 6, 1> gradient = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 6> hessian = Eigen::Matrix<double, 6, 6>::Zero();
};

RigidInertiaTerm RigidInertia(double mass, const Eigen::Matrix3d& secondMoment,
                              const Eigen::Vector3d& p, const Eigen::Matrix3d& R,
                              const Eigen::Vector3d& pHat, const Eigen::Matrix3d& RHat,
                              bool withDerivatives);

/// The global minimizer over p [m] and R ∈ SO(3) of one free body's inertial stage energy
///   Φ(p, R) = E(p, R) / Δt² − m g·p   [J]
/// (E above, Δt the stage step [s], g gravity [m/s²]): the stage of a body that no contact term
/// reaches. p* = p̂ + Δt² g. Since tr(R J Rᵀ) = tr J for every rotation, E's rotational part is
/// const − tr(R (R̂ J)ᵀ), maximized over SO(3) by the rotation factor of R̂ J (orthogonal
/// Procrustes): with R̂ J = U Σ Vᵀ, R* = U diag(1, 1, det(U Vᵀ)) Vᵀ. Exact, no iteration; R̂ need
/// not be a rotation. The mass does not enter; J must be positive definite (a body with volume)
/// for R* to be unique.
struct RigidInertiaMinimum {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
};
RigidInertiaMinimum MinimizeRigidInertia(const Eigen::Matrix3d& secondMoment,
                                         const Eigen::Vector3d& pHat, const Eigen::Matrix3d& RHat,
                                         double dt, const Eigen::Vector3d& gravity);

/// Gravity potential of a body of mass m [kg] with centre of mass at p [m] in gravity g [m/s²]:
/// U = −m g·p [J], ∂U/∂p = −m g, ∂²U/∂p² = 0.
inline double GravityPotential(double mass, const Eigen::Vector3d& g, const Eigen::Vector3d& p) {
  return -mass * g.dot(p);
}

}  // namespace superdex
