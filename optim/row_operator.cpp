#include "optim/row_operator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace superdex {
namespace {
/// Rows per task; below two grains the product runs on the calling thread.
constexpr Eigen::Index kRowGrain = 512;
/// The largest group of rows summed together (RowProducts).
constexpr Eigen::Index kMaxGroupRows = 6;
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
    // Groups of up to kMaxGroupRows consecutive rows with one column pattern (a node's three rows,
    // a rigid body's six in contact).
    group_.clear();
    for (Eigen::Index i = 0; i < n;) {
      group_.push_back(static_cast<int>(i));
      const int* columns = rowInner_.data() + rowOuter_[i];
      const int length = rowOuter_[i + 1] - rowOuter_[i];
      Eigen::Index g = 1;
      while (g < kMaxGroupRows && i + g < n &&
             rowOuter_[i + g + 1] - rowOuter_[i + g] == length &&
             std::equal(columns, columns + length, rowInner_.data() + rowOuter_[i + g]))
        ++g;
      i += g;
    }
    group_.push_back(static_cast<int>(n));
  }
  const double* value = A.valuePtr();
  for (size_t k = 0; k < nnz; ++k) rowValue_[position_[k]] = value[k];
}

namespace {

/// Sums the rows [r0, r0 + G), which share one column pattern: x_j is loaded once for the G rows,
/// and each row's sum runs in its own accumulator, over its entries in column order.
template <int G>
void GroupProducts(Eigen::Index r0, const int* outer, const int* inner, const double* value,
                   const double* x, double* dst) {
  double acc[G];
  const double* v[G];
  for (int r = 0; r < G; ++r) {
    acc[r] = 0.0;
    v[r] = value + outer[r0 + r];
  }
  const int* columns = inner + outer[r0];
  const int length = outer[r0 + 1] - outer[r0];
  for (int t = 0; t < length; ++t) {
    const double xj = x[columns[t]];
    for (int r = 0; r < G; ++r) acc[r] += v[r][t] * xj;
  }
  for (int r = 0; r < G; ++r) dst[r0 + r] = acc[r];
}

/// dst_i = +0 + Σ_k A_ik x_k for every row i, in parallel over the row groups (`group`: first
/// rows, then n).
void RowProducts(const std::vector<int>& group, const int* outer, const int* inner,
                 const double* value, const double* x, double* dst) {
  auto groupRange = [&](size_t begin, size_t end) {
    for (size_t q = begin; q < end; ++q) {
      const Eigen::Index r0 = group[q];
      switch (group[q + 1] - group[q]) {
        case 2: GroupProducts<2>(r0, outer, inner, value, x, dst); break;
        case 3: GroupProducts<3>(r0, outer, inner, value, x, dst); break;
        case 4: GroupProducts<4>(r0, outer, inner, value, x, dst); break;
        case 5: GroupProducts<5>(r0, outer, inner, value, x, dst); break;
        case 6: GroupProducts<6>(r0, outer, inner, value, x, dst); break;
        default: GroupProducts<1>(r0, outer, inner, value, x, dst); break;
      }
    }
  };
  const size_t groups = group.empty() ? 0 : group.size() - 1;
  const Eigen::Index n = groups ? group.back() : 0;
  if (n < 2 * kRowGrain) {
    groupRange(0, groups);
    return;
  }
  // About kRowGrain rows per task.
  const size_t grain = std::max<size_t>(1, static_cast<size_t>(kRowGrain) * groups / n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, groups, grain),
                    [&](const tbb::blocked_range<size_t>& r) { groupRange(r.begin(), r.end()); });
}

}  // namespace

void RowOperator::Multiply(const double* x, double* dst) const {
  RowProducts(group_, rowOuter_.data(), rowInner_.data(), rowValue_.data(), x, dst);
}

}  // namespace superdex
