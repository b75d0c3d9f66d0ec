#include "optim/triplet_assembly.h"

#include <algorithm>

namespace superdex {
namespace {

using Index = Eigen::SparseMatrix<double>::StorageIndex;

/// Block b's 36 values into their entries (column c's six rows from slots[c]), each assigned
/// where bit 6c + r of `first` is set, else added.
void ScatterBlock(const DenseBlock6& block, std::uint64_t first, const Eigen::Index* slots,
                  double* v) {
  for (int c = 0; c < 6; ++c) {
    double* column = v + slots[c];
    for (int r = 0; r < 6; ++r) {
      if (first >> (6 * c + r) & 1u)
        column[r] = block.v[6 * c + r];
      else
        column[r] += block.v[6 * c + r];
    }
  }
}

const std::vector<DenseBlock6>& NoBlocks() {
  static const std::vector<DenseBlock6> none;
  return none;
}

}  // namespace

void TripletAssembly::Assemble(const std::vector<Triplet>& triplets, Eigen::Index n,
                               Eigen::SparseMatrix<double>* out) {
  Assemble(triplets, NoBlocks(), triplets.size(), n, out);
}

bool TripletAssembly::SamePattern(const std::vector<Triplet>& triplets,
                                  const std::vector<DenseBlock6>& blocks, size_t blockPosition,
                                  Eigen::Index n) const {
  if (n != n_ || triplets.size() != rows_.size() || blocks.size() != blockRows_.size() ||
      blockPosition != blockPosition_)
    return false;
  for (size_t k = 0; k < triplets.size(); ++k)
    if (triplets[k].row() != rows_[k] || triplets[k].col() != cols_[k]) return false;
  for (size_t b = 0; b < blocks.size(); ++b)
    if (blocks[b].row != blockRows_[b] || blocks[b].col != blockCols_[b]) return false;
  return true;
}

void TripletAssembly::Assemble(const std::vector<Triplet>& triplets,
                               const std::vector<DenseBlock6>& blocks, size_t blockPosition,
                               Eigen::Index n, Eigen::SparseMatrix<double>* out) {
  // The sequence came back: worth its slots.
  if (!haveSlots_ && SamePattern(triplets, blocks, blockPosition, n))
    FindSlots(triplets, blocks, blockPosition, false);
  // The usual call: the stored sequence again, with its slots, compared while it is scattered; a
  // mismatch leaves the values to the paths below, which overwrite every stored entry.
  if (haveSlots_ && Scatter(triplets, blocks, blockPosition, n, out)) {
    ++reused_;
    return;
  }
  // A new sequence over the same entries (a contact stencil that comes back, an exact zero left
  // out, another order): setFromTriplets would give the stored structure, so the values are
  // scattered into it (the stored sequence now: Scatter's comparison passes).
  if (n == n_ && FindSlots(triplets, blocks, blockPosition, true)) {
    Store(triplets, blocks, blockPosition, sharedPrefix_);
    if (Scatter(triplets, blocks, blockPosition, n, out)) {
      ++reused_;
      return;
    }
  }
  // A new structure: built by setFromTriplets (which allocates).
  ++rebuilt_;
  pattern_.resize(n, n);
  if (blocks.empty()) {
    pattern_.setFromTriplets(triplets.begin(), triplets.end());
  } else {
    expanded_.clear();
    expanded_.reserve(triplets.size() + 36 * blocks.size());
    expanded_.insert(expanded_.end(), triplets.begin(), triplets.begin() + blockPosition);
    for (const DenseBlock6& b : blocks)
      for (int c = 0; c < 6; ++c)
        for (int r = 0; r < 6; ++r) expanded_.emplace_back(b.row + r, b.col + c, b.v[6 * c + r]);
    expanded_.insert(expanded_.end(), triplets.begin() + blockPosition, triplets.end());
    pattern_.setFromTriplets(expanded_.begin(), expanded_.end());
  }
  pattern_.makeCompressed();
  n_ = n;
  Store(triplets, blocks, blockPosition, 0);
  haveSlots_ = false;
  unhit_.clear();
  *out = pattern_;
}

void TripletAssembly::Store(const std::vector<Triplet>& triplets,
                            const std::vector<DenseBlock6>& blocks, size_t blockPosition,
                            size_t from) {
  const size_t T = triplets.size(), B = blocks.size();
  rows_.resize(T);
  cols_.resize(T);
  for (size_t k = from; k < T; ++k) {
    rows_[k] = triplets[k].row();
    cols_[k] = triplets[k].col();
  }
  blockRows_.resize(B);
  blockCols_.resize(B);
  for (size_t b = 0; b < B; ++b) {
    blockRows_[b] = blocks[b].row;
    blockCols_[b] = blocks[b].col;
  }
  blockPosition_ = blockPosition;
}

bool TripletAssembly::Scatter(const std::vector<Triplet>& triplets,
                              const std::vector<DenseBlock6>& blocks, size_t blockPosition,
                              Eigen::Index n, Eigen::SparseMatrix<double>* out) {
  if (n != n_ || triplets.size() != rows_.size() || blocks.size() != blockRows_.size() ||
      blockPosition != blockPosition_ || slot_.size() != rows_.size())
    return false;
  double* v = pattern_.valuePtr();
  // Each entry's triplets in sequence order, the first assigned: setFromTriplets' sums.
  auto scalars = [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const Triplet& t = triplets[k];
      if (t.row() != rows_[k] || t.col() != cols_[k]) return false;
      if (first_[k])
        v[slot_[k]] = t.value();
      else
        v[slot_[k]] += t.value();
    }
    return true;
  };
  for (Eigen::Index e : unhit_) v[e] = 0.0;
  if (!scalars(0, blockPosition_)) return false;
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (blocks[b].row != blockRows_[b] || blocks[b].col != blockCols_[b]) return false;
    ScatterBlock(blocks[b], blockFirst_[b], &blockSlot_[6 * b], v);
  }
  if (!scalars(blockPosition_, triplets.size())) return false;
  *out = pattern_;
  return true;
}

bool TripletAssembly::FindSlots(const std::vector<Triplet>& triplets,
                                const std::vector<DenseBlock6>& blocks, size_t position,
                                bool exact) {
  const size_t T = triplets.size(), B = blocks.size();
  const size_t nnz = static_cast<size_t>(pattern_.nonZeros());
  // Entries a new sequence must hit: all, or at least kSupersetFill of them (compared unrounded:
  // a floor would accept a sequence just below the fill).
  const double needed = keepSuperset_ ? kSupersetFill * static_cast<double>(nnz)
                                      : static_cast<double>(nnz);
  if (exact && static_cast<double>(T + 36 * B) < needed) return false;  // too few can be hit
  // A new sequence that begins as the stored one (a soft body's elastic terms, then contacts that
  // changed) keeps the stored slots and first flags of that common beginning: the same entries
  // in the same order land on the same slots.
  size_t reuse = 0;
  if (exact && haveSlots_ && slot_.size() == rows_.size()) {
    const size_t limit = std::min({position, blockPosition_, T, rows_.size()});
    while (reuse < limit && triplets[reuse].row() == rows_[reuse] &&
           triplets[reuse].col() == cols_[reuse])
      ++reuse;
  }
  sharedPrefix_ = reuse;
  haveSlots_ = false;
  unhit_.clear();
  slot_.resize(T);
  first_.resize(T);
  std::fill(first_.begin() + reuse, first_.end(), 0);
  blockSlot_.resize(6 * B);
  blockFirst_.assign(B, 0);
  seen_.assign(nnz, 0);
  const Index* inner = pattern_.innerIndexPtr();
  const Index* outer = pattern_.outerIndexPtr();
  size_t hit = 0;
  for (size_t k = 0; k < reuse; ++k) {
    seen_[slot_[k]] = 1;
    hit += first_[k] ? 1 : 0;
  }
  Index lastCol = -1;
  Eigen::Index last = -1;  // the previous triplet's slot
  // The entry (row, col), or −1 when the pattern lacks it.
  auto find = [&](Index row, Index col) -> Eigen::Index {
    // Stencil blocks are appended column by column: the next row of the same column is usually
    // the next stored entry.
    if (col == lastCol && last + 1 < outer[col + 1] && inner[last + 1] == row) return last + 1;
    if (col < 0 || col >= pattern_.outerSize()) return -1;
    const Index* begin = inner + outer[col];
    const Index* end = inner + outer[col + 1];
    const Index* it = std::lower_bound(begin, end, row);
    if (it == end || *it != row) return -1;
    return it - inner;
  };
  auto scalars = [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const Index row = static_cast<Index>(triplets[k].row());
      const Index col = static_cast<Index>(triplets[k].col());
      const Eigen::Index at = find(row, col);
      if (at < 0) return false;
      lastCol = col;
      last = at;
      slot_[k] = at;
      first_[k] = !seen_[at];
      if (first_[k]) {
        seen_[at] = 1;
        ++hit;
      }
    }
    return true;
  };
  auto fail = [&] {
    slot_.clear();
    blockSlot_.clear();
    unhit_.clear();
    return false;
  };
  if (!scalars(reuse, position)) return fail();
  for (size_t b = 0; b < B; ++b) {
    std::uint64_t first = 0;
    for (int c = 0; c < 6; ++c) {
      const Index col = static_cast<Index>(blocks[b].col + c);
      const Index row = static_cast<Index>(blocks[b].row);
      lastCol = -1;
      const Eigen::Index at = find(row, col);
      // The block's six rows of this column are consecutive entries (no other row lies between).
      if (at < 0 || at + 5 >= outer[col + 1] || inner[at + 5] != row + 5) return fail();
      blockSlot_[6 * b + c] = at;
      for (int r = 0; r < 6; ++r) {
        if (!seen_[at + r]) {
          seen_[at + r] = 1;
          first |= std::uint64_t(1) << (6 * c + r);
          ++hit;
        }
      }
    }
    blockFirst_[b] = first;
  }
  lastCol = -1;
  if (!scalars(position, T)) return fail();
  if (exact && static_cast<double>(hit) < needed) return fail();
  if (hit != nnz)
    for (size_t e = 0; e < nnz; ++e)
      if (!seen_[e]) unhit_.push_back(static_cast<Eigen::Index>(e));
  haveSlots_ = true;
  return true;
}

}  // namespace superdex
