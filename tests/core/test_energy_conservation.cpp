// A frictionless, undamped sphere bouncing on a plane under implicit midpoint (SymplecticDIRK12)
// keeps its total energy (kinetic + gravity + penalty) within 1% over 5 s.
// Setting: sphere r = 0.1 m, 1 kg, k = 1e7 Pa/m, dropped from 0.2 m above contact, dt = 5e-4 s;
// each impact lasts about 22 ms, i.e. over 44 steps (asserted below: at least 10).
#include <catch2/catch.hpp>
#include <cmath>

#include "core/scene.h"
#include "scene_builders.h"

using namespace superdex;

TEST_CASE("SymplecticDIRK12 keeps the energy of a bouncing sphere", "[core][physics][energy]") {
  SceneSettings settings;
  settings.integrator = IntegrationMethod::SymplecticDIRK12;
  Scene scene(settings);
  Error e;
  REQUIRE(scene.AddRigidActor(test::StaticGround(1e7, 0.0), &e).IsValid());
  RigidActorDesc ball;
  ball.name = "ball";
  ball.shape.radius = 0.1;
  ball.shape.surfaceResolution = 2;
  ball.mass = 1.0;
  ball.position = Eigen::Vector3d(0, 0, 0.3 + 0.001);
  ball.contact.penaltyCoefficient = 1e7;
  ball.contact.coulombFrictionCoefficient = 0.0;
  REQUIRE(scene.AddRigidActor(ball, &e).IsValid());

  const double dt = 5e-4;
  const double E0 = scene.Energies().Total();
  double maxDeviation = 0.0;
  int impacts = 0, contactSteps = 0, shortest = 1 << 30, run = 0;
  for (int i = 0; i < static_cast<int>(5.0 / dt); ++i) {
    StepReport r;
    REQUIRE(scene.Step(dt, &r, &e));
    REQUIRE(r.status == StageStatus::Converged);
    if (r.contact.activeSamples > 0) {
      ++contactSteps;
      ++run;
    } else if (run > 0) {
      ++impacts;
      shortest = std::min(shortest, run);
      run = 0;
    }
    maxDeviation = std::max(maxDeviation, std::abs(scene.Energies().Total() - E0));
  }
  INFO("E0 = " << E0 << " J, max |E - E0| = " << maxDeviation << " J, " << impacts
               << " impacts, shortest " << shortest << " steps");
  REQUIRE(impacts >= 3);
  CHECK(shortest >= 10);
  CHECK(maxDeviation <= 0.01 * std::abs(E0));
}
