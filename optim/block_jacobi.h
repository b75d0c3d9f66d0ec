// Block-Jacobi preconditioner with the 3×3 diagonal blocks of a sparse matrix: one block per
// point of R³ (a soft node, a rigid body's translation or its rotation), for the Krylov solves
// of optim/linear_solver.cpp (our conjugate gradients and Eigen's BiCGSTAB, whose preconditioner
// interface it follows). Matrices whose size is not a multiple of 3 use 1×1 blocks (Jacobi).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace superdex {

class BlockJacobi3 {
 public:
  using Scalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic };

  BlockJacobi3() = default;
  template <typename MatrixType>
  BlockJacobi3& analyzePattern(const MatrixType&) {
    return *this;
  }
  /// Inverts the diagonal blocks of A (compressed column). A singular block is replaced by the
  /// inverse of its diagonal (entries 0 → 1), and PositiveDefinite() becomes false, as it does for
  /// a block that has no Cholesky factor.
  template <typename MatrixType>
  BlockJacobi3& factorize(const MatrixType& A) {
    const Eigen::Index n = A.cols();
    block_ = n % 3 == 0 ? 3 : 1;
    blocks_.assign(n / block_, Eigen::Matrix3d::Zero());
    for (Eigen::Index j = 0; j < A.outerSize(); ++j)
      for (typename MatrixType::InnerIterator e(A, j); e; ++e)
        if (e.row() / block_ == j / block_)
          blocks_[j / block_](e.row() % block_, j % block_) = e.value();
    Invert();
    return *this;
  }
  template <typename MatrixType>
  BlockJacobi3& compute(const MatrixType& A) {
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
  void Invert();
  int block_ = 3;
  std::vector<Eigen::Matrix3d> blocks_;  // the blocks, then their inverses (top-left block_²)
  bool positiveDefinite_ = true;
};

}  // namespace superdex
