// The broad phase (core/contact/broad_phase.h) against every pair tested directly: finite, infinite
// (planes, half-spaces), empty and NaN boxes, on both sides of the direct-test limit.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "core/contact/broad_phase.h"

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

TEST_CASE("OverlapCache gives FindOverlappingPairs' pairs while boxes drift, sweeping rarely",
          "[broad_phase]") {
  // Boxes that move a little at each call (a stage's Newton iterates), with now and then one
  // that jumps (out of its fat box) or turns empty and back; every call must list exactly the
  // overlapping pairs, sorted; the sweep must run far less often than the calls.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n : {3, 9, 40, 200}) {
    std::vector<Aabb> boxes = RandomBoxes(n, &rng);
    OverlapCache cache;
    std::vector<std::pair<int, int>> pairs;
    const int calls = 60;
    for (int call = 0; call < calls; ++call) {
      for (Aabb& b : boxes) {
        if (b.IsEmpty() || !b.min.allFinite() || !b.max.allFinite()) continue;
        const Eigen::Vector3d move(1e-3 * u(rng), 1e-3 * u(rng), 1e-3 * u(rng));
        b.min += move;
        b.max += move;
      }
      if (call % 10 == 5) {  // a jump, and a box emptied or restored
        Aabb& b = boxes[call % n];
        if (b.min.allFinite() && b.max.allFinite() && !b.IsEmpty()) {
          b.min.x() += 0.5;
          b.max.x() += 0.5;
        }
        Aabb& e = boxes[(3 * call) % n];
        if (e.IsEmpty()) {
          e.min = Eigen::Vector3d(0.4, 0.4, 0.4);
          e.max = Eigen::Vector3d(0.6, 0.6, 0.6);
        } else if (e.min.allFinite() && e.max.allFinite()) {
          e = Aabb();
        }
      }
      cache.Find(boxes, &pairs);
      INFO("n = " << n << ", call " << call);
      REQUIRE(pairs == BruteForce(boxes));
    }
    INFO("n = " << n << ": " << cache.sweeps() << " sweeps in " << calls << " calls");
    if (n > 8) CHECK(cache.sweeps() <= 15);
  }
}
