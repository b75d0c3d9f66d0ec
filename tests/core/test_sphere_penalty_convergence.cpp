// The spec's sampled surface integral of a sphere (the icosphere's quadrature, ContactState's
// penalty energy) converges under refinement to the closed form of energies/sphere_penalty.h,
// against a plane and against a static sphere: an independent check of both.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/scene.h"
#include "energies/sphere_penalty.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

// The sampled energy of a ball of radius 0.1 m at surface resolution `res`, its centre at
// `centre`, on `collider`.
double SampledEnergy(const RigidActorDesc& collider, const Eigen::Vector3d& centre, int res) {
  Scene scene;
  Error e;
  REQUIRE(scene.AddRigidActor(collider, &e).IsValid());
  RigidActorDesc ball = test::Ball(0.1, 0.0);
  ball.shape.surfaceResolution = res;
  ball.position = centre;
  INFO(e.message);
  REQUIRE(scene.AddRigidActor(ball, &e).IsValid());
  return scene.ContactState().energy;
}

// Relative errors of the sampled energy against `exact` at the shipped resolution 3 and at 6
// (about 40 000 samples): the finest within `finest` and at most 1 % of the shipped one's (the
// error falls erratically on the way: a small cap meets the sample rows where it happens to).
void CheckConvergence(const RigidActorDesc& collider, const Eigen::Vector3d& centre, double exact,
                      double finest) {
  const double shipped = std::abs(SampledEnergy(collider, centre, 3) / exact - 1.0);
  const double fine = std::abs(SampledEnergy(collider, centre, 6) / exact - 1.0);
  INFO("relative error at resolution 3: " << shipped << ", at 6: " << fine);
  CHECK(fine < finest);
  CHECK(fine < 0.01 * shipped);
}

}  // namespace

TEST_CASE("a sampled sphere's penalty converges to the exact integral on a plane",
          "[core][contact][sphere]") {
  const PenaltyParams p;  // k = 1e9 Pa/m, ε = 5 mm, δ = 1 mm: the actors' defaults
  for (double depth : {0.5e-3, 2e-3, 6e-3, 20e-3}) {  // penetration past the threshold δ [m]
    DYNAMIC_SECTION("depth " << depth) {
      const double h = 0.1 + p.delta - depth;
      const double exact = SpherePlanePenalty(h, 0.1, 0.0, p).E;
      CheckConvergence(test::StaticGround(1e9, 0.0), Eigen::Vector3d(0.013, -0.021, h), exact,
                       1e-6);
    }
  }
}

TEST_CASE("a sampled sphere's penalty converges to the exact integral on a sphere's field",
          "[core][contact][sphere]") {
  const PenaltyParams p;  // k = 1e9 Pa/m, ε = 5 mm, δ = 1 mm: the actors' defaults
  const RigidActorDesc fixed = test::FixedSphere(0.07);
  const Eigen::Vector3d e = Eigen::Vector3d(2, 1, -1).normalized();
  for (double depth : {2e-3, 6e-3, 20e-3}) {
    DYNAMIC_SECTION("depth " << depth) {
      const double d = 0.1 + 0.07 + p.delta - depth;
      const double exact = SphereSpherePenalty(d, 0.1, 0.07, 0.0, p).E;
      CheckConvergence(fixed, d * e, exact, 1e-5);
    }
  }
}
