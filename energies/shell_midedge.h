// Kirchhoff–Love bending of a shell triangle from its discrete second fundamental form with
// mid-edge normals (the "mid-edge average" shape operator; Chen, Chen, Vouga et al., "Physical
// simulation of environmentally induced thin shell deformation", ACM TOG 37(4), 2018).
//
// A triangle q0, q1, q2 (counter-clockwise) with unit normal n; across its edge i (opposite q_i)
// the neighbouring triangle (q_{i+2}, q_{i+1}, p_i) has unit normal n_i, and the mid-edge normal is
// m_i = (n + n_i)/|n + n_i| (on a free boundary edge m_i = n + φ_i t_i, t_i its in-plane unit
// normal, with φ_i minimizing W; held at its rest value on a clamped edge). Interpolating the
// mid-edge normals
// linearly over the triangle, n(u, v) = Σ_i (1 − 2λ_i) m_i, gives the second fundamental form
// II_ab = −r_a·n_b in the edge basis r_u = q1 − q0, r_v = q2 − q0:
//   II = 2 [ (q1−q0)·(m1−m0)  (q1−q0)·(m2−m0) ; (q2−q0)·(m1−m0)  (q2−q0)·(m2−m0) ]  (symmetrized),
// and with the rest first fundamental form ā = [r̄_a·r̄_b] and rest ĪI, the shape-operator change
// M = ā⁻¹ (II − ĪI). The bending energy of the plate of thickness h, with the plane-stress Lamé
// parameters μ, λ_s:
//   W = h³/12 · Ā · ( μ tr(M²) + λ_s/2 (tr M)² )                                          [J]
// For a cylinder of curvature κ this is D/2 κ² Ā and for a sphere D (1 + ν) κ² Ā, D = E h³ /
// (12 (1 − ν²)): Kirchhoff's D/2 [(κ₁ + κ₂)² − 2 (1 − ν) κ₁κ₂] with its Poisson term (which the
// hinge model lacks), so that a plate's free edges behave as the plate's. A free edge's angle
// φ_i is the discrete natural boundary condition (no moment across the edge): W is quadratic in
// φ, so φ* = −A⁻¹ b per evaluation and the triangle's energy is W*(x) = W(x, φ*(x)), with
// gradient ∂W/∂x at φ* and Hessian W_xx − W_xφ W_φφ⁻¹ W_φx. The mid-edge average converges on
// regular meshes. Derivatives: W is written once as a template on the scalar type and evaluated
// on second-order jets (energies/second_order_jet.h) for its exact gradient and Hessian in the 18
// coordinates of q0, q1, q2, p0, p1, p2 (and the free edges' φ, condensed).
#pragma once

#include <Eigen/Core>

#include "energies/stable_neo_hookean.h"

namespace superdex {

/// How a triangle's edge i (opposite q_i) gets its mid-edge normal m_i: a free boundary edge's
/// is minimized over (m_i = n + φ_i t_i), a shared one is the neighbours' average
/// (m_i = (n + n_i)/|n + n_i|), a held one a given unit vector (a clamped edge: its rest
/// mid-edge normal).
enum class MidedgeEdge { Boundary, Shared, Held };

/// The rest data of a mid-edge bending triangle.
struct MidedgeTriangle {
  Eigen::Matrix2d abarInv = Eigen::Matrix2d::Identity();  ///< ā⁻¹ [1/m²]
  Eigen::Matrix2d IIbar = Eigen::Matrix2d::Zero();        ///< rest II [m]
  double restArea = 0.0;                                  ///< Ā [m²]
  MidedgeEdge edge[3] = {MidedgeEdge::Boundary, MidedgeEdge::Boundary, MidedgeEdge::Boundary};
  Eigen::Vector3d held[3];                                ///< m_i of a Held edge
};

/// The triangle's 18 coordinates: q0, q1, q2, p0, p1, p2 (a missing p_i's entries unused).
using MidedgeStencil = Eigen::Matrix<double, 18, 1>;

/// The rest data from rest coordinates X: edge i is Shared where hasNeighbour[i], Held where
/// held[i] (its rest mid-edge normal kept), else Boundary.
MidedgeTriangle MakeMidedgeTriangle(const MidedgeStencil& X, const bool hasNeighbour[3],
                                    const bool held[3] = nullptr);

/// The second fundamental form II (symmetrized) of triangle t's stencil at coordinates x [m].
Eigen::Matrix2d MidedgeSecondFundamentalForm(const MidedgeStencil& x, const MidedgeTriangle& t);

/// W at x [J]; order >= 1 adds its gradient into *g, order 2 its Hessian into *H (18 × 18;
/// projected to PSD with `project`). Entries of a missing neighbour are zero.
double MidedgeBendingEnergy(const MidedgeStencil& x, const MidedgeTriangle& t,
                            const LameParameters& lame, double thickness, int order, bool project,
                            Eigen::Matrix<double, 18, 1>* g, Eigen::Matrix<double, 18, 18>* H);

}  // namespace superdex
