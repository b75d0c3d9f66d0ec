// The sparse matrix of the Krylov solves (optim/linear_solver.cpp) as an operator whose product
// y = A x runs in parallel over rows (TBB): a row-major copy of A, each row's entries in column
// order. Per entry it forms the same products and sums, in the same order, as Eigen's column-major
// sparse × dense product (res_i += A_ij · (α x_j), j ascending), so the Krylov iterates are bit
// for bit those of the serial product, on any number of threads. Our conjugate gradients and
// BiCGSTAB (optim/bicgstab.h) call it directly; it also plugs into Eigen's iterative routines as a
// matrix-free operator (Eigen's "matrix-free solvers" pattern). One difference there: Eigen forms
// b − A x for a sparse matrix in place (b, then += −1·A x entry by entry) and for an operator
// through a temporary A x, so a BiCGSTAB restart (r = b − A x at x ≠ 0, after r has become
// orthogonal to r₀) rounds differently; from a solve's start, x = 0, both give b.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace superdex {
class RowOperator;
}

namespace Eigen {
namespace internal {
template <>
struct traits<superdex::RowOperator> : public traits<SparseMatrix<double>> {};
}  // namespace internal
}  // namespace Eigen

namespace superdex {

class RowOperator : public Eigen::EigenBase<RowOperator> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum {
    ColsAtCompileTime = Eigen::Dynamic,
    MaxColsAtCompileTime = Eigen::Dynamic,
    IsRowMajor = false
  };

  /// Copies the compressed matrix A row by row. While A's pattern stays the one of the last call
  /// only the values are copied (no allocation once the buffers have their size).
  void Set(const Eigen::SparseMatrix<double>& A);
  Eigen::Index rows() const { return n_; }
  /// Groups of consecutive rows with one column pattern, summed together (at most 6 rows each).
  Eigen::Index RowGroups() const { return group_.empty() ? 0 : Eigen::Index(group_.size()) - 1; }
  Eigen::Index cols() const { return n_; }

  /// dst += alpha A x (x and dst of cols() and rows() entries; they must not overlap).
  void ScaleAndAdd(const double* x, double alpha, double* dst) const;
  /// dst = A x: bit for bit what dst = 0 followed by ScaleAndAdd(x, 1, dst) gives (each row's sum
  /// starts at +0 and 1 · x_j = x_j), without the pass that zeroes dst.
  void Multiply(const double* x, double* dst) const;

  template <typename Rhs>
  Eigen::Product<RowOperator, Rhs, Eigen::AliasFreeProduct> operator*(
      const Eigen::MatrixBase<Rhs>& x) const {
    return Eigen::Product<RowOperator, Rhs, Eigen::AliasFreeProduct>(*this, x.derived());
  }

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

namespace Eigen {
namespace internal {

template <typename Rhs>
struct generic_product_impl<superdex::RowOperator, Rhs, SparseShape, DenseShape, GemvProduct>
    : generic_product_impl_base<superdex::RowOperator, Rhs,
                                generic_product_impl<superdex::RowOperator, Rhs>> {
  using Scalar = typename Product<superdex::RowOperator, Rhs>::Scalar;
  template <typename Dest>
  static void scaleAndAddTo(Dest& dst, const superdex::RowOperator& lhs, const Rhs& rhs,
                            const Scalar& alpha) {
    const Ref<const VectorXd> x(rhs);
    Ref<VectorXd> y(dst);
    lhs.ScaleAndAdd(x.data(), alpha, y.data());
  }
};

}  // namespace internal
}  // namespace Eigen
