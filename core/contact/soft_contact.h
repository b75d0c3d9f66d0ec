// Contact between a colliding soft actor's surface samples and a rigid collider's field: the soft
// actor's colliding role (its face samples, culled face by face) handed to the one assembler of
// core/contact/kind_contact.h.
//
// Kinematics of one sample on boundary face (i, j, k) with barycentrics b: y = Σ_a b_a x_a (the
// sample's SamplePointMap::Face, linear in the nodes), its colliding normal the deformed unit face
// normal, which moves with the nodes. Stencil per face:
//   [x_i, x_j, x_k]               (9 dofs, B static) or
//   [x_i, x_j, x_k, δp_B, δθ_B]   (15 dofs, B dynamic).
// Penalty: w W(Φ_B(Y)) [J]. Alignment rejection (s = G_B·N_A > m) is decided at the reference
// configuration (x_n), as for rigid pairs. Dissipation: Δt_i w R(V_rel), V_rel = (Y − Y⁰)/Δt_i,
// with the modes of core/contact/rigid_dissipation.h; in the current-geometry modes the residual
// Jacobian (with the dependence of λ̂_n, N and N_A on the nodes) is the assembler's AD Jacobian.
#pragma once

#include <vector>

#include "core/contact/contact_stencil.h"
#include "core/contact/kind_contact.h"
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
  int dofOffset = 0;  ///< the actor's first stage dof (node a: dofOffset + 3 freeIndex[a])
};

/// The soft actor's face samples that can contribute on B's field (any frame: a rigid body's, a
/// kind's), culled face by face by the faces' bounding spheres against the field's Lipschitz
/// bound; with dissipation (B.hasStart and A's x⁰) also by the mode's load geometry.
void GatherSoftSamples(const SoftPairInput& A, const FrameSide& B, double delta,
                       const DissipationSetup* dissipation, SampleSink* sink);

/// order: 0 value only, 1 with gradient/residual, 2 with Hessian/Jacobian. `dissipation` null:
/// penalty only. One stencil per face with a contribution (carrying its blocks: the face's nodes,
/// then B's [δp, δθ] at bOffset when B is dynamic, bOffset >= 0), unprojected. `records` (order 0
/// only) collects the active penalty samples.
void EvaluateSoftRigidPair(const SoftPairInput& A, const RigidBodyModel& B, const RigidPose& b,
                           const RigidStageStart* b0, int bOffset, const PenaltyParams& penalty,
                           double maxAlignment, const DissipationSetup* dissipation, int order,
                           PairStencils* out, std::vector<ContactSampleRecord>* records = nullptr);

}  // namespace superdex
