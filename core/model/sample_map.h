// The material-point map of one colliding surface sample: how its world point y moves with its
// actor's degrees of freedom (DESIGN "Degrees of freedom"). Every actor kind gives its samples one;
// the contact assembler (core/contact/sample_chain.h) chains every sample term through it, so a
// new kind of colliding actor writes its map here and nothing in the contact chain.
#pragma once

#include <Eigen/Core>

namespace superdex {

/// A sample's point map on its actor's stencil dofs q_A:
///   Rigid: y = p_A + R_A X on [δp_A, δθ_A] (6 dofs, retraction R ← exp([δθ]×) R):
///          J = ∂y/∂q_A = [I, −[r]×], r = R_A X [m], and for a force g [N] at y the retraction's
///          curvature ∂²(g·y)/∂δθ² = ½(g rᵀ + r gᵀ) − (g·r) I [N·m].
///   Nodes: y = Σ_a b_a x_a over 1 <= `nodes` <= 4 nodal positions, on [x_0, …, x_{nodes−1}]
///          (3 nodes dofs): J = [b_0 I, …], linear (no curvature). A point mass is one node with
///          b = 1, a triangle's sample three nodes with its barycentrics, a segment's sample two.
struct SamplePointMap {
  enum class Kind { Rigid, Nodes };
  Kind kind = Kind::Nodes;
  Eigen::Vector3d r = Eigen::Vector3d::Zero();       ///< Rigid: y − p_A (world) [m]
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< Rigid: p_A (world) [m]
  Eigen::Vector4d bary = Eigen::Vector4d::Zero();  ///< Nodes: the weights b_a
  int nodes = 0;                                   ///< Nodes: how many

  static SamplePointMap Rigid(const Eigen::Vector3d& r,
                              const Eigen::Vector3d& origin = Eigen::Vector3d::Zero()) {
    SamplePointMap m;
    m.kind = Kind::Rigid;
    m.r = r;
    m.origin = origin;
    return m;
  }
  /// A sample on a triangle with barycentrics b (three nodes).
  static SamplePointMap Face(const Eigen::Vector3d& b) {
    SamplePointMap m;
    m.bary.head<3>() = b;
    m.nodes = 3;
    return m;
  }
  /// The point of one node (a particle).
  static SamplePointMap Point() {
    SamplePointMap m;
    m.bary[0] = 1.0;
    m.nodes = 1;
    return m;
  }
  /// The size of the actor's part of a sample's stencil.
  int Dofs() const { return kind == Kind::Rigid ? 6 : 3 * nodes; }
};

}  // namespace superdex
