// The offsets of a scene file's grid replication ("grid": count, spacing, jitter, seed), shared by
// the scene loader and the peer adapters (bench/peers) so that both place the same copies.
#pragma once

#include <Eigen/Core>
#include <random>
#include <vector>

namespace superdex {

/// One offset [m] per copy, x fastest, then y, then z: (x, y, z) ∘ spacing plus a jitter drawn
/// uniformly in [−jitter, jitter] per axis from std::mt19937(seed). `count` holds whole numbers.
/// The loader's copy k is its actor's position plus offset k.
inline std::vector<Eigen::Vector3d> GridCopyOffsets(const Eigen::Vector3d& count,
                                                     const Eigen::Vector3d& spacing,
                                                     double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector3d> offsets;
  for (int z = 0; z < int(count.z()); ++z)
    for (int y = 0; y < int(count.y()); ++y)
      for (int x = 0; x < int(count.x()); ++x) {
        // The three draws in the order the compiler evaluates the constructor's arguments (the
        // order the shipped scenes' recordings were made with).
        offsets.push_back(Eigen::Vector3d(x, y, z).cwiseProduct(spacing) +
                          jitter * Eigen::Vector3d(u(rng), u(rng), u(rng)));
      }
  return offsets;
}

}  // namespace superdex
