// A kind's tet field as a collider side (experimental, spec: "Contact Kinematics"): the grid SDF
// Φ_B of its reference surface, mapped by the deformation (ActorKind::TetCollider). For a query
// point y the pullback X_B(y) is found in the deformed tet t that contains y and inverted through
// its affine map:
//   β = Ds⁻¹ (y − x_0),  λ = (1 − Σβ, β),  X = X_0 + Dm β,   F = Ds Dm⁻¹,  F⁻¹ = Dm Ds⁻¹,
// Ds, Dm the tet's deformed and reference edge matrices. Points in no tet are rejected. The
// spatial field φ_B(y) = Φ_B(X_B(y)) is not an exact SDF; V_rel = (X − X⁰)/Δt_i is measured in
// B's reference coordinates (its magnitude follows the local stretch F⁻¹), and the colliding
// normal enters the alignment test as Fᵀ n_A, normalized (normals map by the transpose).
//
// Derivatives of f(X) on the point stencil z = [y, x_0, x_1, x_2, x_3] (15 dofs):
//   ∂X/∂z = F⁻¹ R,  R = [I, −λ_0 I, −λ_1 I, −λ_2 I, −λ_3 I]
//   ∇_z f = Rᵀ F⁻ᵀ g,   g = ∂f/∂X
//   ∇²_z f = Rᵀ F⁻ᵀ H F⁻¹ R − Σ_a (u_a v_aᵀ + v_a u_aᵀ),  u_a = Rᵀ L_aᵀ, v_a = c at x_a, c = F⁻ᵀ g,
// with L the 4 × 3 matrix of dλ/dr (rows of Ds⁻¹, row 0 minus their sum), r = dy − Σ λ_a dx_a.
// The one assembler (core/contact/kind_contact.h) chains it to the colliding actor like a frame's
// pullback; a world covector of B's reference coordinates (the field's gradient, a traction) is
// F⁻ᵀ v.
//
// Tet choice per term: the penalty and the current-geometry dissipation modes use the tet
// containing the current y (the pullback is continuous across tets; its derivative jumps), and
// that tet's affine map at x_n and x⁰ for their stage-start quantities (the alignment reference,
// the reconstructed load's X_n, X⁰ of V_rel). In ExplicitNormals mode the dissipation uses the tet
// that contains y_n at x_n, so that the dissipation potential is smooth in q within the stage.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/contact/sample_chain.h"
#include "core/model/soft_body.h"
#include "geometry/aabb.h"
#include "geometry/tet_locator.h"

namespace superdex {

/// The affine pullback through tet `tet` of B at some node positions (extended beyond the tet).
struct TetPullback {
  int tet = -1;
  Eigen::Vector4d lambda;
  Eigen::Vector3d X;     ///< reference point [m]
  Eigen::Matrix3d B;     ///< Ds⁻¹ [1/m]
  Eigen::Matrix3d Finv;  ///< Dm Ds⁻¹
  Eigen::Matrix3d F;     ///< Ds Dm⁻¹
};

/// The pullback of y through tet t of model m at positions x; false (nothing written) when the
/// tet is inverted or degenerate there.
bool PullbackThrough(const SoftBodyModel& m, const Eigen::VectorXd& x, int t,
                     const Eigen::Vector3d& y, TetPullback* pb);

/// f(X) on the point stencil z = [y, x_0..x_3] (header formulas), unweighted: gradient from
/// gX = ∂f/∂X, Hessian from HX = ∂²f/∂X² when not null.
void TetPullbackStencil(const TetPullback& pb, const Eigen::Vector3d& gX,
                        const Eigen::Matrix3d* HX, PointStencil* out);

/// The unit direction of Fᵀ n (zero for a zero vector): a world normal in B's reference
/// coordinates.
Eigen::Vector3d ReferenceNormal(const TetPullback& pb, const Eigen::Vector3d& n);

/// Whether a colliding sample (a KindSample or a PairSample) collides on a tet field: its normal
/// must move with its dofs, a rigid map's or a deforming face's. Samples without a colliding
/// normal (a particle's) are not supported there yet.
template <typename Sample>
bool CollidesOnTetField(const Sample& s) {
  return s.hasNormal && (s.map.kind == SamplePointMap::Kind::Rigid || s.faceNormal);
}

/// The collider B at one evaluation: its tet field now, at x_n and at the stage start, the point
/// locators over x and x_n (built by the caller), the stage dof of each local dof (node a: 3a; −1
/// prescribed), and the bounding boxes of x and x_n (padded for round-off).
struct TetFieldSide {
  const SoftBodyModel* model = nullptr;
  const Eigen::VectorXd* x = nullptr;
  const Eigen::VectorXd* xLast = nullptr;  ///< x when there is no x_n
  const Eigen::VectorXd* x0 = nullptr;     ///< null: no stage start (no dissipation)
  const TetLocator* locator = nullptr;
  const TetLocator* locatorLast = nullptr;
  const std::vector<int>* nodeDof = nullptr;
  Aabb box, boxLast;
  /// Sets the boxes from x and x_n.
  void FormBoxes();
  /// The stage offset of tet t's node c.
  int NodeOffset(int t, int c) const { return (*nodeDof)[3 * model->rest.tets[t][c]]; }
};

}  // namespace superdex
