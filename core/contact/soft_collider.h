// A soft body as a collider (experimental, spec: "Contact Kinematics"): the grid SDF Φ_B of its
// reference surface, mapped by the deformation (a kind's tet field, ActorKind::TetCollider). For
// a query point y the pullback X_B(y) is found in the deformed tet t that contains y and inverted
// through its affine map:
//   β = Ds⁻¹ (y − x_0),  λ = (1 − Σβ, β),  X = X_0 + Dm β,   F = Ds Dm⁻¹,  F⁻¹ = Dm Ds⁻¹,
// Ds, Dm the tet's deformed and reference edge matrices. Points in no tet are rejected. The
// spatial field φ_B(y) = Φ_B(X_B(y)) is not an exact SDF; V_rel = (X − X⁰)/Δt_i is measured in
// B's reference coordinates (its magnitude follows the local stretch F⁻¹), and the colliding
// normal enters the alignment test as Fᵀ n_A (normals map by the transpose).
//
// Derivatives of f(X) on the point stencil z = [y, x_0, x_1, x_2, x_3] (15 dofs):
//   ∂X/∂z = F⁻¹ R,  R = [I, −λ_0 I, −λ_1 I, −λ_2 I, −λ_3 I]
//   ∇_z f = Rᵀ F⁻ᵀ g,   g = ∂f/∂X
//   ∇²_z f = Rᵀ F⁻ᵀ H F⁻¹ R − Σ_a (u_a v_aᵀ + v_a u_aᵀ),  u_a = Rᵀ L_aᵀ, v_a = c at x_a, c = F⁻ᵀ g,
// with L the 4 × 3 matrix of dλ/dr (rows of Ds⁻¹, row 0 minus their sum), r = dy − Σ λ_a dx_a.
// The point y is then chained to the colliding actor A through its sample's SamplePointMap by
// the one sample chain (core/contact/sample_chain.h, ChainToActor): a rigid sample y = p_A + R_A X_A
// (6 dofs, with the rotation's curvature) or a deforming face's sample y = Σ b_a x_a (9 dofs).
// Each active sample contributes one stencil [A's dofs, the 4 tet nodes of B].
//
// Tet choice per term: the penalty uses the tet containing the current y (the pullback is
// continuous across tets; its derivative jumps). Stage-start quantities (X⁰ for V_rel, X_n for
// the reconstructed load, the alignment reference) use that tet's affine map at x⁰ and x_n. In
// ExplicitNormals mode every term of a sample uses the tet that contains y_n at x_n, so that the
// dissipation potential is smooth in q within the stage.
#pragma once

#include <vector>

#include "core/contact/contact_stencil.h"
#include "core/contact/rigid_contact.h"
#include "core/contact/rigid_dissipation.h"
#include "core/model/actor_kind.h"
#include "core/model/soft_body.h"
#include "geometry/tet_locator.h"

namespace superdex {

/// The collider B at one stage, a kind's tet field (ActorKind::TetCollider): positions now, at
/// x_n and at the stage start, point locators for the current and last configurations (built by
/// the caller), and the stage dof of each of its local dofs (node a: 3a; −1 prescribed).
struct SoftColliderInput {
  const SoftBodyModel* model = nullptr;
  const Eigen::VectorXd* x = nullptr;
  const Eigen::VectorXd* xLast = nullptr;  ///< null: x
  const Eigen::VectorXd* x0 = nullptr;     ///< null: no dissipation
  const TetLocator* locator = nullptr;     ///< over x
  const TetLocator* locatorLast = nullptr; ///< over xLast (explicit normals)
  const std::vector<int>* nodeDof = nullptr;
};

/// The colliding actor A: a kind's sample body (a rigid body's pose and stage start, its [δp, δθ]
/// at the stage dofs bodyOffs), or a kind's own samples (ActorKind::Sample at q = x, x_n = xLast,
/// x⁰ = x0; their local dofs at the stage dofs `stageDof`). A kind's sample takes part only with a
/// colliding normal that is a rigid map's or a deforming face's (KindSample::faceNormal); others
/// are skipped.
struct CollidingInput {
  const RigidBodyModel* rigid = nullptr;
  const RigidPose* pose = nullptr;
  const RigidStageStart* start = nullptr;  ///< rigid A's x⁰ and x_n (null: the pose)
  int bodyOffs[2] = {-1, -1};
  const ActorKind* kind = nullptr;
  const std::vector<int>* stageDof = nullptr;  ///< kind A
  const Eigen::VectorXd* x = nullptr;
  const Eigen::VectorXd* xLast = nullptr;
  const Eigen::VectorXd* x0 = nullptr;
};

/// Whether a kind's sample can collide on a soft collider's field (see CollidingInput).
inline bool CollidesOnSoftField(const KindSample& s) {
  return s.hasNormal && (s.map.kind == SamplePointMap::Kind::Rigid || s.faceNormal);
}

/// Penalty (and, with `dissipation`, the stage-discrete dissipation) of A's samples against the
/// soft collider B. order 0/1/2 as elsewhere. One stencil per active sample and term (penalty or
/// dissipation) on [A's dofs (6 rigid | 9 face | a kind's sample map's), B's tet (12)],
/// unprojected, carrying its blocks (ContactStencil::blocks, offs: A's, then B's four nodes).
/// `records` (order 0) collects active penalty samples.
void EvaluatePairOnSoftCollider(const CollidingInput& A, const SoftColliderInput& B,
                                const PenaltyParams& penalty, double maxAlignment,
                                const DissipationSetup* dissipation, int order,
                                PairStencils* out,
                                std::vector<ContactSampleRecord>* records = nullptr);

}  // namespace superdex
