// Elastic energies of thin shells on triangle meshes: a membrane term per triangle and a bending
// term per interior edge (hinge). Units: SI (m, Pa, J).
//
// Membrane: Saint Venant–Kirchhoff in plane stress on constant-strain triangles. A triangle's
// rest nodes X0, X1, X2 define a 2-D rest frame (t1 along X1 − X0, t2 = n × t1) in which
// Dm = [X1 − X0, X2 − X0] is 2 × 2; its deformation gradient is the 3 × 2 matrix
//   F = [x1 − x0, x2 − x0] Dm⁻¹,   E = ½ (FᵀF − I)   (Green strain, 2 × 2),
//   W_m = h A ( μ tr(E²) + λ_s/2 (tr E)² )                                           [J]
// with thickness h [m], rest area A [m²], μ = E_Y/(2(1 + ν)) and the plane-stress
// λ_s = E_Y ν/(1 − ν²) [Pa]. StVK is chosen for its exact small-strain limit (a membrane of
// E_Y h, ν) and its polynomial derivatives; under compression it is indefinite (buckling is the
// bending term's business), so the projected Hessian clamps its eigenvalues.
// Stress: S = 2μ E + λ_s tr(E) I, P = F S (3 × 2); ∂W_m/∂x from P Dm⁻ᵀ.
//
// Bending: the hinge model of discrete shells (Grinspun, Hirani, Desbrun, Schröder, "Discrete
// Shells", SCA 2003) with the stiffness of a Kirchhoff plate: for an interior edge with rest
// length |ē| shared by triangles of rest areas A₁, A₂, and dihedral angle θ (0 when flat, signed),
//   W_b = k_e (θ − θ̄)²,   k_e = D |ē|² / (2 (A₁ + A₂)),   D = E_Y h³ / (12 (1 − ν²))     [J]
// θ̄ the rest angle. On a regular mesh bent to a cylinder of radius R (edges along the axis,
// θ = s/R for a spacing s) the sum is D/2 κ² per unit area: the plate's energy of cylindrical
// bending. The hinge model measures the mean curvature only, W ≈ D/2 ∫ (κ₁ + κ₂)² dA, without
// the plate's Poisson term −D (1 − ν) ∫ κ₁κ₂ dA: a null Lagrangian inside, but it sets a free
// edge's moment, so a plate with free edges is too soft with hinges (it relaxes
// anticlastically: a square cantilever at ν = 0 deflects 28 % more than Kirchhoff's on a 16 × 16
// mesh). Plates and shells take the mid-edge model (energies/shell_midedge.h); the hinge is the
// cheaper model for cloth.
// The angle: with e = x1 − x0 (the hinge, nodes 0 and 1), a = x2 − x0 and b = x3 − x0 (the two
// wings), n_A = e × a, n_B = b × e,
//   c = n_A·n_B = (e·b)(a·e) − (e·e)(a·b),   s = (n_A × n_B)·ê = −|e| det[e, a, b],
//   θ = atan2(s, c),
// so that θ's gradient and Hessian follow from those of dot products, a determinant and |e|:
// closed forms, no normalized normals (tests/energies/test_shell_energies.cpp checks them).
#pragma once

#include <Eigen/Core>

#include "energies/stable_neo_hookean.h"

namespace superdex {

/// Rest data of a membrane triangle: Dm⁻¹ in its rest frame [1/m] and its rest area [m²].
struct ShellTriangle {
  Eigen::Matrix2d DmInv = Eigen::Matrix2d::Identity();
  double restArea = 0.0;
};

/// The rest data of the triangle X0, X1, X2 [m] (a degenerate one has restArea 0).
ShellTriangle MakeShellTriangle(const Eigen::Vector3d& X0, const Eigen::Vector3d& X1,
                                const Eigen::Vector3d& X2);

/// Plane-stress Lamé parameters of a membrane [Pa]: μ = E/(2(1+ν)), λ_s = Eν/(1−ν²).
LameParameters PlaneStressLame(double youngsModulus, double poissonRatio);

/// W_m of the triangle at node positions x (9 entries [x0; x1; x2]) [J]; order >= 1 adds its
/// gradient into *g (9), order 2 its Hessian into *H (9 × 9), projected to PSD with `project`.
double MembraneEnergy(const Eigen::Matrix<double, 9, 1>& x, const ShellTriangle& t,
                      const LameParameters& lame, double thickness, int order, bool project,
                      Eigen::Matrix<double, 9, 1>* g, Eigen::Matrix<double, 9, 9>* H);

/// The signed dihedral angle θ of the hinge x = [x0; x1; x2; x3] (hinge x0–x1, wings x2, x3)
/// [rad], with order >= 1 its gradient into *g (12) and order 2 its Hessian into *H (12 × 12)
/// (both written, not added).
double HingeAngle(const Eigen::Matrix<double, 12, 1>& x, int order,
                  Eigen::Matrix<double, 12, 1>* g, Eigen::Matrix<double, 12, 12>* H);

/// Bending stiffness k_e = D |ē|² / (2 (A₁ + A₂)) of a hinge [J/rad²] from its rest edge length
/// [m], rest wing areas [m²] and the plate stiffness D [N·m].
double HingeStiffness(double restEdgeLength, double restAreaSum, double plateStiffness);

/// W_b = k (θ − θ̄)² of the hinge at x [J]; order >= 1 adds the gradient into *g, order 2 the
/// Hessian into *H, projected to PSD with `project`.
double HingeBendingEnergy(const Eigen::Matrix<double, 12, 1>& x, double stiffness,
                          double restAngle, int order, bool project,
                          Eigen::Matrix<double, 12, 1>* g, Eigen::Matrix<double, 12, 12>* H);

}  // namespace superdex
