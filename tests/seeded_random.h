// Random test data from a seeded generator. Eigen's Random() reads the process-wide std::rand
// state, so its values would depend on the tests run before; these depend on the seed alone.
#pragma once

#include <Eigen/Core>
#include <random>

namespace superdex::test {

/// A vector of n entries uniform in [−1, 1].
inline Eigen::VectorXd UniformVector(Eigen::Index n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = u(rng);
  return v;
}

/// A 3 × 3 matrix of entries uniform in [−1, 1].
inline Eigen::Matrix3d UniformMatrix(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d m;
  for (int i = 0; i < 9; ++i) m.data()[i] = u(rng);
  return m;
}

}  // namespace superdex::test
