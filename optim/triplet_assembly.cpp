#include "optim/triplet_assembly.h"

#include <algorithm>

namespace superdex {

bool TripletAssembly::SamePattern(const std::vector<Triplet>& triplets, Eigen::Index n) const {
  if (n != n_ || triplets.size() != rows_.size()) return false;
  for (size_t k = 0; k < triplets.size(); ++k)
    if (triplets[k].row() != rows_[k] || triplets[k].col() != cols_[k]) return false;
  return true;
}

void TripletAssembly::Assemble(const std::vector<Triplet>& triplets, Eigen::Index n,
                               Eigen::SparseMatrix<double>* out) {
  if (SamePattern(triplets, n)) {
    ++reused_;
    double* v = pattern_.valuePtr();
    for (size_t k = 0; k < triplets.size(); ++k) {
      if (first_[k])
        v[slot_[k]] = triplets[k].value();
      else
        v[slot_[k]] += triplets[k].value();
    }
    *out = pattern_;
    return;
  }
  ++rebuilt_;
  pattern_.resize(n, n);
  pattern_.setFromTriplets(triplets.begin(), triplets.end());
  pattern_.makeCompressed();
  n_ = n;
  const size_t T = triplets.size();
  rows_.resize(T);
  cols_.resize(T);
  slot_.resize(T);
  first_.assign(T, 0);
  std::vector<char> seen(pattern_.nonZeros(), 0);
  using Index = Eigen::SparseMatrix<double>::StorageIndex;
  const Index* inner = pattern_.innerIndexPtr();
  const Index* outer = pattern_.outerIndexPtr();
  for (size_t k = 0; k < T; ++k) {
    rows_[k] = triplets[k].row();
    cols_[k] = triplets[k].col();
    const Index* begin = inner + outer[cols_[k]];
    const Index* end = inner + outer[cols_[k] + 1];
    slot_[k] = std::lower_bound(begin, end, static_cast<Index>(rows_[k])) - inner;
    first_[k] = !seen[slot_[k]];
    seen[slot_[k]] = 1;
  }
  *out = pattern_;
}

}  // namespace superdex
