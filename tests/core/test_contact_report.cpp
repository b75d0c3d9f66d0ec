// Contact results (Scene::ContactSamples with the last stage's dissipation, SummarizeContactPairs):
// a pair's total force balances the loads it carries at rest, whatever the dissipation mode.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/contact/contact_report.h"
#include "core/scene.h"
#include "scene_builders.h"
#include "scene_runs.h"
#include "sensitivity_scenes.h"

using namespace superdex;

namespace {

constexpr double kG = 9.81;

using test::Run;

// The summary of the pair (a, b), which must exist.
ContactPairSummary PairOf(Scene* scene, int a, int b) {
  for (const ContactPairSummary& p : SummarizeContactPairs(scene->ContactSamples()))
    if (p.a == a && p.b == b) return p;
  FAIL("no contact between actors " << a << " and " << b);
  return {};
}

}  // namespace

TEST_CASE("contact results: a box at rest on a plane carries its weight, without friction",
          "[core][contact_report][physics]") {
  for (int mode : {0, 1}) {
    DYNAMIC_SECTION(test::kModeNames[mode]) {
      SceneSettings settings;
      settings.eval = test::EvalParamsForMode(mode);
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::Ground(Eigen::Vector3d::UnitZ(), 1e7, 0.5, 5.0), &e)
                  .IsValid());
      RigidActorDesc box = test::Cube(1e7, 0.5, 5.0);
      box.position.z() = 0.1;
      REQUIRE(scene.AddRigidActor(box, &e).IsValid());
      Run(&scene, 1.0, 1e-3);
      const ContactPairSummary p = PairOf(&scene, 0, 1);
      // Force on the ground (a = 0): the box's weight, down; the dissipation vanishes at rest.
      CHECK(-p.force.z() == Approx(kG).epsilon(1e-6));
      CHECK(p.frictionForce.norm() < 1e-6 * kG);
      CHECK(p.force.head<2>().norm() < 1e-6 * kG);
      CHECK(p.area == Approx(0.04).epsilon(1e-9));  // the bottom face
      CHECK(p.centreOfPressure.head<2>().norm() < 1e-6);
      CHECK(p.maxPenetration > 0.0);
    }
  }
}

TEST_CASE("contact results: static friction on a 30 degree incline equals m g sin 30",
          "[core][contact_report][physics]") {
  const double theta = M_PI / 6;
  const Eigen::Vector3d n(std::sin(theta), 0, std::cos(theta));
  const Eigen::Vector3d down(std::cos(theta), 0, -std::sin(theta));  // along the slope
  for (int mode : {0, 1}) {
    DYNAMIC_SECTION(test::kModeNames[mode]) {
      SceneSettings settings;
      settings.eval = test::EvalParamsForMode(mode);
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::Ground(n, 1e7, 0.7, 5.0), &e).IsValid());
      REQUIRE(scene.AddRigidActor(test::CubeOnIncline(theta, 1e7, 0.7, 5.0), &e).IsValid());
      Run(&scene, 6.0, 1e-3);
      // μ = 0.7 > tan 30°: the box creeps within the friction band towards a steady speed
      // (5.8 mm/s; its acceleration decays like e^(−t/0.5 s), 2.5e-5 m/s² at 6 s), so the friction
      // on it balances gravity's pull along the slope (on the ground: its opposite).
      const ContactPairSummary p = PairOf(&scene, 0, 1);
      const Eigen::Vector3d friction = -p.frictionForce, normal = -p.normalForce;  // on the box
      CHECK(friction.dot(down) == Approx(-kG * std::sin(theta)).epsilon(1e-4));
      CHECK(normal.dot(n) == Approx(kG * std::cos(theta)).epsilon(1e-4));
      CHECK((-p.force - kG * Eigen::Vector3d::UnitZ()).norm() < 1e-4 * kG);
      // A state set anew has no stage: its dissipation is not reported.
      scene.SetState(scene.RigidActors()[1], scene.State({1}), &e);
      CHECK(PairOf(&scene, 0, 1).frictionForce.norm() == 0.0);
    }
  }
}

TEST_CASE("contact results: both passes of a box on a box add up to one load",
          "[core][contact_report][physics]") {
  Scene scene;
  Error e;
  REQUIRE(scene.AddRigidActor(test::Ground(Eigen::Vector3d::UnitZ(), 1e7, 0.5, 5.0), &e)
              .IsValid());
  RigidActorDesc lower = test::Cube(1e7, 0.5, 5.0), upper = test::Cube(1e7, 0.5, 5.0);
  lower.name = "lower";
  upper.name = "upper";
  lower.position.z() = 0.1;
  upper.position.z() = 0.3;
  upper.mass = 0.5;
  REQUIRE(scene.AddRigidActor(lower, &e).IsValid());
  REQUIRE(scene.AddRigidActor(upper, &e).IsValid());
  Run(&scene, 1.0, 1e-3);
  int passes[2] = {0, 0};
  for (const ContactSampleRecord& r : scene.ContactSamples())
    if (r.colliding + r.collider == 3) ++passes[r.colliding == 1 ? 0 : 1];
  CHECK(passes[0] > 0);  // the lower box's samples on the upper one's field, and the reverse
  CHECK(passes[1] > 0);
  const ContactPairSummary boxes = PairOf(&scene, 1, 2);
  CHECK(boxes.force.z() == Approx(-0.5 * kG).epsilon(1e-6));  // on the lower box, from the upper
  CHECK(PairOf(&scene, 0, 1).force.z() == Approx(-1.5 * kG).epsilon(1e-6));
  CHECK(boxes.area == Approx(0.04).epsilon(1e-9));
}

TEST_CASE("contact results: a box sliding on a soft slab's Sdf field: the reported forces are "
          "the box's momentum change", "[core][contact_report][soft][physics]") {
  // Both passes carry friction: the slab's nodes on the box's field, and the box's samples on the
  // slab's tet field (friction in B's reference coordinates, mapped to the world by F⁻ᵀ). The
  // records describe the last stage at its solution, so under backward Euler the pair's force on
  // the box is m (v_{n+1} − v_n)/Δt − m g, to the stage's tolerance.
  for (DissipationMode mode : {DissipationMode::ReconstructedLoad, DissipationMode::ExplicitNormals}) {
    DYNAMIC_SECTION(ToString(mode)) {
      Scene scene = test::BoxOnSoftSlab(IntegrationMethod::BackwardEuler, mode, 0.5, 0.5, true);
      const double dt = 5e-3, m = 0.5;
      Run(&scene, 0.025, dt);
      const Eigen::Vector3d v0 = scene.State({1}).v;
      Run(&scene, dt, dt);
      const Eigen::Vector3d v1 = scene.State({1}).v;
      int onTets = 0;  // the box's samples on the slab's field with friction
      for (const ContactSampleRecord& r : scene.ContactSamples())
        if (r.colliding == 1 && r.collider == 0 && !r.friction.isZero(0)) ++onTets;
      CHECK(onTets > 0);
      const ContactPairSummary p = PairOf(&scene, 0, 1);  // forces on the slab
      const Eigen::Vector3d expected = m * (v1 - v0) / dt + m * kG * Eigen::Vector3d::UnitZ();
      INFO("friction " << p.frictionForce.transpose() << ", normal " << p.normalForce.transpose()
                       << ", damping " << p.dampingForce.transpose() << "; expected on the box "
                       << expected.transpose());
      CHECK(p.frictionForce.x() > 0.0);  // the box drags the slab along +x
      CHECK((-p.force - expected).norm() < 1e-6 * m * kG);
    }
  }
}
