// Sparse symmetric linear solves: CHOLMOD supernodal Cholesky, Eigen SimplicialLDLT as fallback.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

namespace superdex {

/// Solves H x = b for symmetric H (full storage, compressed column). Keeps the symbolic analysis
/// while the sparsity pattern stays the same between calls.
class SymmetricSolver {
 public:
  SymmetricSolver();
  ~SymmetricSolver();
  SymmetricSolver(const SymmetricSolver&) = delete;
  SymmetricSolver& operator=(const SymmetricSolver&) = delete;

  /// Factorizes H. Returns false if H is not positive definite for both backends.
  bool Factorize(const Eigen::SparseMatrix<double>& H);
  /// Solves with the last successful factorization.
  Eigen::VectorXd Solve(const Eigen::VectorXd& b) const;
  /// "cholmod" or "ldlt": the backend of the last successful factorization.
  const char* Backend() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace superdex
