// Symmetric triangle quadrature rules for surface contact sampling.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace superdex {

/// Quadrature rule on each boundary face of rigid, soft and articulated actors (spec:
/// "Surface Quadrature"). Linear (P1) faces; Qn = n points per face.
enum class ActorBoundaryElementType {
  P1Q1,               ///< 1 point, exact for degree 1
  P1Q3,               ///< 3 points, exact for degree 2 (default)
  P1Q6,               ///< 6 points, exact for degree 4
  ExperimentalP1Q7,   ///< 7 points, exact for degree 5
  ExperimentalP1Q12,  ///< 12 points, exact for degree 6
  ExperimentalP1Q16,  ///< 16 points, exact for degree 8
};

/// A rule on the reference triangle: points in barycentric coordinates (each sums to 1),
/// weights positive and summing to 1, so that  ∫_T f dA ≈ area(T) Σ_i w_i f(Σ_j b_ij v_j).
struct TriangleQuadratureRule {
  std::vector<Eigen::Vector3d> barycentric;
  std::vector<double> weights;
  int degree = 0;  ///< highest total polynomial degree integrated exactly
};

/// The rule for `type`; built once, valid for the program's lifetime, thread-safe. The tabulated
/// orbit parameters are refined at first use by Newton's method on the symmetric moment equations,
/// so every rule integrates its degree exactly to double round-off. A value outside the
/// enumeration yields the default rule, P1Q3.
const TriangleQuadratureRule& GetTriangleQuadratureRule(ActorBoundaryElementType type);

}  // namespace superdex
