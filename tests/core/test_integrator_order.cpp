// Measured convergence order on a smooth contact problem: a box oscillating vertically on a plane
// with every bottom sample inside the polynomial part of the ramp (0 < δ − φ < 2ε), so the force
// is a smooth function of the height. Reference: the same 1-D equation
//   m z'' = −m g + k A h(φ) h'(φ),  φ = z − side/2,
// integrated independently by classical RK4 with a step 100 times smaller than the finest tested.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/scene.h"
#include "core/dynamics/integrators.h"
#include "energies/penalty_ramp.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

constexpr double kSide = 0.2, kMass = 1.0, kG = 9.81, kK = 1e6, kT = 0.1;
constexpr double kEps = 0.005, kDelta = 0.001;
constexpr double kZ0 = kSide / 2 + kDelta - 0.003;  // start at s = δ − φ = 3 mm, at rest

double Accel(double z) {
  const RampValue r = PenaltyRamp(z - kSide / 2, kEps, kDelta);
  return -kG + kK * kSide * kSide * r.h * r.dh / kMass;
}

double ReferenceHeight() {
  const int n = 200000;
  const double h = kT / n;
  double z = kZ0, v = 0.0;
  for (int i = 0; i < n; ++i) {
    const double k1z = v, k1v = Accel(z);
    const double k2z = v + 0.5 * h * k1v, k2v = Accel(z + 0.5 * h * k1z);
    const double k3z = v + 0.5 * h * k2v, k3v = Accel(z + 0.5 * h * k2z);
    const double k4z = v + h * k3v, k4v = Accel(z + h * k3z);
    z += h / 6 * (k1z + 2 * k2z + 2 * k3z + k4z);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  return z;
}

double SimulatedHeight(IntegrationMethod method, double dt) {
  SceneSettings settings;
  settings.integrator = method;
  settings.solver.absoluteTolerance = 1e-20;
  settings.solver.relativeTolerance = 1e-14;
  settings.solver.stepTolerance = 1e-12;
  Scene scene(settings);
  Error e;
  REQUIRE(scene.AddRigidActor(test::StaticGround(kK), &e).IsValid());
  RigidActorDesc box;
  box.name = "box";
  box.shape.kind = RigidShapeKind::Box;
  box.shape.halfExtents = Eigen::Vector3d::Constant(kSide / 2);
  box.shape.surfaceResolution = 1;
  box.mass = kMass;
  box.position = Eigen::Vector3d(0, 0, kZ0);
  box.contact.penaltyCoefficient = kK;
  const ActorHandle h = scene.AddRigidActor(box, &e);
  REQUIRE(h.IsValid());
  const int steps = static_cast<int>(std::lround(kT / dt));
  for (int i = 0; i < steps; ++i) {
    StepReport r;
    REQUIRE(scene.Step(dt, &r, &e));
    REQUIRE(r.status == StageStatus::Converged);
    const double s = kDelta - (scene.State(h).p.z() - kSide / 2);
    REQUIRE(s > 0.0);         // stays inside the smooth band
    REQUIRE(s < 2 * kEps);
  }
  return scene.State(h).p.z();
}

double MeasuredOrder(IntegrationMethod method, double dt) {
  const double ref = ReferenceHeight();
  const double e1 = std::abs(SimulatedHeight(method, dt) - ref);
  const double e2 = std::abs(SimulatedHeight(method, dt / 2) - ref);
  const double e3 = std::abs(SimulatedHeight(method, dt / 4) - ref);
  INFO(ToString(method) << ": errors " << e1 << ", " << e2 << ", " << e3 << " m");
  // Least-squares slope of log e against log dt over the three steps.
  const double p12 = std::log2(e1 / e2), p23 = std::log2(e2 / e3);
  return 0.5 * (p12 + p23);
}

}  // namespace

TEST_CASE("every integrator converges at its order on smooth contact", "[core][order]") {
  // Steps chosen so that the error stays well above the solver tolerance at the finest step
  // and the asymptotic regime is reached at the coarsest.
  struct Case { IntegrationMethod m; double dt; };
  for (const Case c : {Case{IntegrationMethod::BackwardEuler, 4e-4}, Case{IntegrationMethod::BDF2, 4e-4},
                       Case{IntegrationMethod::BDF3, 8e-4}, Case{IntegrationMethod::DIRK22, 4e-4},
                       Case{IntegrationMethod::DIRK23, 8e-4}, Case{IntegrationMethod::DIRK33, 8e-4},
                       Case{IntegrationMethod::SymplecticDIRK12, 4e-4},
                       Case{IntegrationMethod::SymplecticDIRK22, 4e-4}}) {
    DYNAMIC_SECTION(ToString(c.m)) {
      const double p = MeasuredOrder(c.m, c.dt);
      const int expected = DesignOrder(c.m);
      INFO("measured order " << p << ", design order " << expected);
      CHECK(std::abs(p - expected) <= 0.2);
    }
  }
}
