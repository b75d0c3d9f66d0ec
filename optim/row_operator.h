// The sparse matrix of the Krylov solves (optim/linear_solver.cpp: conjugate gradients and
// BiCGSTAB, optim/bicgstab.h) as an operator whose product y = A x runs in parallel over rows
// (TBB): a row-major copy of A, each row's entries in column order. Per entry it forms the same
// products and sums, in the same order, as Eigen's column-major sparse × dense product
// (y_i = 0 + Σ_j A_ij x_j, j ascending), so the Krylov iterates are bit for bit those of the serial
// product, on any number of threads.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace superdex {

class RowOperator {
 public:
  /// Copies the compressed matrix A row by row. While A's pattern stays the one of the last call
  /// only the values are copied (no allocation once the buffers have their size).
  void Set(const Eigen::SparseMatrix<double>& A);
  Eigen::Index rows() const { return n_; }
  Eigen::Index cols() const { return n_; }
  /// Groups of consecutive rows with one column pattern, summed together (at most 6 rows each).
  Eigen::Index RowGroups() const { return group_.empty() ? 0 : Eigen::Index(group_.size()) - 1; }

  /// dst = A x (x and dst of cols() and rows() entries; they must not overlap): bit for bit
  /// Eigen's dst.noalias() = A * x.
  void Multiply(const double* x, double* dst) const;

 private:
  Eigen::Index n_ = 0;
  std::vector<int> colOuter_, colInner_;  // A's pattern at the last call (column-major)
  std::vector<int> rowOuter_, rowInner_;  // the same entries by rows, columns ascending
  std::vector<int> position_;             // A's entry k at rowValue_[position_[k]]
  std::vector<double> rowValue_;
  std::vector<int> rowScratch_;           // Set's fill pointers
  std::vector<int> group_;                // first rows of groups of rows with one pattern, then n
};

}  // namespace superdex
