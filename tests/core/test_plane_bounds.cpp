// A plane's world box (WorldBounds, core/model/rigid_body.h) is its half-space's: bounded by the
// plane where the normal is parallel to an axis, all of space otherwise; every point the field
// puts on or below the plane lies in it. The broad phase then pairs a body with the ground only
// when it comes within the collider's reach.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "core/model/rigid_body.h"
#include "core/scene.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

RigidBodyModel PlaneModel(const Eigen::Vector3d& n) {
  RigidActorDesc d = test::Ground(n, 1e9, 0.0, 0.0);
  RigidBodyModel m;
  RigidBodyState s;
  Error e;
  REQUIRE(BuildRigidBody(d, "", &m, &s, &e));
  return m;
}

bool Unbounded(const Aabb& b, int axis) {
  return b.min[axis] == -INFINITY && b.max[axis] == INFINITY;
}

}  // namespace

TEST_CASE("a plane's box is its half-space's: one face where the normal is an axis, else all",
          "[core][broad_phase]") {
  const Eigen::Vector3d p(1.0, -2.0, 3.0);
  SECTION("normal +z, and turned about z") {
    const RigidBodyModel m = PlaneModel(Eigen::Vector3d::UnitZ());
    for (const double turn : {0.0, 0.7}) {
      const Eigen::Matrix3d R = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).matrix();
      const Aabb b = WorldBounds(m, p, R);
      CHECK(Unbounded(b, 0));
      CHECK(Unbounded(b, 1));
      CHECK(b.min[2] == -INFINITY);
      CHECK(b.max[2] >= 3.0);
      CHECK(b.max[2] <= 3.0 + 1e-9);
    }
  }
  SECTION("normal −y: the box lies on the +y side") {
    const Aabb b = WorldBounds(PlaneModel(-Eigen::Vector3d::UnitY()), p, Eigen::Matrix3d::Identity());
    CHECK(Unbounded(b, 0));
    CHECK(Unbounded(b, 2));
    CHECK(b.max[1] == INFINITY);
    CHECK(b.min[1] <= -2.0);
    CHECK(b.min[1] >= -2.0 - 1e-9);
  }
  SECTION("an oblique normal: all of space") {
    const Aabb b = WorldBounds(PlaneModel(Eigen::Vector3d(1, 0, 1)), p, Eigen::Matrix3d::Identity());
    for (int i = 0; i < 3; ++i) CHECK(Unbounded(b, i));
    const Eigen::Matrix3d tilt = Eigen::AngleAxisd(1e-3, Eigen::Vector3d::UnitX()).matrix();
    const Aabb t = WorldBounds(PlaneModel(Eigen::Vector3d::UnitZ()), p, tilt);
    for (int i = 0; i < 3; ++i) CHECK(Unbounded(t, i));
  }
  SECTION("every point the field puts on or below the plane lies in the box") {
    const RigidBodyModel m = PlaneModel(Eigen::Vector3d::UnitZ());
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const Eigen::Vector3d far(1e3, -2e3, 1e3);
    const Aabb b = WorldBounds(m, far, Eigen::Matrix3d::Identity());
    int below = 0;
    for (int k = 0; k < 20000; ++k) {
      const Eigen::Vector3d x = far + Eigen::Vector3d(1e3 * u(rng), 1e3 * u(rng), 1e-12 * u(rng));
      if (m.collider.Value(x - far) > 0.0) continue;
      ++below;
      CHECK(b.Contains(x));
    }
    CHECK(below > 5000);
  }
}

TEST_CASE("a ball is paired with the ground only within the ground's reach", "[core][contact]") {
  Scene scene;
  Error error;
  REQUIRE(scene.AddRigidActor(test::StaticGround(), &error).IsValid());
  RigidActorDesc ball = test::Ball(0.1, 0.5);
  // δ = 1 mm by default, and each box grows by its actor's reach (the ball is a collider too):
  // a gap of 3 mm is beyond both, 0.5 mm within the ground's.
  ball.position = Eigen::Vector3d(0, 0, 0.1 + 0.003);
  const ActorHandle h = scene.AddRigidActor(ball, &error);
  REQUIRE(h.IsValid());
  const ContactStats far = scene.ContactState();
  CHECK(far.candidatePairs == 0);
  CHECK(far.activeSamples == 0);
  ball.position.z() = 0.1 + 0.0005;
  Scene near;
  REQUIRE(near.AddRigidActor(test::StaticGround(), &error).IsValid());
  REQUIRE(near.AddRigidActor(ball, &error).IsValid());
  const ContactStats st = near.ContactState();
  CHECK(st.candidatePairs == 1);
  CHECK(st.activeSamples > 0);
}
