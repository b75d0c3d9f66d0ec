// Driving rigid bodies: applied forces and torques (RigidActorDesc::appliedForce, appliedTorque)
// against closed-form motion, and kinematic actors (RigidActorDesc::kinematic) that follow their
// prescribed motion and push what they touch with the force friction asks for.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/contact/contact_report.h"
#include "core/model/rigid_math.h"
#include "core/scene.h"
#include "scene_builders.h"
#include "scene_runs.h"

using namespace superdex;

namespace {

constexpr double kG = 9.81;

using test::Run;

SceneSettings Settings(IntegrationMethod method, const Eigen::Vector3d& gravity) {
  SceneSettings s;
  s.integrator = method;
  s.gravity = gravity;
  return s;
}

// A kinematic box `name` of the given half extents [m].
RigidActorDesc KinematicBox(const std::string& name, const Eigen::Vector3d& halfExtents) {
  RigidActorDesc d;
  d.name = name;
  d.dynamic = false;
  d.kinematic = true;
  d.shape.kind = RigidShapeKind::Box;
  d.shape.halfExtents = halfExtents;
  return d;
}

// A free 2 kg sphere of radius 0.1 m (I = 2/5 m r² = 0.008 kg·m²) at the origin.
RigidActorDesc FreeSphere() {
  RigidActorDesc d = test::Ball(0.1, 0.5);
  d.mass = 2.0;
  return d;
}

}  // namespace

TEST_CASE("applied loads: a force equal to the weight holds a body where it is",
          "[core][applied_loads][physics]") {
  for (IntegrationMethod method : {IntegrationMethod::BDF2, IntegrationMethod::DIRK22}) {
    DYNAMIC_SECTION(ToString(method)) {
      Scene scene(Settings(method, Eigen::Vector3d(0, 0, -kG)));
      RigidActorDesc d = FreeSphere();
      d.appliedForce = {{0.0, Eigen::Vector3d(0, 0, 2.0 * kG)}};
      Error e;
      const ActorHandle a = scene.AddRigidActor(d, &e);
      REQUIRE(a.IsValid());
      Run(&scene, 1.0, 1e-2);
      CHECK(scene.State(a).p.norm() < 1e-12);
      CHECK(scene.State(a).v.norm() < 1e-12);
    }
  }
}

TEST_CASE("applied loads: a force ramp gives v = ∫F/m and x = ∬F/m", "[core][applied_loads][physics]") {
  // F(t) = (4 N/s) t along x on 2 kg: a = 2t, v(1) = 1 m/s, x(1) = 1/3 m. BDF2's error is O(h²)
  // (its Backward Euler start: O(h²) too); at h = 1e-3 both are below 1e-5 of the values.
  for (IntegrationMethod method : {IntegrationMethod::BDF2, IntegrationMethod::DIRK22}) {
    DYNAMIC_SECTION(ToString(method)) {
      Scene scene(Settings(method, Eigen::Vector3d::Zero()));
      RigidActorDesc d = FreeSphere();
      d.appliedForce = {{0.0, Eigen::Vector3d::Zero()}, {1.0, Eigen::Vector3d(4, 0, 0)}};
      Error e;
      const ActorHandle a = scene.AddRigidActor(d, &e);
      REQUIRE(a.IsValid());
      Run(&scene, 1.0, 1e-3);
      const RigidBodyState s = scene.State(a);
      CHECK(s.v.x() == Approx(1.0).epsilon(1e-5));
      CHECK(s.p.x() == Approx(1.0 / 3.0).epsilon(1e-5));
      CHECK(s.p.tail<2>().norm() < 1e-12);
      // After the last keyframe the last force holds.
      Run(&scene, 0.5, 1e-3);
      CHECK(scene.State(a).v.x() == Approx(2.0).epsilon(1e-5));
    }
  }
}

TEST_CASE("applied loads: a torque spins a body up at τ/I; the stage is solved on its residual",
          "[core][applied_loads][physics]") {
  // A sphere (I = 0.008 kg·m² about every axis) and a box (I_zz = m (a² + b²)/12) under a
  // constant torque τ about z from rest: ω(T) = τ T / I_zz, the turn θ(T) = ½ τ T² / I_zz. DIRK22
  // ends each step with L̇ = τ by its own weights (core/dynamics/integrators.h): ω exact. BDF2 in
  // material-point form turns with an O((ω h)²) error: ω's and θ's relative errors shrink 4× when
  // h halves, and stay below 2 (ω(T) h)².
  for (IntegrationMethod method : {IntegrationMethod::BDF2, IntegrationMethod::DIRK22}) {
    for (bool box : {false, true}) {
      DYNAMIC_SECTION(ToString(method) << (box ? " box" : " sphere")) {
        RigidActorDesc d = FreeSphere();
        double I = 0.4 * 2.0 * 0.01;
        if (box) {
          d.shape.kind = RigidShapeKind::Box;
          d.shape.halfExtents = Eigen::Vector3d(0.2, 0.1, 0.05);
          I = 2.0 * (0.16 + 0.04) / 12.0;
        }
        const double tau = 0.3, T = 0.5;
        d.appliedTorque = {{0.0, Eigen::Vector3d(0, 0, tau)}};
        const double omega = tau * T / I, turn = 0.5 * tau * T * T / I;
        double omegaError[2], turnError[2];
        for (int k = 0; k < 2; ++k) {
          const double h = k == 0 ? 1e-3 : 5e-4;
          Scene scene(Settings(method, Eigen::Vector3d::Zero()));
          Error e;
          const ActorHandle a = scene.AddRigidActor(d, &e);
          REQUIRE(a.IsValid());
          Run(&scene, T, h);
          const RigidBodyState s = scene.State(a);
          const Eigen::Vector3d w = s.AngularVelocity();
          CHECK(w.head<2>().norm() < 1e-9);
          CHECK(s.p.norm() < 1e-12);
          const Eigen::Vector3d theta = LogSo3(s.R);
          CHECK(theta.head<2>().norm() < 1e-9);
          omegaError[k] = std::abs(w.z() / omega - 1.0);
          // The turn modulo 2π, from the rotation.
          const double wrapped = std::remainder(turn, 2 * M_PI);
          turnError[k] = std::abs(theta.z() - wrapped) / turn;
          INFO("h " << h << ": ω error " << omegaError[k] << ", turn error " << turnError[k]);
          CHECK(turnError[k] < 2 * std::pow(omega * h, 2));
          if (method == IntegrationMethod::DIRK22) CHECK(omegaError[k] < 1e-9);
          else CHECK(omegaError[k] < 2 * std::pow(omega * h, 2));
        }
        if (method == IntegrationMethod::BDF2) {
          CHECK(omegaError[0] / omegaError[1] == Approx(4.0).epsilon(0.1));
          CHECK(turnError[0] / turnError[1] == Approx(4.0).epsilon(0.1));
        }
      }
    }
  }
}

TEST_CASE("applied loads: a torque about a tilted axis keeps L̇ = τ", "[core][applied_loads][physics]") {
  // A box spinning about a non-principal direction under a constant world torque: whatever the
  // motion, its angular momentum grows by τ t (to the integrator's accuracy).
  Scene scene(Settings(IntegrationMethod::BDF2, Eigen::Vector3d::Zero()));
  RigidActorDesc d = FreeSphere();
  d.shape.kind = RigidShapeKind::Box;
  d.shape.halfExtents = Eigen::Vector3d(0.2, 0.1, 0.05);
  d.angularVelocity = Eigen::Vector3d(1.0, 2.0, 0.5);
  const Eigen::Vector3d tau(0.1, -0.2, 0.3);
  d.appliedTorque = {{0.0, tau}};
  Error e;
  const ActorHandle a = scene.AddRigidActor(d, &e);
  REQUIRE(a.IsValid());
  const Eigen::Vector3d L0 = AngularMomentum(scene.Model(a), scene.State(a));
  Run(&scene, 0.5, 1e-3);
  const Eigen::Vector3d L = AngularMomentum(scene.Model(a), scene.State(a));
  INFO("L − L0 = " << (L - L0).transpose() << ", τ T = " << (0.5 * tau).transpose());
  CHECK((L - L0 - 0.5 * tau).norm() < 1e-3 * (0.5 * tau).norm());
}

TEST_CASE("applied loads: bad input names the field and the rule", "[core][applied_loads][input]") {
  Scene scene;
  Error e;
  RigidActorDesc d = FreeSphere();
  d.appliedForce = {{1.0, Eigen::Vector3d::Zero()}, {0.5, Eigen::Vector3d::Zero()}};
  CHECK_FALSE(scene.AddRigidActor(d, &e).IsValid());
  CHECK_THAT(e.message, Catch::Contains("applied_force: keyframe times must increase"));
  d = FreeSphere();
  d.appliedTorque = {{0.0, Eigen::Vector3d(NAN, 0, 0)}};
  CHECK_FALSE(scene.AddRigidActor(d, &e).IsValid());
  CHECK_THAT(e.message, Catch::Contains("applied_torque: keyframes must be finite"));
  d = test::StaticGround();
  d.appliedForce = {{0.0, Eigen::Vector3d::UnitX()}};
  CHECK_FALSE(scene.AddRigidActor(d, &e).IsValid());
  CHECK_THAT(e.message, Catch::Contains("applied_force: only a dynamic actor takes applied loads"));
  d = FreeSphere();
  d.kinematic = true;
  CHECK_FALSE(scene.AddRigidActor(d, &e).IsValid());
  CHECK_THAT(e.message, Catch::Contains("kinematic: a kinematic actor is not dynamic"));
  d = FreeSphere();
  d.path = {PoseKeyframe()};
  CHECK_FALSE(scene.AddRigidActor(d, &e).IsValid());
  CHECK_THAT(e.message, Catch::Contains("path: only a kinematic actor follows a path"));
  d.dynamic = false;
  d.kinematic = true;
  d.path = {PoseKeyframe(), PoseKeyframe()};
  CHECK_FALSE(scene.AddRigidActor(d, &e).IsValid());
  CHECK_THAT(e.message, Catch::Contains("path[1].t: keyframe times must increase"));
}

TEST_CASE("kinematic actors: the pose follows the path, the velocity its segments",
          "[core][kinematic]") {
  for (IntegrationMethod method : {IntegrationMethod::BDF2, IntegrationMethod::DIRK22}) {
    DYNAMIC_SECTION(ToString(method)) {
      Scene scene(Settings(method, Eigen::Vector3d(0, 0, -kG)));
      RigidActorDesc d = KinematicBox("paddle", Eigen::Vector3d(0.3, 0.02, 0.1));
      PoseKeyframe k0, k1, k2;
      k0.position = Eigen::Vector3d(0, 0, 1);
      k1.t = 1.0;
      k1.position = Eigen::Vector3d(1, 0, 1);
      k1.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
      k2.t = 2.0;
      k2.position = Eigen::Vector3d(1, 1, 1);
      k2.orientation = k1.orientation;
      d.path = {k0, k1, k2};
      Error e;
      const ActorHandle a = scene.AddRigidActor(d, &e);
      REQUIRE(a.IsValid());
      Run(&scene, 0.5, 1e-2);
      RigidBodyState s = scene.State(a);
      CHECK((s.p - Eigen::Vector3d(0.5, 0, 1)).norm() < 1e-12);
      CHECK((s.R - ExpSo3(Eigen::Vector3d(0, 0, M_PI / 4))).norm() < 1e-12);
      CHECK((s.v - Eigen::Vector3d(1, 0, 0)).norm() < 1e-12);
      CHECK((s.AngularVelocity() - Eigen::Vector3d(0, 0, M_PI / 2)).norm() < 1e-12);
      Run(&scene, 1.0, 1e-2);
      s = scene.State(a);
      CHECK((s.p - Eigen::Vector3d(1, 0.5, 1)).norm() < 1e-12);
      CHECK((s.v - Eigen::Vector3d(0, 1, 0)).norm() < 1e-12);
      CHECK(s.AngularVelocity().norm() < 1e-12);
      // Its state is not the user's to set.
      CHECK_FALSE(scene.SetState(a, s, &e));
      CHECK_THAT(e.message, Catch::Contains("kinematic actor"));
    }
  }
}

TEST_CASE("kinematic actors: a plate pushing a box at constant speed needs mu m g",
          "[core][kinematic][contact_report][physics]") {
  // A 1 kg slab (0.2 × 0.2 × 0.05 m) on the ground (combined μ = 0.5), pushed along x at 0.1 m/s
  // (10 V_f: full Coulomb friction) by a frictionless kinematic plate moving at constant velocity.
  // Once the slab moves with the plate, the plate's push balances the ground's friction μ m g;
  // both pair totals sum both passes of their pairs (the plate's and the slab's samples). (A tall
  // cube pushed at mid-height rocks without settling, with a heavy dynamic plate as with a
  // kinematic one: the slab keeps the push's moment small.)
  for (int mode : {0, 1}) {
    DYNAMIC_SECTION(test::kModeNames[mode]) {
      SceneSettings settings = Settings(IntegrationMethod::BDF2, Eigen::Vector3d(0, 0, -kG));
      settings.eval = test::EvalParamsForMode(mode);
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::Ground(Eigen::Vector3d::UnitZ(), 1e7, 0.5, 5.0), &e)
                  .IsValid());
      RigidActorDesc cube = test::Cube(1e7, 0.5, 5.0);
      cube.shape.halfExtents.z() = 0.025;
      cube.position.z() = 0.025;
      const ActorHandle c = scene.AddRigidActor(cube, &e);
      REQUIRE(c.IsValid());
      RigidActorDesc plate = KinematicBox("plate", Eigen::Vector3d(0.01, 0.15, 0.02));
      plate.shape.surfaceResolution = 4;
      plate.position = Eigen::Vector3d(-0.11 - 0.002, 0, 0.025);
      plate.linearVelocity = Eigen::Vector3d(0.1, 0, 0);
      plate.contact.penaltyCoefficient = 1e7;
      plate.contact.coulombFrictionCoefficient = 0.0;
      plate.contact.normalViscousDampingCoefficient = 5.0;  // pairs take the geometric mean
      const ActorHandle p = scene.AddRigidActor(plate, &e);
      REQUIRE(p.IsValid());
      Run(&scene, 1.0, 1e-3);
      const RigidBodyState s = scene.State(c);
      CHECK(s.v.x() == Approx(0.1).epsilon(1e-3));
      CHECK(scene.State(p).p.x() == Approx(-0.112 + 0.1).epsilon(1e-12));
      double push = NAN, friction = NAN;
      for (const ContactPairSummary& q : SummarizeContactPairs(scene.ContactSamples())) {
        if (q.a == c.index && q.b == p.index) push = q.force.x();  // on the cube (a): +x
        if (q.a == 0 && q.b == c.index) friction = q.frictionForce.x();  // on the ground: +x
      }
      const double expected = 0.5 * 1.0 * kG;
      CHECK(push == Approx(expected).epsilon(0.01));
      CHECK(friction == Approx(expected).epsilon(0.01));
      // Sideways: the faces' triangulations are not mirror-symmetric (measured 33 µm over 0.1 m).
      CHECK(s.p.y() == Approx(0.0).margin(1e-4));
    }
  }
}
