// The scenes of the hard-case suite (tests/core/test_hard_cases.cpp), shared with the trajectory
// regression recorder (tests/regression/).
#pragma once

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>

#include "core/scene.h"
#include "scene_builders.h"

namespace superdex::test {

inline RigidActorDesc HardCaseBox(const std::string& name, double side, double mass,
                                  const Eigen::Vector3d& p) {
  RigidActorDesc d = Cube(1e9, 0.5, 0.0);
  d.name = name;
  d.shape.halfExtents = Eigen::Vector3d::Constant(side / 2);
  d.mass = mass;
  d.position = p;
  return d;
}

/// A 1000 kg box on a 1 kg box on the ground (step 1e-2 s).
inline Scene MassRatioStack() {
  Scene scene;
  Error e;
  REQUIRE(scene.AddRigidActor(StaticGround(), &e).IsValid());
  REQUIRE(scene.AddRigidActor(HardCaseBox("light", 0.2, 1.0, {0, 0, 0.1 + 1e-5}), &e).IsValid());
  REQUIRE(scene.AddRigidActor(HardCaseBox("heavy", 0.2, 1000.0, {0, 0, 0.3 + 2e-5}), &e).IsValid());
  return scene;
}

/// The incline's angle [rad] of SteepIncline.
constexpr double kSteepInclineAngle = 40.0 * M_PI / 180.0;

/// A flat box (0.3 × 0.3 × 0.1 m), μ = 1, V_f = 1e-5 m/s, on a 40° incline (BackwardEuler).
/// A 0.2 m cube is close to tipping on 40° (it must carry its load 0.1 tan 40° = 0.084 m downhill
/// of the centre, and its outermost quadrature samples lie at 0.083 m (2 cells per edge) or
/// 0.092 m (4 cells): measured, it tips over in both cases).
inline Scene SteepIncline() {
  const double th = kSteepInclineAngle;
  const Eigen::Vector3d n(std::sin(th), 0, std::cos(th));
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BackwardEuler;
  Scene scene(settings);
  Error e;
  REQUIRE(scene.AddRigidActor(Ground(n, 1e9, 1.0, 1.0), &e).IsValid());
  RigidActorDesc cube = Cube(1e9, 1.0, 1.0);
  cube.shape.halfExtents = Eigen::Vector3d(0.15, 0.15, 0.05);
  cube.shape.surfaceResolution = 3;
  cube.contact.frictionFalloffVel = 1e-5;
  cube.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(th, Eigen::Vector3d::UnitY()));
  cube.position = n * (0.05 + 1e-5);
  REQUIRE(scene.AddRigidActor(cube, &e).IsValid());
  return scene;
}

/// A box resting on the ground with k = 1e11 Pa/m on both.
inline Scene StiffRestingBox() {
  Scene scene;
  Error e;
  REQUIRE(scene.AddRigidActor(StaticGround(1e11, 0.5), &e).IsValid());
  RigidActorDesc b = HardCaseBox("box", 0.2, 1.0, {0, 0, 0.101});
  b.contact.penaltyCoefficient = 1e11;
  REQUIRE(scene.AddRigidActor(b, &e).IsValid());
  return scene;
}

/// A stack of 5 boxes of 0.2 m, 1 kg on the ground.
inline Scene FiveBoxStack() {
  Scene scene;
  Error e;
  REQUIRE(scene.AddRigidActor(StaticGround(), &e).IsValid());
  for (int k = 0; k < 5; ++k)
    REQUIRE(scene.AddRigidActor(HardCaseBox("b" + std::to_string(k), 0.2, 1.0,
                                            {0, 0, 0.1 + 0.2 * k + 1e-5 * (k + 1)}), &e)
                .IsValid());
  return scene;
}

/// A 0.2 m, 1 kg box spinning at 20 rad/s about z on the ground (μ = 0.5).
inline Scene SpinningBox() {
  Scene scene;
  Error e;
  REQUIRE(scene.AddRigidActor(StaticGround(1e9, 0.5), &e).IsValid());
  RigidActorDesc b = HardCaseBox("box", 0.2, 1.0, {0, 0, 0.1000165});
  b.angularVelocity = Eigen::Vector3d(0, 0, 20.0);
  REQUIRE(scene.AddRigidActor(b, &e).IsValid());
  return scene;
}

/// A sphere (r = 0.05 m, 1 kg, k = 1e11 Pa/m) at 20 m/s towards a static 1 × 1 × 0.01 m plate.
inline Scene SphereAtPlate() {
  Scene scene;
  Error e;
  RigidActorDesc plate;
  plate.name = "plate";
  plate.dynamic = false;
  plate.shape.kind = RigidShapeKind::Box;
  plate.shape.halfExtents = Eigen::Vector3d(0.5, 0.5, 0.005);
  REQUIRE(scene.AddRigidActor(plate, &e).IsValid());
  RigidActorDesc ball;
  ball.name = "ball";
  ball.shape.radius = 0.05;
  ball.shape.surfaceResolution = 3;
  ball.mass = 1.0;
  ball.position = Eigen::Vector3d(0, 0, 0.005 + 0.05 + 0.01);
  ball.linearVelocity = Eigen::Vector3d(0, 0, -20.0);
  ball.contact.penaltyCoefficient = 1e11;  // k of a static collider's pair: the colliding actor's
  REQUIRE(scene.AddRigidActor(ball, &e).IsValid());
  return scene;
}

/// 14 rows of 0.2 m, 1 kg boxes (14 at the base, 1 at the top, 1 mm gaps in a row): 106 actors.
inline Scene BoxPyramid() {
  Scene scene;
  Error e;
  REQUIRE(scene.AddRigidActor(StaticGround(), &e).IsValid());
  const int rows = 14;
  for (int r = 0; r < rows; ++r) {
    const int n = rows - r;
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d p(0.201 * (k - 0.5 * (n - 1)), 0.0, 0.1 + 0.2 * r);
      REQUIRE(scene.AddRigidActor(HardCaseBox("b" + std::to_string(r) + "_" + std::to_string(k),
                                              0.2, 1.0, p), &e).IsValid());
    }
  }
  return scene;
}

/// The container of scenes/data/pile.json (a 0.1 m floor slab, four 0.1 m walls, 1.3 m inside)
/// with a 4 × 4 × 10 column of its spheres (r = 0.05 m, density 1000, 0.11 m pitch, 4 mm jitter),
/// in dissipation mode `mode` (kModeNames). Actors 0-4 are the container.
inline Scene SphereColumn(int mode) {
  SceneSettings settings;
  settings.eval = EvalParamsForMode(mode);
  Scene scene(settings);
  Error e;
  auto slab = [&](const std::string& name, const Eigen::Vector3d& size, const Eigen::Vector3d& p) {
    RigidActorDesc d;
    d.name = name;
    d.dynamic = false;
    d.shape.kind = RigidShapeKind::Box;
    d.shape.halfExtents = 0.5 * size;
    d.position = p;
    REQUIRE(scene.AddRigidActor(d, &e).IsValid());
  };
  slab("floor", {1.4, 1.4, 0.1}, {0, 0, -0.05});
  slab("wall_x0", {0.1, 1.4, 1.2}, {-0.7, 0, 0.6});
  slab("wall_x1", {0.1, 1.4, 1.2}, {0.7, 0, 0.6});
  slab("wall_y0", {1.3, 0.1, 1.2}, {0, -0.7, 0.6});
  slab("wall_y1", {1.3, 0.1, 1.2}, {0, 0.7, 0.6});
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int k = 0;
  for (int z = 0; z < 10; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x, ++k) {
        RigidActorDesc d;
        d.name = "ball_" + std::to_string(k);
        d.shape.radius = 0.05;
        d.shape.surfaceResolution = 2;
        d.position = Eigen::Vector3d(-0.165 + 0.11 * x, -0.165 + 0.11 * y, 0.1 + 0.11 * z) +
                     0.004 * Eigen::Vector3d(u(rng), u(rng), u(rng));
        REQUIRE(scene.AddRigidActor(d, &e).IsValid());
      }
  return scene;
}

}  // namespace superdex::test
