// Block-Jacobi preconditioner for the Krylov solves of optim/linear_solver.cpp (our conjugate
// gradients and Eigen's BiCGSTAB, whose preconditioner interface it follows): the inverses of the
// diagonal blocks of a sparse matrix, as a DofBlockLayout gives them (optim/block_layout.h):
// blocks of 6 and 3 dofs in the layout's order, then blocks of 3 (StageProblem::BlockLayout).
// Where the layout does not fit the matrix every block is 1×1 (plain Jacobi).
// Measurements: docs/optim-notes.md.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "optim/block_layout.h"

namespace superdex {

class BlockJacobi {
 public:
  using Scalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic };
  using Matrix6 = Eigen::Matrix<double, 6, 6>;

  BlockJacobi() = default;
  /// The layout of the next factorizations (see the file comment).
  void SetLayout(const DofBlockLayout& layout) { layout_ = layout; }

  template <typename MatrixType>
  BlockJacobi& analyzePattern(const MatrixType&) {
    return *this;
  }
  /// Inverts the diagonal blocks of A (compressed column). A singular block is replaced by the
  /// inverse of its diagonal (entries 0 → 1), and PositiveDefinite() becomes false, as it does for
  /// a block that has no Cholesky factor.
  template <typename MatrixType>
  BlockJacobi& factorize(const MatrixType& A) {
    Layout(A.cols());
    for (Eigen::Index j = 0; j < A.outerSize(); ++j)
      for (typename MatrixType::InnerIterator e(A, j); e; ++e) Store(e.row(), j, e.value());
    Invert();
    return *this;
  }
  template <typename MatrixType>
  BlockJacobi& compute(const MatrixType& A) {
    return factorize(A);
  }
  /// z = B⁻¹ r (no allocation when z already has r's size).
  void Apply(const Eigen::VectorXd& r, Eigen::VectorXd* z) const;
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const {
    Eigen::VectorXd z(r.size());
    Apply(r, &z);
    return z;
  }
  Eigen::ComputationInfo info() const { return Eigen::Success; }
  /// Every diagonal block is symmetric positive definite (necessary for A to be).
  bool PositiveDefinite() const { return positiveDefinite_; }

 private:
  /// Sizes the blocks for an n × n matrix and zeroes them.
  void Layout(Eigen::Index n);
  /// Adds entry (row, col) to its block if it lies in one.
  void Store(Eigen::Index row, Eigen::Index col, double value) {
    if (scalar_) {
      if (row == col) diagonal_[row] = value;
      return;
    }
    const Block& b = blocks_[blockOf_[row]];
    if (blockOf_[col] != blockOf_[row]) return;
    if (b.size == 6)
      six_[b.index](row - b.first, col - b.first) = value;
    else
      three_[b.index](row - b.first, col - b.first) = value;
  }
  void Invert();

  // A diagonal block: its first dof, its size (3 or 6) and its index in six_ or three_.
  struct Block {
    Eigen::Index first = 0;
    int size = 3;
    int index = 0;
  };
  DofBlockLayout layout_;
  bool scalar_ = false;             // the layout does not fit: 1×1 blocks
  Eigen::Index laidOut_ = -1;       // the n of the blocks below (−1: none yet)
  DofBlockLayout laidOutLayout_;    // and their layout
  std::vector<Block> blocks_;
  std::vector<int> blockOf_;        // per dof: its block
  std::vector<Matrix6> six_;        // the 6×6 blocks, then their inverses
  std::vector<Eigen::Matrix3d> three_;
  Eigen::VectorXd diagonal_;        // scalar_: the diagonal, then its inverse
  bool positiveDefinite_ = true;
};

}  // namespace superdex
