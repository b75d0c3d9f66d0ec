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

}  // namespace superdex::test
