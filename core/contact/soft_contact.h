// Contact between a colliding soft actor's surface samples and a rigid collider's field: the
// normal penalty and the stage-discrete dissipation, face by face.
//
// Kinematics of one sample on boundary face (i, j, k) with barycentrics b: y = Σ_a b_a x_a (linear
// in the nodes: the sample's SamplePointMap::Face, with no curvature). The collider side is the
// rigid pullback Y = R_Bᵀ(y − p_B); every term is a function f(Y) chained by the one sample chain
// (core/contact/sample_chain.h: RigidPullbackStencil, then ChainToActor). Stencil per face:
//   [x_i, x_j, x_k]               (9 dofs, B static) or
//   [x_i, x_j, x_k, δp_B, δθ_B]   (15 dofs, B dynamic).
// Penalty: w W(Φ_B(Y)) [J]. Alignment rejection (s = G_B·N_A > m) uses the deformed unit face
// normal n_A and is decided at the reference configuration (x_n), as for rigid pairs.
// Dissipation: Δt_i w R(V_rel), V_rel = (Y − Y⁰)/Δt_i, Y⁰ = (R⁰_B)⁻¹(y⁰ − p⁰_B), with the modes of
// core/contact/rigid_dissipation.h; in the current-geometry modes N_A is the current deformed face normal
// and the residual Jacobian (with the dependence of λ̂_n, N and N_A on the nodes) is computed by
// forward-mode automatic differentiation.
#pragma once

#include <vector>

#include "core/contact/contact_stencil.h"
#include "core/contact/rigid_contact.h"
#include "core/contact/rigid_dissipation.h"
#include "core/model/soft_body.h"

namespace superdex {

/// The soft side of one stage: current positions x, the last actual positions x_n (alignment
/// and explicit-normals geometry; null: use x) and the stage-start positions x⁰ (dissipation).
struct SoftPairInput {
  const SoftBodyModel* model = nullptr;
  const Eigen::VectorXd* x = nullptr;
  const Eigen::VectorXd* xLast = nullptr;
  const Eigen::VectorXd* x0 = nullptr;
};

/// order: 0 value only, 1 with gradient/residual, 2 with Hessian/Jacobian. `dissipation` null:
/// penalty only. One stencil per face with a contribution (ContactStencil::aFace), unprojected.
/// `records` (order 0 only) collects the active penalty samples with their face.
void EvaluateSoftRigidPair(const SoftPairInput& A, const RigidBodyModel& B, const RigidPose& b,
                           const RigidStageStart* b0, bool bDynamic, const PenaltyParams& penalty,
                           double maxAlignment, const DissipationSetup* dissipation, int order,
                           PairStencils* out,
                           std::vector<ContactSampleRecord>* records = nullptr);

}  // namespace superdex
