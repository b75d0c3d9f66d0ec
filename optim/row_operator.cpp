#include "optim/row_operator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace superdex {
namespace {
/// Rows per task; below two grains the product runs on the calling thread.
constexpr Eigen::Index kRowGrain = 512;
}  // namespace

void RowOperator::Set(const Eigen::SparseMatrix<double>& A) {
  rows_ = A;  // Eigen transposes the storage order: each row's entries in column order
  rows_.makeCompressed();
}

void RowOperator::ScaleAndAdd(const double* x, double alpha, double* dst) const {
  const int* outer = rows_.outerIndexPtr();
  const int* inner = rows_.innerIndexPtr();
  const double* value = rows_.valuePtr();
  auto rowRange = [&](Eigen::Index begin, Eigen::Index end) {
    for (Eigen::Index i = begin; i < end; ++i) {
      double acc = dst[i];
      for (int k = outer[i]; k < outer[i + 1]; ++k) acc += value[k] * (alpha * x[inner[k]]);
      dst[i] = acc;
    }
  };
  const Eigen::Index n = rows_.rows();
  if (n < 2 * kRowGrain) {
    rowRange(0, n);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, n, kRowGrain),
                    [&](const tbb::blocked_range<Eigen::Index>& r) {
                      rowRange(r.begin(), r.end());
                    });
}

}  // namespace superdex
