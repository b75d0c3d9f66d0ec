// Per-tet elastic energy of soft bodies: the stable neo-Hookean model of Smith, de Goes and Kim,
// "Stable Neo-Hookean Flesh Simulation" (ACM TOG 37(2), 2018), on linear (constant-strain)
// tetrahedra.
//
// Energy density, in the paper's rest-stable form (its §3.4) with its Lamé re-parametrization
// (§3.5), written with the classic (small-strain) Lamé parameters μ, λ [Pa] of the material:
//
//   Ψ(F) = μ'/2 (I_C − 3) + λ'/2 (J − α)² − μ'/2 log(I_C + 1) − Ψ₀                      [J/m³]
//
//   I_C = tr(FᵀF) = ‖F‖²,  J = det F,
//   μ' = 4/3 μ,  λ' = λ + 5/6 μ,  α = 1 + 3μ'/(4λ') = 1 + μ/λ',
//   Ψ₀ = λ'/2 (1 − α)² − μ'/2 log 4   (a constant: makes Ψ(I) = 0).
//
// Expanded (how it is evaluated; α never appears, so no cancellation through α − 1):
//
//   Ψ(F) = 2μ/3 (I_C − 3) − 2μ/3 log(1 + (I_C − 3)/4) + λ'/2 (J − 1)² − μ (J − 1)
//
// Properties (all checked by tests/energies/test_stable_neo_hookean.cpp):
//  (a) Ψ(I) = 0 and P(I) = 0 (rest stability: the α shift cancels the log term's rest stress);
//  (b) the second-order expansion at F = I is μ ‖sym H‖² + λ/2 (tr H)² for F = I + H: linear
//      elasticity with exactly the given μ, λ (this is what μ', λ' are chosen for);
//  (c) Ψ is a polynomial in F plus log(I_C + 1) with I_C + 1 >= 1: defined and C^∞ for every F,
//      including degenerate (J = 0) and inverted (J < 0) elements, where the force pushes back
//      towards J > 0. Exception: F = 0 (the element collapsed to a point) is a stationary point
//      (P = 0 and ∂²Ψ/∂F² = 0 there), so it exerts no restoring force at exactly that state.
// λ' > 0 for every admissible Poisson ratio (−1 < ν < 1/2), so α is always finite.
//
// Stress and stress derivative [Pa]:
//   P = ∂Ψ/∂F = μ' (1 − 1/(I_C + 1)) F + κ cof F,   κ = λ'(J − α) = λ'(J − 1) − μ,
//   ∂²Ψ/∂F² = μ'(1 − 1/(I_C+1)) I₉ + 2μ'/(I_C+1)² f fᵀ + λ' g gᵀ + κ H_J
// with f = vec F, g = vec cof F = vec ∂J/∂F and H_J = ∂²J/∂F² (vec: column-major, F_ab at a + 3b).
//
// Hessian projection (projectPsd): the analytic eigensystem of the paper (§4). With the
// rotation-variant SVD F = U Σ Vᵀ (U, V rotations, σ₃ carrying the sign of J):
//   twist modes U (e_i e_jᵀ − e_j e_iᵀ) Vᵀ/√2:  μ'(1 − 1/(I_C+1)) + κ σ_k
//   flip modes  U (e_i e_jᵀ + e_j e_iᵀ) Vᵀ/√2:  μ'(1 − 1/(I_C+1)) − κ σ_k    ({i, j, k} = {1, 2, 3})
//   scaling modes U diag(z) Vᵀ: z, eigenvalue from the 3×3 matrix
//     A_ij = μ'(1 − 1/(I_C+1)) δ_ij + 2μ'/(I_C+1)² σ_i σ_j + λ' J²/(σ_i σ_j) + κ (1 − δ_ij) σ_k
//     (with J/σ_i written as the product of the other two singular values).
// The negative eigenvalues are clamped to zero and ∂²Ψ/∂F² is rebuilt from the 9 modes, then
// mapped to the nodes by the (constant) 9×12 ∂F/∂x: the result is exactly PSD (up to rounding)
// and keeps the rigid null space (rotations are zero twist modes at rest, translations are the
// null space of ∂F/∂x). When ∂²Ψ/∂F² is PSD already it is returned unchanged (bit for bit; a
// Cholesky test skips the SVD when it is positive definite), except that a rounding-level
// negative eigenvalue of a semi-definite one (e.g. the rotation modes at rest) may be clamped.
#pragma once

#include <Eigen/Core>
#include <string>

namespace superdex {

/// Classic Lamé parameters of an isotropic material [Pa]: μ (shear modulus) and λ.
struct LameParameters {
  double mu = 0.0;      ///< μ [Pa]
  double lambda = 0.0;  ///< λ [Pa]
};

/// μ = E/(2(1+ν)), λ = Eν/((1+ν)(1−2ν)) [Pa] from Young's modulus E [Pa] and Poisson's ratio ν
/// [-]. Valid for E > 0, −1 < ν < 1/2 (core/model/soft_body.h: kSoftMaterialFields).
LameParameters LameFromYoungPoisson(double youngsModulus, double poissonRatio);

/// Ψ(F) [J/m³] (header comment). Any F, also J <= 0.
double StableNeoHookeanEnergyDensity(const Eigen::Matrix3d& F, const LameParameters& p);

/// First Piola–Kirchhoff stress P = ∂Ψ/∂F [Pa].
Eigen::Matrix3d StableNeoHookeanStress(const Eigen::Matrix3d& F, const LameParameters& p);

/// ∂²Ψ/∂F² [Pa] as a 9×9 matrix over column-major vec F; with projectPsd, projected to PSD by
/// the analytic eigensystem (header comment).
Eigen::Matrix<double, 9, 9> StableNeoHookeanStressDerivative(const Eigen::Matrix3d& F,
                                                            const LameParameters& p,
                                                            bool projectPsd);

/// Rest-state data of a linear tetrahedron with rest nodes X0..X3 [m]:
/// Dm = [X1 − X0, X2 − X0, X3 − X0], DmInv = Dm⁻¹ [1/m], restVolume = det(Dm)/6 [m³].
struct TetElement {
  Eigen::Matrix3d DmInv = Eigen::Matrix3d::Identity();
  double restVolume = 0.0;
};

/// Fills *out and returns true, or returns false (leaving *out unchanged) when the rest tet is
/// inverted (det Dm < 0), degenerate (det Dm <= 1e-10 ‖X1−X0‖ ‖X2−X0‖ ‖X3−X0‖, i.e. the
/// normalized volume is below 1e-10) or not finite.
bool MakeTetElement(const Eigen::Vector3d X[4], TetElement* out);

/// One tet's elastic energy and its derivatives with respect to the 12 node coordinates
/// (x0, y0, z0, x1, …, z3).
struct TetElasticTerm {
  double value = 0.0;                                                      ///< V Ψ(F) [J]
  Eigen::Matrix<double, 12, 1> gradient = Eigen::Matrix<double, 12, 1>::Zero();   ///< [N]
  Eigen::Matrix<double, 12, 12> hessian = Eigen::Matrix<double, 12, 12>::Zero();  ///< [N/m]
  double detF = 1.0;  ///< J = det F [-] (< 0: the element is inverted)
};

/// F = Ds Dm⁻¹ with Ds = [x1 − x0, x2 − x0, x3 − x0] at the deformed nodes x [m], then
///   value = V Ψ(F),  gradient_i = V P Dm⁻ᵀ e_i (nodes 1..3), gradient_0 = −Σ others,
///   hessian = V Bᵀ ∂²Ψ/∂F² B  with B = ∂vec F/∂x (9×12, constant).
/// order 0: value (and detF); 1: also gradient; 2: also hessian. The fields not computed are
/// zeroed. projectPsd (order 2 only): the analytic PSD projection of ∂²Ψ/∂F² (header comment).
/// The value does not depend on order or projectPsd (the same operations in the same order).
/// No heap allocation.
void EvaluateStableNeoHookean(const TetElement& e, const LameParameters& p,
                              const Eigen::Vector3d x[4], int order, bool projectPsd,
                              TetElasticTerm* out);

}  // namespace superdex
