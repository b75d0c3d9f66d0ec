// Right-preconditioned BiCGSTAB (van der Vorst, 1992) for the unsymmetric Krylov solves of
// optim/linear_solver.cpp, on the parallel row operator (optim/row_operator.h) with the
// block-Jacobi preconditioner M (optim/block_jacobi.h). Its vectors live in a workspace kept by
// the caller, so a solve allocates nothing once the workspace has the system's size (Eigen's
// routine declares its ten work vectors, and returns two preconditioned vectors, per call).
//
// From x = 0: r = b, shadow residual r̂ = r, ρ = α = ω = 1, v = p = 0; each iteration
//   ρ' = r̂·r                       (if |ρ'| < ε² ‖r̂‖², r has become orthogonal to r̂: restart
//                                    with r = b − A x, r̂ = r, ρ' = ‖r‖²; ε the machine epsilon)
//   β = (ρ'/ρ)(α/ω),  p = r + β (p − ω v),  y = M⁻¹ p,  v = A y,  α = ρ'/(r̂·v)
//   s = r − α v,  z = M⁻¹ s,  t = A z,  ω = (t·s)/(t·t)  (0 when t·t is not positive)
//   x += α y + ω z,  r = s − ω t,  ρ = ρ'
// while ‖r‖² > tol² ‖b‖² and fewer than maxIterations iterations ran. The operations, their
// order and the stopping rule are those of Eigen's `internal::bicgstab` on a matrix-free operator
// (which the solver used before), so the iterates are the same bit for bit; one difference: Eigen
// resets its iteration count at the first restart, this count runs on (maxIterations bounds the
// whole solve).
#pragma once

#include <Eigen/Core>

#include "optim/block_jacobi.h"
#include "optim/row_operator.h"

namespace superdex {

/// The vectors of a BiCGSTAB solve, kept between solves.
struct BiCgStabWorkspace {
  Eigen::VectorXd r, shadow, p, v, y, z, s, t;
};

/// How a solve ended.
struct BiCgStabResult {
  int iterations = 0;
  double relativeResidual = 0.0;  ///< ‖r‖ / ‖b‖ of the recursively updated residual [-]
  bool converged = false;         ///< ‖r‖ <= tolerance ‖b‖ (true at once for b = 0)
};

/// Solves A x = b into *x (resized; x = 0 for b = 0) with at most maxIterations iterations.
BiCgStabResult SolveBiCgStab(const RowOperator& A, const BlockJacobi& M, const Eigen::VectorXd& b,
                             double tolerance, int maxIterations, Eigen::VectorXd* x,
                             BiCgStabWorkspace* work);

}  // namespace superdex
