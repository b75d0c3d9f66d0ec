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

  /// Factorizes H (only its lower triangle is read). Returns false if H is not positive definite
  /// for both backends, is empty or non-square, or has non-finite entries.
  bool Factorize(const Eigen::SparseMatrix<double>& H);
  /// Solves H x = b with the last factorization; all NaN if the last Factorize returned false
  /// (a failed attempt overwrites the previous factors).
  Eigen::VectorXd Solve(const Eigen::VectorXd& b) const;
  /// "dense" (<= 48 unknowns), "cholmod" or "ldlt": the backend of the last factorization;
  /// "none" if it failed.
  const char* Backend() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Solves J x = b for a general square J (compressed column): UMFPACK LU with the symmetric
/// strategy and a METIS ordering (stage Jacobians are structurally symmetric and nearly symmetric
/// in value), a dense partial-pivoting LU up to 48 unknowns. Keeps the symbolic analysis while
/// the sparsity pattern stays the same between calls.
class UnsymmetricSolver {
 public:
  UnsymmetricSolver();
  ~UnsymmetricSolver();
  UnsymmetricSolver(const UnsymmetricSolver&) = delete;
  UnsymmetricSolver& operator=(const UnsymmetricSolver&) = delete;

  /// Factorizes J. Returns false if J is (numerically) singular.
  bool Factorize(const Eigen::SparseMatrix<double>& J);
  /// Solves with the last factorization.
  Eigen::VectorXd Solve(const Eigen::VectorXd& b);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace superdex
