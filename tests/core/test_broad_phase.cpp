// The broad phase (core/broad_phase.h) against every pair tested directly: finite, infinite
// (planes, half-spaces), empty and NaN boxes, on both sides of the direct-test limit.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "core/broad_phase.h"

using namespace superdex;

namespace {

std::vector<std::pair<int, int>> BruteForce(const std::vector<Aabb>& boxes) {
  std::vector<std::pair<int, int>> out;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(boxes.size()); ++j)
      if (!boxes[i].IsEmpty() && !boxes[j].IsEmpty() && boxes[i].Overlaps(boxes[j]))
        out.emplace_back(i, j);
  return out;
}

std::vector<Aabb> RandomBoxes(int n, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Aabb> boxes(n);
  for (int i = 0; i < n; ++i) {
    const double kind = u(*rng);
    Aabb& b = boxes[i];
    if (kind < 0.08) {
      b = Aabb();  // empty
    } else if (kind < 0.14) {
      b = Aabb::Everything();
    } else if (kind < 0.20) {  // a half-space below a random height, as a plane's box
      b = Aabb::Everything();
      b.max.z() = u(*rng);
    } else if (kind < 0.22) {
      b.min.setConstant(NAN);
      b.max.setConstant(NAN);
    } else {
      const Eigen::Vector3d c(u(*rng), u(*rng), u(*rng));
      const double r = 0.02 + 0.1 * u(*rng);
      b.min = c.array() - r;
      b.max = c.array() + r;
    }
  }
  return boxes;
}

}  // namespace

TEST_CASE("FindOverlappingPairs lists every overlapping pair once, sorted", "[broad_phase]") {
  std::mt19937 rng(7);
  for (int n : {0, 1, 2, 3, 8, 9, 12, 40, 200}) {
    for (int trial = 0; trial < 20; ++trial) {
      const std::vector<Aabb> boxes = RandomBoxes(n, &rng);
      std::vector<std::pair<int, int>> pairs = {{-1, -1}};  // cleared by the call
      FindOverlappingPairs(boxes, &pairs);
      INFO("n = " << n << ", trial " << trial);
      CHECK(pairs == BruteForce(boxes));
    }
  }
  // A sphere's box over a plane's, and the same pair once the sphere has left the half-space.
  Aabb plane = Aabb::Everything();
  plane.max.z() = 0.0;
  Aabb sphere;
  sphere.min = Eigen::Vector3d(-0.1, -0.1, -0.01);
  sphere.max = Eigen::Vector3d(0.1, 0.1, 0.19);
  std::vector<std::pair<int, int>> pairs;
  FindOverlappingPairs({sphere, plane}, &pairs);
  CHECK(pairs == std::vector<std::pair<int, int>>{{0, 1}});
  sphere.min.z() = 0.5;
  sphere.max.z() = 0.7;
  FindOverlappingPairs({sphere, plane}, &pairs);
  CHECK(pairs.empty());
}
