// The one chain rule of a contact sample term (the contact assembler's per-sample core).
//
// A term f (penalty density W, or the dissipation Δt_i R) is a function of the pullback
// Y = X_B(y; q_B) of the colliding sample's world point y into the collider's reference frame. Its
// derivatives reach the pair's stencil [q_A, q_B] in two steps:
//   1. the collider's side (its pullback, the collider role of its actor kind): g_Y = ∂f/∂Y and
//      H_Y = ∂²f/∂Y² become the gradient and Hessian of f on the point stencil [y, q_B]
//      (PointStencil): RigidPullbackStencil, or a tet field's TetPullbackStencil
//      (core/contact/tet_field.h);
//   2. the colliding side (ChainToActor): y = y(q_A) through the sample's SamplePointMap
//      (core/model/sample_map.h), with its curvature where the map is nonlinear, times the
//      quadrature weight w [m²], applied here and only here.
// Units: Y, y [m]; g_Y [J/m² per m] for a density per reference area; w [m²].
#pragma once

#include <Eigen/Core>

#include "core/model/sample_map.h"
#include "energies/normal_penalty.h"
#include "energies/stencil.h"
#include "geometry/analytic_sdf.h"

namespace superdex {

/// The penalty density W(Φ_B(Y)) in the collider's point Y [m]: g_Y = W'(φ) ∇Φ [J/m³] and, if
/// HY is not null, H_Y = W''(φ) ∇Φ ∇Φᵀ + W'(φ) ∇²Φ [J/m⁴], φ = Φ_B(Y) (`field` at Y).
inline void PenaltyInPullback(const PenaltyDensity& W, const SdfSample& field, Eigen::Vector3d* gY,
                              Eigen::Matrix3d* HY) {
  *gY = W.dW * field.gradient;
  if (HY) *HY = W.d2W * field.gradient * field.gradient.transpose() + W.dW * field.hessian;
}

/// f on the point stencil [y, q_B]: 3 + colliderDofs entries (q_B: 6 for a dynamic rigid
/// collider [δp_B, δθ_B], 12 for a soft collider's tet, 0 for a static collider).
struct PointStencil {
  static constexpr int kMax = 15;
  int colliderDofs = 0;
  Eigen::Matrix<double, kMax, 1> g;
  Eigen::Matrix<double, kMax, kMax> H;  ///< only with a Hessian
  int Size() const { return 3 + colliderDofs; }
};

/// A rigid collider B's pullback Y = R_Bᵀ(y − p_B) on the point stencil [y, δp_B, δθ_B] (B's part
/// only when `bDynamic`). With n = R_B g_Y, d = y − p_B and the world Hessian H_w = R_B H_Y R_Bᵀ:
///   ∇f = [n, −n, −d × n],   ∇²f = J_pᵀ H_w J_p + S,   J_p = [I, −I, [d]×],
///   S_θθ = ½(n dᵀ + d nᵀ) − (n·d) I,  S_θy = [n]×,  S_θp = −[n]×  (and their transposes),
/// S the curvature of B's retraction. `HY` null: gradient only.
void RigidPullbackStencil(const Eigen::Matrix3d& RB, const Eigen::Vector3d& d,
                          const Eigen::Vector3d& gY, const Eigen::Matrix3d* HY, bool bDynamic,
                          PointStencil* out);

/// Adds w times f's derivatives on the pair stencil [q_A (map.Dofs()), q_B] to *g (and *H when
/// not null and the point stencil carries a Hessian):
///   ∇_A = Jᵀ g_y,  ∇_B = g_B,
///   ∇²_AA = Jᵀ H_yy J + C(g_y),  ∇²_AB = Jᵀ H_yB,  ∇²_BB = H_BB,
/// J the map's Jacobian and C its curvature contracted with g_y (rigid maps only).
void ChainToActor(const SamplePointMap& map, const PointStencil& point, double w,
                  StencilVector* g, StencilMatrix* H);

}  // namespace superdex
