// A soft actor's colliding role: its boundary faces' quadrature samples on a collider's field
// carried by a frame (a rigid body's, a kind's), handed to the one assembler of
// core/contact/kind_contact.h.
//
// Kinematics of one sample on boundary face (i, j, k) with barycentrics b: y = Σ_a b_a x_a (the
// sample's SamplePointMap::Face, linear in the nodes) [m], its colliding normal the deformed unit
// face normal, which moves with the nodes. The assembler opens one stencil per face:
//   [x_i, x_j, x_k]               (9 dofs, B static) or
//   [x_i, x_j, x_k, δp_B, δθ_B]   (15 dofs, B a dynamic rigid body).
#pragma once

#include "core/contact/kind_contact.h"
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

/// The soft actor's face samples that can contribute on B's field, culled face by face: each
/// face's samples lie in a ball about its centroid, now and at x_n, of radius r the larger
/// centroid-to-node distance of the two, tested by BallCulling (spread 2: a sample's Y_n − Y
/// differs from the centroid's by at most 2 r); with dissipation (B.hasStart and A's x⁰) also by
/// the mode's load geometry.
void GatherSoftSamples(const SoftPairInput& A, const FrameSide& B, double delta,
                       const DissipationSetup* dissipation, SampleSink* sink);

}  // namespace superdex
