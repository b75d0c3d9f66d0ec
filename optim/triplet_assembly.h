// Sparse assembly from triplets that keeps the pattern between calls.
//
// A Newton solve assembles its Hessian or Jacobian from the same (row, col) sequence at most
// iterations while the contact pairs and their stencils stay. When the sequence equals the
// previous call's, the values are scattered into the previous pattern through a stored slot per
// triplet (no sort, no transposition, no allocation; the slots are found the first time a
// sequence comes back). A different sequence whose entries are exactly the stored pattern's (each
// triplet lands on a stored entry and every stored entry is hit: the structure setFromTriplets
// would build) is scattered as well, through slots found for it. Otherwise the matrix is built by
// Eigen's setFromTriplets. Either way the entries are the same sums in the same order as
// setFromTriplets (duplicates added left to right in triplet order), so the result is bitwise
// identical to it.
#pragma once

#include <Eigen/Sparse>
#include <vector>

namespace superdex {

class TripletAssembly {
 public:
  using Triplet = Eigen::Triplet<double>;
  /// *out = the n × n matrix Σ triplets (compressed, column-major).
  void Assemble(const std::vector<Triplet>& triplets, Eigen::Index n,
                Eigen::SparseMatrix<double>* out);
  /// Calls that reused the stored pattern, and calls that rebuilt it (for benchmarks and tests).
  long reused() const { return reused_; }
  long rebuilt() const { return rebuilt_; }

 private:
  bool SamePattern(const std::vector<Triplet>& triplets, Eigen::Index n) const;
  void FindSlots();
  // Slots of a new sequence in the stored pattern; false (slots cleared) unless its entries are
  // exactly the pattern's. On success the sequence becomes the stored one.
  bool SlotsInPattern(const std::vector<Triplet>& triplets);
  void Scatter(const std::vector<Triplet>& triplets, Eigen::SparseMatrix<double>* out);
  Eigen::SparseMatrix<double> pattern_;
  Eigen::Index n_ = -1;
  std::vector<int> rows_, cols_;    // the (row, col) sequence of the stored pattern
  std::vector<Eigen::Index> slot_;  // triplet k's entry in pattern_.valuePtr()
  std::vector<char> first_;         // triplet k is the first one of its entry
  std::vector<char> seen_;          // scratch of FindSlots
  long reused_ = 0, rebuilt_ = 0;
};

}  // namespace superdex
