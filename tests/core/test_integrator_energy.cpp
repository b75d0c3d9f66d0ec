// Energy behaviour of the integrator family: the symplectic methods keep a frictionless, undamped
// bouncing box's energy bounded without drift over 10⁴ steps; the L-stable methods damp the stiff
// penalty mode of a box resting on a plane, the symplectic ones do not.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/scene.h"
#include "scene_builders.h"

using namespace superdex;

TEST_CASE("symplectic methods: bounded energy, no drift, over 10^4 steps of a bouncing box",
          "[core][physics][energy]") {
  // A 0.2 m, 1 kg cube (k = 1e6 Pa/m, μ = 0, c_n = 0) dropped flat from 0.1 m: each impact
  // lasts ~20 ms, resolved by ~40 steps of 5e-4 s (asserted: >= 20).
  for (IntegrationMethod m : {IntegrationMethod::SymplecticDIRK12, IntegrationMethod::SymplecticDIRK22}) {
    DYNAMIC_SECTION(ToString(m)) {
      SceneSettings settings;
      settings.integrator = m;
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::Ground(Eigen::Vector3d::UnitZ(), 1e6, 0.0, 0.0), &e).IsValid());
      RigidActorDesc box = test::Cube(1e6, 0.0, 0.0);
      box.position = Eigen::Vector3d(0, 0, 0.2 + 0.001);
      REQUIRE(scene.AddRigidActor(box, &e).IsValid());
      const double dt = 5e-4;
      const int steps = 10000;
      const double E0 = scene.Energies().Total();
      double maxDeviation = 0.0;
      int impacts = 0, run = 0, shortest = 1 << 30;
      // Least-squares trend of E(t): slope over the run.
      double st = 0, sE = 0, stt = 0, stE = 0;
      for (int i = 0; i < steps; ++i) {
        StepReport r;
        REQUIRE(scene.Step(dt, &r, &e));
        REQUIRE(r.status == StageStatus::Converged);
        if (r.contact.activeSamples > 0) {
          ++run;
        } else if (run > 0) {
          ++impacts;
          shortest = std::min(shortest, run);
          run = 0;
        }
        const double E = scene.Energies().Total(), t = scene.Time();
        maxDeviation = std::max(maxDeviation, std::abs(E - E0));
        st += t;
        sE += E;
        stt += t * t;
        stE += t * E;
      }
      const double slope = (steps * stE - st * sE) / (steps * stt - st * st);
      const double T = steps * dt;
      INFO("E0 = " << E0 << " J, max |E − E0| = " << maxDeviation << " J, trend " << slope * T
                   << " J over " << T << " s, " << impacts << " impacts, shortest " << shortest
                   << " steps");
      REQUIRE(impacts >= 5);
      CHECK(shortest >= 20);
      CHECK(maxDeviation <= 0.01 * std::abs(E0));
      CHECK(std::abs(slope * T) <= 1e-3 * std::abs(E0));
    }
  }
}

TEST_CASE("L-stable methods damp the stiff penalty mode; symplectic methods keep it",
          "[core][physics][energy]") {
  // The cube resting at its equilibrium height, given 0.05 m/s downward: its vertical penalty
  // mode (ω ≈ 220 rad/s at the rest load with the default ramp) is stepped at ω Δt ≈ 11.
  auto residualSpeed = [](IntegrationMethod m) {
    SceneSettings settings;
    settings.integrator = m;
    Scene scene(settings);
    Error e;
    REQUIRE(scene.AddRigidActor(test::Ground(Eigen::Vector3d::UnitZ(), 1e9, 0.0, 0.0), &e).IsValid());
    RigidActorDesc box = test::Cube(1e9, 0.0, 0.0);
    box.position = Eigen::Vector3d(0, 0, 0.1000165);  // the rest height (box_rest scene)
    box.linearVelocity = Eigen::Vector3d(0, 0, -0.05);
    REQUIRE(scene.AddRigidActor(box, &e).IsValid());
    double last = 0.0;
    for (int i = 0; i < 20; ++i) {
      StepReport r;
      REQUIRE(scene.Step(0.05, &r, &e));
      REQUIRE(r.status == StageStatus::Converged);
      last = std::abs(scene.State(ActorHandle{1}).v.z());
    }
    return last;
  };
  for (IntegrationMethod m : {IntegrationMethod::BackwardEuler, IntegrationMethod::DIRK22,
                              IntegrationMethod::DIRK33}) {
    const double v = residualSpeed(m);
    INFO(ToString(m) << ": |v_z| after 1 s = " << v << " m/s");
    CHECK(v < 1e-6);
  }
  for (IntegrationMethod m : {IntegrationMethod::SymplecticDIRK12, IntegrationMethod::SymplecticDIRK22}) {
    // A symplectic map keeps the mode's energy: the velocity stays of the initial order (its
    // phase at t = 1 s is arbitrary, so the bound is on the energy: ½ m v² + ½ k_eff z²).
    SceneSettings settings;
    settings.integrator = m;
    Scene scene(settings);
    Error e;
    REQUIRE(scene.AddRigidActor(test::Ground(Eigen::Vector3d::UnitZ(), 1e9, 0.0, 0.0), &e).IsValid());
    RigidActorDesc box = test::Cube(1e9, 0.0, 0.0);
    box.position = Eigen::Vector3d(0, 0, 0.1000165);
    box.linearVelocity = Eigen::Vector3d(0, 0, -0.05);
    REQUIRE(scene.AddRigidActor(box, &e).IsValid());
    const double E0 = scene.Energies().Total();
    double minEnergyAbove = INFINITY;  // E − E_rest at the end
    for (int i = 0; i < 20; ++i) {
      StepReport r;
      REQUIRE(scene.Step(0.05, &r, &e));
      REQUIRE(r.status == StageStatus::Converged);
    }
    const double kinetic0 = 0.5 * 0.05 * 0.05;
    const double E1 = scene.Energies().Total();
    INFO(ToString(m) << ": E0 = " << E0 << ", E(1 s) = " << E1 << " J, initial mode energy "
                     << kinetic0 << " J");
    (void)minEnergyAbove;
    CHECK(std::abs(E1 - E0) < 0.2 * kinetic0);
  }
}
