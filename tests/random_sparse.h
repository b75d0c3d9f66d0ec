// Random sparse systems and a bitwise comparison for the linear-algebra tests (tests/optim).
#pragma once

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace superdex::test {

inline bool SameBits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

/// An unsymmetric compressed n × n matrix: `diagonal` ± 1 on the diagonal and 8 n coupling entries
/// of `scale` · 1e-3 … 1e3 (values over many magnitudes, so that a change of any operation's
/// order would show in the last bits).
inline Eigen::SparseMatrix<double> RandomUnsymmetric(int n, double diagonal, double scale,
                                                     std::mt19937* rng) {
  std::uniform_int_distribution<int> index(0, n - 1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, diagonal + u(*rng));
  for (int k = 0; k < 8 * n; ++k)
    t.emplace_back(index(*rng), index(*rng), u(*rng) * std::pow(10.0, 3.0 * u(*rng)) * scale);
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

/// A matrix of dense blocks: consecutive row blocks of the sizes in `sizes` (cycled), each with
/// full blocks on the diagonal and in 6 random block columns, so that the rows of a block share
/// one column pattern; entries of 1e-3 … 1e3 and a dominant diagonal.
inline Eigen::SparseMatrix<double> RandomBlocked(int n, const std::vector<int>& sizes,
                                                 std::mt19937* rng) {
  std::vector<int> start;
  for (int r = 0, k = 0; r < n; r += sizes[k++ % sizes.size()]) start.push_back(r);
  start.push_back(n);
  const int blocks = static_cast<int>(start.size()) - 1;
  std::uniform_int_distribution<int> block(0, blocks - 1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  for (int I = 0; I < blocks; ++I) {
    std::vector<int> columns{I};
    for (int k = 0; k < 6; ++k) columns.push_back(block(*rng));
    for (int J : columns)
      for (int i = start[I]; i < std::min(start[I + 1], n); ++i)
        for (int j = start[J]; j < std::min(start[J + 1], n); ++j)
          t.emplace_back(i, j, (i == j ? 100.0 : 0.0) + u(*rng) * std::pow(10.0, 3.0 * u(*rng)));
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

}  // namespace superdex::test
