#include "optim/row_operator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace superdex {
namespace {
/// Rows per task; below two grains the product runs on the calling thread.
constexpr Eigen::Index kRowGrain = 512;
}  // namespace

void RowOperator::Set(const Eigen::SparseMatrix<double>& A) {
  eigen_assert(A.isCompressed() && A.rows() == A.cols());
  const Eigen::Index n = A.cols();
  const size_t nnz = static_cast<size_t>(A.nonZeros());
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const bool same = n == n_ && colInner_.size() == nnz &&
                    std::equal(outer, outer + n + 1, colOuter_.begin()) &&
                    std::equal(inner, inner + nnz, colInner_.begin());
  if (!same) {
    n_ = n;
    colOuter_.assign(outer, outer + n + 1);
    colInner_.assign(inner, inner + nnz);
    rowOuter_.assign(n + 1, 0);
    for (size_t k = 0; k < nnz; ++k) ++rowOuter_[inner[k] + 1];
    for (Eigen::Index i = 0; i < n; ++i) rowOuter_[i + 1] += rowOuter_[i];
    rowInner_.resize(nnz);
    position_.resize(nnz);
    rowValue_.resize(nnz);
    // Columns in ascending order: each row receives its entries in column order.
    std::vector<int>& next = rowScratch_;
    next.assign(rowOuter_.begin(), rowOuter_.end() - 1);
    for (Eigen::Index j = 0; j < n; ++j)
      for (int k = outer[j]; k < outer[j + 1]; ++k) {
        const int at = next[inner[k]]++;
        rowInner_[at] = static_cast<int>(j);
        position_[k] = at;
      }
  }
  const double* value = A.valuePtr();
  for (size_t k = 0; k < nnz; ++k) rowValue_[position_[k]] = value[k];
}

namespace {

/// dst_i = (accumulate ? dst_i : +0) + Σ_k A_ik (alpha x_k) for every row i, in parallel by rows.
void RowProducts(Eigen::Index n, const int* outer, const int* inner, const double* value,
                 const double* x, double alpha, bool accumulate, double* dst) {
  // Four rows at a time: each row's sum is one chain of dependent additions (its order fixed,
  // so that the bits are Eigen's), and four independent chains keep the adder busy where one
  // waits on its last addition.
  auto rowRange = [&](Eigen::Index begin, Eigen::Index end) {
    Eigen::Index i = begin;
    for (; i + 4 <= end; i += 4) {
      double acc0 = accumulate ? dst[i] : 0.0, acc1 = accumulate ? dst[i + 1] : 0.0;
      double acc2 = accumulate ? dst[i + 2] : 0.0, acc3 = accumulate ? dst[i + 3] : 0.0;
      const int k0 = outer[i], k1 = outer[i + 1], k2 = outer[i + 2], k3 = outer[i + 3];
      const int n0 = k1 - k0, n1 = k2 - k1, n2 = k3 - k2, n3 = outer[i + 4] - k3;
      const int common = std::min(std::min(n0, n1), std::min(n2, n3));
      for (int t = 0; t < common; ++t) {
        acc0 += value[k0 + t] * (alpha * x[inner[k0 + t]]);
        acc1 += value[k1 + t] * (alpha * x[inner[k1 + t]]);
        acc2 += value[k2 + t] * (alpha * x[inner[k2 + t]]);
        acc3 += value[k3 + t] * (alpha * x[inner[k3 + t]]);
      }
      for (int k = k0 + common; k < k1; ++k) acc0 += value[k] * (alpha * x[inner[k]]);
      for (int k = k1 + common; k < k2; ++k) acc1 += value[k] * (alpha * x[inner[k]]);
      for (int k = k2 + common; k < k3; ++k) acc2 += value[k] * (alpha * x[inner[k]]);
      for (int k = k3 + common; k < k3 + n3; ++k) acc3 += value[k] * (alpha * x[inner[k]]);
      dst[i] = acc0;
      dst[i + 1] = acc1;
      dst[i + 2] = acc2;
      dst[i + 3] = acc3;
    }
    for (; i < end; ++i) {
      double acc = accumulate ? dst[i] : 0.0;
      for (int k = outer[i]; k < outer[i + 1]; ++k) acc += value[k] * (alpha * x[inner[k]]);
      dst[i] = acc;
    }
  };
  if (n < 2 * kRowGrain) {
    rowRange(0, n);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, n, kRowGrain),
                    [&](const tbb::blocked_range<Eigen::Index>& r) {
                      rowRange(r.begin(), r.end());
                    });
}

}  // namespace

void RowOperator::ScaleAndAdd(const double* x, double alpha, double* dst) const {
  RowProducts(n_, rowOuter_.data(), rowInner_.data(), rowValue_.data(), x, alpha, true, dst);
}

void RowOperator::Multiply(const double* x, double* dst) const {
  RowProducts(n_, rowOuter_.data(), rowInner_.data(), rowValue_.data(), x, 1.0, false, dst);
}

}  // namespace superdex
