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
  const size_t T = triplets.size();
  if (SamePattern(triplets, n)) {
    ++reused_;
    if (slot_.size() != T) FindSlots();  // the sequence came back: worth its slots now
    double* v = pattern_.valuePtr();
    for (size_t k = 0; k < T; ++k) {
      if (first_[k])
        v[slot_[k]] = triplets[k].value();
      else
        v[slot_[k]] += triplets[k].value();
    }
    *out = pattern_;
    return;
  }
  // A new sequence: built by setFromTriplets; its slots are found only if it comes back (in a
  // pile whose contacts change every iteration most sequences are seen once).
  ++rebuilt_;
  pattern_.resize(n, n);
  pattern_.setFromTriplets(triplets.begin(), triplets.end());
  pattern_.makeCompressed();
  n_ = n;
  rows_.resize(T);
  cols_.resize(T);
  for (size_t k = 0; k < T; ++k) {
    rows_[k] = triplets[k].row();
    cols_[k] = triplets[k].col();
  }
  slot_.clear();
  *out = pattern_;
}

void TripletAssembly::FindSlots() {
  const size_t T = rows_.size();
  slot_.resize(T);
  first_.assign(T, 0);
  seen_.assign(pattern_.nonZeros(), 0);
  using Index = Eigen::SparseMatrix<double>::StorageIndex;
  const Index* inner = pattern_.innerIndexPtr();
  const Index* outer = pattern_.outerIndexPtr();
  for (size_t k = 0; k < T; ++k) {
    const Index* begin = inner + outer[cols_[k]];
    const Index* end = inner + outer[cols_[k] + 1];
    slot_[k] = std::lower_bound(begin, end, static_cast<Index>(rows_[k])) - inner;
    first_[k] = !seen_[slot_[k]];
    seen_[slot_[k]] = 1;
  }
}

}  // namespace superdex
