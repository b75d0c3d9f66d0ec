// The regularized linear solve of both Newton solvers (optim/newton_solver.h,
// optim/residual_newton.h): d = −A⁻¹ b; where A does not factorize or d is not acceptable,
// d = −(A + τI)⁻¹ b for τ = τ₀, 10 τ₀, 100 τ₀, ... (kMaxShiftRetries shifts, τ₀ = kInitialShift ·
// max_i |A_ii|), the first acceptable d taken:
//   ShiftGoal::Descent (A symmetric, b the gradient g): d finite and g·d < 0. The scale falls
//     back to max_ij |A_ij|, then 1, on a zero diagonal. After the ladder one last shift
//     τ >= max_i (Σ_{j≠i} |A_ij| − A_ii) + scale (Gershgorin: A + τI strictly diagonally dominant
//     with a positive diagonal, hence positive definite).
//   ShiftGoal::Nonsingular (A general, b the residual r): d finite. The scale falls back to 1.
// See docs/solver.md.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "optim/linear_solver.h"
#include "optim/newton_solver.h"

namespace superdex {

/// Diagonal shifts tried after the unshifted factorization fails: τ_k = τ₀ 10^k, k < this.
constexpr int kMaxShiftRetries = 12;
/// First shift relative to the matrix's scale: τ₀ = kInitialShift max_i |A_ii|.
constexpr double kInitialShift = 1e-8;

enum class ShiftGoal {
  Descent,      ///< a descent direction of the potential whose gradient is b
  Nonsingular,  ///< any finite solution
};

struct RegularizedSolve {
  bool solved = false;     ///< d is acceptable
  double lastShift = 0.0;  ///< the last τ tried (0: none)
};

/// *x = A⁻¹ b by solver.Solve (a SymmetricSolver or UnsymmetricSolver), adding its Krylov
/// iterations and fallbacks to *stats.
template <typename LinearSolver>
void SolveCounted(LinearSolver& solver, const Eigen::VectorXd& b, Eigen::VectorXd* x,
                  SolverStats* stats) {
  solver.Solve(b, x);
  stats->krylovIterations += solver.LastSolve().iterations;
  stats->krylovFallbacks += solver.LastSolve().fellBack ? 1 : 0;
}

/// d = −A⁻¹ b (the Newton direction) into the preallocated d.
template <typename LinearSolver>
void SolveNegated(LinearSolver& solver, const Eigen::VectorXd& b, Eigen::VectorXd* d,
                  SolverStats* stats) {
  SolveCounted(solver, b, d, stats);
  *d = -*d;
}

/// d = −A⁻¹ b, regularized as the file comment says, with solver (a SymmetricSolver or
/// UnsymmetricSolver). A (square, compressed) gets every diagonal entry stored (explicit zeros
/// where missing), so that A and A + τI share one pattern and the symbolic analysis is kept.
/// `shifted`, `diagonal`: buffers. Counts the Krylov work and, where a shift was needed,
/// stats->regularizations.
template <typename LinearSolver>
RegularizedSolve SolveRegularized(LinearSolver& solver, Eigen::SparseMatrix<double>* A,
                                  const Eigen::VectorXd& b, ShiftGoal goal, Eigen::VectorXd* d,
                                  Eigen::SparseMatrix<double>* shifted,
                                  std::vector<Eigen::Index>* diagonal, SolverStats* stats);

}  // namespace superdex
