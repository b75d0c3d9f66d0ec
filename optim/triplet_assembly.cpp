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
    if (slot_.size() != triplets.size()) FindSlots();  // the sequence came back: worth its slots
    Scatter(triplets, out);
    return;
  }
  // A new sequence over the same entries (a contact stencil that comes back, an exact zero left
  // out, another order): setFromTriplets would give the stored structure, so the values are
  // scattered into it.
  if (n == n_ && SlotsInPattern(triplets)) {
    ++reused_;
    Scatter(triplets, out);
    return;
  }
  // A new structure: built by setFromTriplets (which allocates).
  ++rebuilt_;
  const size_t T = triplets.size();
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

void TripletAssembly::Scatter(const std::vector<Triplet>& triplets,
                              Eigen::SparseMatrix<double>* out) {
  double* v = pattern_.valuePtr();
  for (size_t k = 0; k < triplets.size(); ++k) {
    if (first_[k])
      v[slot_[k]] = triplets[k].value();
    else
      v[slot_[k]] += triplets[k].value();
  }
  *out = pattern_;
}

bool TripletAssembly::SlotsInPattern(const std::vector<Triplet>& triplets) {
  const size_t T = triplets.size();
  const size_t nnz = static_cast<size_t>(pattern_.nonZeros());
  if (T < nnz) return false;  // some entry cannot be hit
  slot_.resize(T);
  first_.assign(T, 0);
  seen_.assign(nnz, 0);
  using Index = Eigen::SparseMatrix<double>::StorageIndex;
  const Index* inner = pattern_.innerIndexPtr();
  const Index* outer = pattern_.outerIndexPtr();
  size_t hit = 0;
  Index lastCol = -1;
  Eigen::Index last = -1;  // the previous triplet's slot
  for (size_t k = 0; k < T; ++k) {
    const Index row = static_cast<Index>(triplets[k].row());
    const Index col = static_cast<Index>(triplets[k].col());
    // Stencil blocks are appended column by column: the next row of the same column is usually
    // the next stored entry.
    Eigen::Index at;
    if (col == lastCol && last + 1 < outer[col + 1] && inner[last + 1] == row) {
      at = last + 1;
    } else {
      const Index* begin = inner + outer[col];
      const Index* end = inner + outer[col + 1];
      const Index* it = std::lower_bound(begin, end, row);
      if (it == end || *it != row) {
        slot_.clear();
        return false;
      }
      at = it - inner;
    }
    lastCol = col;
    last = at;
    slot_[k] = at;
    first_[k] = !seen_[slot_[k]];
    if (first_[k]) {
      seen_[slot_[k]] = 1;
      ++hit;
    }
  }
  if (hit != nnz) {
    slot_.clear();
    return false;
  }
  rows_.resize(T);
  cols_.resize(T);
  for (size_t k = 0; k < T; ++k) {
    rows_[k] = triplets[k].row();
    cols_[k] = triplets[k].col();
  }
  return true;
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
