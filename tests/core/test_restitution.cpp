// Hunt–Crossley restitution (spec: "Restitution Behavior of Rigid Collisions"): with gravity off,
// a cube launched flat at a plane rebounds with e(c_n v). For a damping force c_n V_n times the
// elastic force, e depends on c_n v alone, whatever the elastic law (the impact integral
// ∫ u/(1 + c_n u) du = 0 from v to −e v); the spec's rational formula approximates that relation
// within 1.5% for c_n v <= 2.5.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/scene.h"
#include "energies/contact_dissipation.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

struct Bounce {
  double e = 0.0;
  int contactSteps = 0;
  double maxPenetration = 0.0;
};

// A 0.2 m, 1 kg cube, k = 1e6 Pa/m, face down 0.1 mm above the contact threshold, moving at
// −v toward the plane z = 0. Returns the rebound speed ratio once no sample is active.
Bounce Launch(double v, double cn, double dt, const ExperimentalEvalParams& eval) {
  SceneSettings settings;
  settings.gravity.setZero();
  settings.integrator = IntegrationMethod::BDF2;
  settings.eval = eval;
  Scene scene(settings);
  Error e;
  REQUIRE(scene.AddRigidActor(test::Ground(Eigen::Vector3d::UnitZ(), 1e6, 0.5, cn), &e).IsValid());
  RigidActorDesc cube = test::Cube(1e6, 0.5, cn);
  const double delta = cube.contact.penaltyThresholdDefault;
  cube.position = Eigen::Vector3d(0, 0, 0.1 + delta + 1e-4);
  cube.linearVelocity = Eigen::Vector3d(0, 0, -v);
  REQUIRE(scene.AddRigidActor(cube, &e).IsValid());
  const ActorHandle h{1};
  Bounce b;
  bool touched = false;
  for (int i = 0; i < 1000000; ++i) {
    StepReport r;
    REQUIRE(scene.Step(dt, &r, &e));
    INFO("step " << i << ": " << r.message);
    REQUIRE(r.status == StageStatus::Converged);
    const bool active = r.contact.activeSamples > 0;
    if (active) {
      touched = true;
      ++b.contactSteps;
      b.maxPenetration = std::max(b.maxPenetration, -r.contact.minSignedDistance);
    } else if (touched) {
      b.e = scene.State(h).v.z() / v;
      return b;
    }
  }
  FAIL("the cube never left the plane");
  return b;
}

}  // namespace

TEST_CASE("restitution matches the rational Hunt-Crossley formula within 3% and falls with c_n",
          "[core][physics][restitution]") {
  const ExperimentalEvalParams defaults;
  for (double v : {1.0, 4.0}) {
    double previous = 1.0;
    for (double cnv : {0.25, 1.0, 2.5}) {
      const double cn = cnv / v;
      // At least 100 steps in contact: the contact lasts about 16 ms at 4 m/s, longer at 1 m/s.
      const double dt = 5e-5;
      const Bounce b = Launch(v, cn, dt, defaults);
      const double expected = HuntCrossleyRestitutionFromDamping(cn, v);
      INFO("v = " << v << " m/s, c_n v = " << cnv << ": e = " << b.e << ", formula " << expected
                  << ", " << b.contactSteps << " steps in contact");
      CHECK(b.contactSteps >= 100);
      CHECK(std::abs(b.e - expected) < 0.03 * expected);
      CHECK(b.e < previous);
      previous = b.e;
    }
  }
}

TEST_CASE("restitution converges as the step shrinks, in every dissipation mode",
          "[core][physics][restitution]") {
  // Reference: the exact Hunt–Crossley relation at c_n v = 1, e = 0.593624 (the root of
  // ∫_{−e}^{1} u/(1 + u) du = 0), which the spec's rational formula approximates by 0.58668.
  const double exact = 0.59362426004004;
  for (int m = 0; m < 3; ++m) {
    const ExperimentalEvalParams eval = test::EvalParamsForMode(m);
    double previousError = INFINITY;
    for (double dt : {4e-4, 2e-4, 1e-4}) {
      const Bounce b = Launch(4.0, 0.25, dt, eval);
      const double error = std::abs(b.e - exact);
      INFO("mode " << m << " dt " << dt << ": e = " << b.e << ", |e − e_exact| = " << error);
      CHECK(error < previousError);
      previousError = error;
    }
  }
}
