// Per-sample contact records: the tractions of a resting box add up to its weight.
#include <catch2/catch.hpp>

#include "core/scene.h"
#include "scene_builders.h"

using namespace superdex;

TEST_CASE("contact samples: the normal tractions of a resting cube sum to its weight",
          "[core][contact]") {
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BackwardEuler;
  Scene scene(settings);
  Error e;
  REQUIRE(scene.AddRigidActor(test::StaticGround(1e9, 0.5), &e).IsValid());
  RigidActorDesc box = test::Cube(1e9, 0.5, 0.0);
  box.position = Eigen::Vector3d(0, 0, 0.101);
  REQUIRE(scene.AddRigidActor(box, &e).IsValid());
  for (int i = 0; i < 400; ++i) {
    StepReport r;
    REQUIRE(scene.Step(5e-3, &r, &e));
  }
  const std::vector<ContactSampleRecord> samples = scene.ContactSamples();
  REQUIRE(samples.size() == 24);  // the bottom face's 2 × 2 cells × 2 triangles × 3 samples
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (const ContactSampleRecord& s : samples) {
    CHECK(s.colliding == 1);
    CHECK(s.collider == 0);
    CHECK(s.normal.isApprox(Eigen::Vector3d::UnitZ()));
    force += s.weight * s.traction;
  }
  INFO("total contact force " << force.transpose());
  CHECK(force.z() == Approx(9.81).epsilon(1e-6));
  CHECK(force.head<2>().norm() < 1e-9);
}
