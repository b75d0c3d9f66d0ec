// The culling bounds of a rigid collider's field (core/model/rigid_body.h): the first-order
// model Φ(X) + ∇Φ(X)·D (the reconstructed load of a sample moved by D since x_n) never falls
// below RigidCollider::FirstOrderLowerBound anywhere in the ball |X − C| <= r, for every field
// type, and the sphere's bound is tighter than the generic Φ(C) − (r + |D|) for an approaching
// ball (the case it is for: a landing pile).
#include <catch2/catch.hpp>
#include <random>

#include "core/model/rigid_body.h"

using namespace superdex;

namespace {

RigidCollider TestField(ColliderType type) {
  RigidCollider f;
  f.type = type;
  f.sphere.radius = 0.05;
  f.box.halfExtents = Eigen::Vector3d(0.1, 0.05, 0.2);
  f.plane.normal = Eigen::Vector3d(1.0, -2.0, 2.0).normalized();
  f.plane.offset = 0.01;
  f.lipschitz = 1.0;
  return f;
}

// The smallest Φ(X) + ∇Φ(X)·D over `n` points of the ball: its centre, its boundary (where the
// minimum of a convex field's model lies for the worst direction) and its inside.
double SampledMinimum(const RigidCollider& f, const Eigen::Vector3d& C, double r,
                      const Eigen::Vector3d& D, std::mt19937* rng, int n) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double lo = INFINITY;
  for (int k = 0; k < n; ++k) {
    Eigen::Vector3d dir(g(*rng), g(*rng), g(*rng));
    dir.normalize();
    const double rho = k == 0 ? 0.0 : (k % 2 ? r : r * std::cbrt(u(*rng)));
    const SdfSample s = f.Evaluate(C + rho * dir);
    lo = std::min(lo, s.value + s.gradient.dot(D));
  }
  return lo;
}

}  // namespace

TEST_CASE("a collider's first-order lower bound holds over its ball", "[collider][culling]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (ColliderType type : {ColliderType::Sphere, ColliderType::Box, ColliderType::Plane}) {
    const RigidCollider f = TestField(type);
    int tight = 0;
    for (int trial = 0; trial < 400; ++trial) {
      const Eigen::Vector3d C = 0.2 * Eigen::Vector3d(u(rng), u(rng), u(rng));
      const double r = 0.05 * (1.0 + u(rng)) + 1e-4;
      const Eigen::Vector3d D = 0.04 * Eigen::Vector3d(u(rng), u(rng), u(rng));
      const double bound = f.FirstOrderLowerBound(C, r, D);
      const double lo = SampledMinimum(f, C, r, D, &rng, 400);
      INFO("type " << static_cast<int>(type) << " trial " << trial << " bound " << bound
                   << " sampled minimum " << lo);
      CHECK(bound <= lo + 1e-14);
      if (bound > f.Value(C) - (r + D.norm()) + 1e-12) ++tight;
    }
    // The sphere's and the plane's bounds use the field's shape; the box's is the generic one.
    if (type == ColliderType::Box) CHECK(tight == 0);
    else CHECK(tight > 100);
  }
}

TEST_CASE("the sphere's first-order bound is sharp for a small approaching ball",
          "[collider][culling]") {
  // A ball of radius 1 mm just outside a 5 cm sphere that moved 2 cm towards it since x_n: its
  // samples' reconstructed load stays near the gap plus 2 cm, which the generic bound (gap minus
  // 2 cm) misses; the sphere's bound is within the chord term (about r/|C| |D|) of the minimum.
  const RigidCollider f = TestField(ColliderType::Sphere);
  const Eigen::Vector3d C(0.0, 0.0, 0.06), D(0.0, 0.0, 0.02);
  const double r = 1e-3;
  std::mt19937 rng(3);
  const double lo = SampledMinimum(f, C, r, D, &rng, 2000);
  const double bound = f.FirstOrderLowerBound(C, r, D);
  CHECK(bound <= lo);
  CHECK(lo - bound < 2.0 * r / C.norm() * D.norm());
  CHECK(f.Value(C) - (r + D.norm()) < 0.0);  // the generic bound would keep the ball
  CHECK(bound > 0.02);                        // this one culls it (δ of the millimetre order)
}

TEST_CASE("Collider fields: the first-order evaluation and its completed Hessian equal the full one",
          "[collider][culling]") {
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0.0, 0.1);
  for (ColliderType type : {ColliderType::Sphere, ColliderType::Box, ColliderType::Plane}) {
    const RigidCollider f = TestField(type);
    for (int k = 0; k < 200; ++k) {
      const Eigen::Vector3d X(g(rng), g(rng), g(rng));
      const double bound = k % 2 ? INFINITY : 0.02;
      SdfSample full, first;
      const bool belowFull = f.EvaluateBelow(X, bound, &full);
      const bool belowFirst = f.EvaluateFirstOrderBelow(X, bound, &first);
      REQUIRE(belowFirst == belowFull);
      CHECK(first.value == full.value);  // the same operations: equal to the bit
      if (!belowFull) continue;
      CHECK(first.gradient == full.gradient);
      f.CompleteHessian(X, &first);
      CHECK(first.value == full.value);
      CHECK(first.gradient == full.gradient);
      CHECK(first.hessian == full.hessian);
    }
  }
}
