// Sparse assembly from triplets that keeps the pattern between calls.
//
// A Newton solve assembles its Hessian or Jacobian from the same (row, col) sequence at most
// iterations while the problem's coupling terms and their stencils stay. When the sequence equals the
// previous call's, the values are scattered into the previous pattern through a stored slot per
// triplet (no sort, no transposition, no allocation; the slots are found the first time a
// sequence comes back). A different sequence whose entries are exactly the stored pattern's (each
// triplet lands on a stored entry and every stored entry is hit: the structure setFromTriplets
// would build) is scattered as well, through slots found for it. Otherwise the matrix is built by
// Eigen's setFromTriplets. Either way the entries are the same sums in the same order as
// setFromTriplets (duplicates added left to right in triplet order), so the result is bitwise
// identical to it.
//
// With SetKeepSuperset(true), a sequence whose entries are a large enough subset of the stored
// pattern's (at least kSupersetFill of them) is scattered into it too, the entries it misses set
// to explicit zeros: the same values, a pattern that stays while coupling terms come and go
// (docs/optim-notes.md). Krylov solves give the same
// iterates with or without explicit zeros; a sparse factorization may order differently.
//
// Dense 6 × 6 blocks (e.g. a stencil's blocks of six dofs) may be passed as blocks rather than
// as 36 triplets each: one (row, col) and one slot per block column instead of 36 of each, half
// the memory traffic. They count as their 36 triplets (column by column, rows in order) standing
// in the triplet sequence before index `blockPosition`.
#pragma once

#include <Eigen/Sparse>
#include <cstdint>
#include <vector>

namespace superdex {

/// A dense 6 × 6 block of a sparse matrix: entries (row + r, col + c) = v[6c + r].
struct DenseBlock6 {
  DenseBlock6() {}  // v is its writer's (not zero-filled first: a pile appends thousands per sweep)
  int row = 0, col = 0;
  double v[36];
};

class TripletAssembly {
 public:
  using Triplet = Eigen::Triplet<double>;
  /// *out = the n × n matrix Σ triplets (compressed, column-major).
  void Assemble(const std::vector<Triplet>& triplets, Eigen::Index n,
                Eigen::SparseMatrix<double>* out);
  /// *out = Σ triplets + Σ blocks, summed as setFromTriplets sums the sequence triplets[0, p),
  /// the blocks' triplets, triplets[p, end) (p = blockPosition <= triplets.size()).
  void Assemble(const std::vector<Triplet>& triplets, const std::vector<DenseBlock6>& blocks,
                size_t blockPosition, Eigen::Index n, Eigen::SparseMatrix<double>* out);
  /// Whether a sequence over a subset of the stored entries may keep the pattern (above).
  void SetKeepSuperset(bool keep) { keepSuperset_ = keep; }
  static constexpr double kSupersetFill = 0.8;
  /// Calls that reused the stored pattern, and calls that rebuilt it (for benchmarks and tests).
  long reused() const { return reused_; }
  long rebuilt() const { return rebuilt_; }

 private:
  bool SamePattern(const std::vector<Triplet>& triplets, const std::vector<DenseBlock6>& blocks,
                   size_t blockPosition, Eigen::Index n) const;
  // Slots of the sequence in the stored pattern, in sequence order (the blocks before triplet
  // `position`). `exact`: a new sequence, false (slots cleared) unless its entries are exactly
  // the pattern's; otherwise the sequence is the stored one.
  bool FindSlots(const std::vector<Triplet>& triplets, const std::vector<DenseBlock6>& blocks,
                 size_t position, bool exact);
  // Stores the sequence's (row, col) pairs; the first `from` equal the stored ones already.
  void Store(const std::vector<Triplet>& triplets, const std::vector<DenseBlock6>& blocks,
             size_t blockPosition, size_t from);
  // With slots for the stored sequence: if the sequence is the stored one, scatters its values
  // through the slots into *out (compared as it goes) and returns true; otherwise false, the
  // stored values left partly overwritten.
  bool Scatter(const std::vector<Triplet>& triplets, const std::vector<DenseBlock6>& blocks,
               size_t blockPosition, Eigen::Index n, Eigen::SparseMatrix<double>* out);
  Eigen::SparseMatrix<double> pattern_;
  Eigen::Index n_ = -1;
  size_t blockPosition_ = 0;
  std::vector<int> rows_, cols_;            // the stored triplets' (row, col) sequence
  std::vector<int> blockRows_, blockCols_;  // the stored blocks' corners
  bool haveSlots_ = false;
  std::vector<Eigen::Index> slot_;          // triplet k's entry in pattern_.valuePtr()
  std::vector<char> first_;                 // triplet k is the first one of its entry
  std::vector<Eigen::Index> blockSlot_;     // 6 per block: entry (row, col + c)
  std::vector<std::uint64_t> blockFirst_;   // per block: bit 6c + r set where it is the first
  std::vector<char> seen_;                  // scratch of FindSlots
  size_t sharedPrefix_ = 0;                 // FindSlots: leading triplets equal to the stored
  std::vector<Eigen::Index> unhit_;         // stored entries the sequence misses: set to zero
  bool keepSuperset_ = false;
  std::vector<Triplet> expanded_;           // scratch of a rebuild with blocks
  long reused_ = 0, rebuilt_ = 0;
};

}  // namespace superdex
