#include "optim/regularized_solve.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace superdex {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// Makes every diagonal entry of A structurally present (explicit zeros where missing), so that
/// A and A + τI share one sparsity pattern. Fills diagonal[k] with the index of A_kk in
/// A.valuePtr().
void FindDiagonal(SparseMatrix* A, std::vector<Eigen::Index>* diagonal) {
  const Eigen::Index n = A->outerSize();
  diagonal->assign(n, -1);
  bool missing = false;
  for (int pass = 0; pass < 2; ++pass) {
    missing = false;
    for (Eigen::Index k = 0; k < n; ++k) {
      using Index = SparseMatrix::StorageIndex;
      const Index* begin = A->innerIndexPtr() + A->outerIndexPtr()[k];
      const Index* end = A->innerIndexPtr() + A->outerIndexPtr()[k + 1];
      const Index* it = std::lower_bound(begin, end, static_cast<Index>(k));
      if (it != end && *it == k) {
        (*diagonal)[k] = it - A->innerIndexPtr();
      } else {
        missing = true;
      }
    }
    if (!missing) return;
    // Rebuild with explicit zeros on the missing diagonal entries (setFromTriplets keeps zeros).
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(A->nonZeros() + n);
    for (Eigen::Index k = 0; k < n; ++k) {
      for (SparseMatrix::InnerIterator e(*A, k); e; ++e)
        triplets.emplace_back(e.row(), e.col(), e.value());
      if ((*diagonal)[k] < 0) triplets.emplace_back(k, k, 0.0);
    }
    SparseMatrix rebuilt(A->rows(), A->cols());
    rebuilt.setFromTriplets(triplets.begin(), triplets.end());
    *A = std::move(rebuilt);
  }
}

/// The shift ladder's scale: max_i |A_ii|; on a zero diagonal max_ij |A_ij| (Descent), then 1.
double ShiftScale(const SparseMatrix& A, const std::vector<Eigen::Index>& diagonal,
                  ShiftGoal goal) {
  double scale = 0.0;
  for (Eigen::Index k : diagonal) scale = std::max(scale, std::abs(A.valuePtr()[k]));
  if (scale == 0.0 && goal == ShiftGoal::Descent)
    scale = Eigen::Map<const Eigen::VectorXd>(A.valuePtr(), A.nonZeros()).lpNorm<Eigen::Infinity>();
  if (scale == 0.0) scale = 1.0;
  return scale;
}

/// Gershgorin: τ >= max_i (Σ_{j≠i} |A_ij| − A_ii) + scale makes A + τI strictly diagonally
/// dominant with a positive diagonal.
double DominantShift(const SparseMatrix& A, const std::vector<Eigen::Index>& diagonal,
                     double scale) {
  const Eigen::Index n = A.rows();
  Eigen::VectorXd offDiagonal = Eigen::VectorXd::Zero(n);
  for (Eigen::Index k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator e(A, k); e; ++e)
      if (e.row() != e.col()) offDiagonal[e.row()] += std::abs(e.value());
  double gershgorin = 0.0;
  for (Eigen::Index k = 0; k < n; ++k)
    gershgorin = std::max(gershgorin, offDiagonal[k] - A.valuePtr()[diagonal[k]]);
  return gershgorin + scale;
}

}  // namespace

template <typename LinearSolver>
RegularizedSolve SolveRegularized(LinearSolver& solver, SparseMatrix* A, const Eigen::VectorXd& b,
                                  ShiftGoal goal, Eigen::VectorXd* d, SparseMatrix* shifted,
                                  std::vector<Eigen::Index>* diagonal, SolverStats* stats) {
  RegularizedSolve out;
  FindDiagonal(A, diagonal);
  auto acceptable = [&] {
    return d->allFinite() && (goal == ShiftGoal::Nonsingular || b.dot(*d) < 0.0);
  };
  auto solveWith = [&](const SparseMatrix& M) {
    if (!solver.Factorize(M)) return false;
    SolveNegated(solver, b, d, stats);
    return acceptable();
  };
  out.solved = solveWith(*A);
  if (out.solved) return out;
  ++stats->regularizations;
  const std::vector<Eigen::Index>& diag = *diagonal;
  const double scale = ShiftScale(*A, diag, goal);
  // Descent: one last shift after the ladder, large enough for diagonal dominance.
  const bool dominant = goal == ShiftGoal::Descent;
  const double dominance = dominant ? DominantShift(*A, diag, scale) : 0.0;
  *shifted = *A;
  double tau = kInitialShift * scale;
  for (int r = 0; r < kMaxShiftRetries + (dominant ? 1 : 0) && !out.solved; ++r, tau *= 10.0) {
    if (r == kMaxShiftRetries) tau = std::max(tau, dominance);
    for (Eigen::Index k : diag) shifted->valuePtr()[k] = A->valuePtr()[k] + tau;
    out.lastShift = tau;
    out.solved = solveWith(*shifted);
  }
  return out;
}

template RegularizedSolve SolveRegularized<SymmetricSolver>(
    SymmetricSolver&, SparseMatrix*, const Eigen::VectorXd&, ShiftGoal, Eigen::VectorXd*,
    SparseMatrix*, std::vector<Eigen::Index>*, SolverStats*);
template RegularizedSolve SolveRegularized<UnsymmetricSolver>(
    UnsymmetricSolver&, SparseMatrix*, const Eigen::VectorXd&, ShiftGoal, Eigen::VectorXd*,
    SparseMatrix*, std::vector<Eigen::Index>*, SolverStats*);

}  // namespace superdex
