// Contact mechanics between bodies against analytic expectations: friction between two dynamic
// bodies, tipping against sliding, rolling on a curved collider.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/scene.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

constexpr double kG = 9.81;

ExperimentalEvalParams Mode(int m) {
  ExperimentalEvalParams p;
  p.explicitNormals = m == 0;
  p.implicitNormalForceForDissipation = m == 2;
  return p;
}
const char* const kModeNames[] = {"explicit normals", "reconstructed load", "current load"};

RigidActorDesc Box(const std::string& name, const Eigen::Vector3d& half, double mass, double mu) {
  RigidActorDesc d;
  d.name = name;
  d.shape.kind = RigidShapeKind::Box;
  d.shape.halfExtents = half;
  d.shape.surfaceResolution = 2;
  d.mass = mass;
  d.contact.penaltyCoefficient = 1e9;
  d.contact.coulombFrictionCoefficient = mu;
  return d;
}

}  // namespace

// A 0.2 m, 1 kg cube thrown at v0 = 1 m/s across a 0.6 × 0.6 × 0.1 m, 2 kg box that rests on a
// frictionless plane (μ = 0.5 between the boxes): friction between two dynamic bodies. The cube
// decelerates at μ g, the box accelerates at μ g m1/m2, so the cube slides
// v0² / (2 μ g (1 + m1/m2)) = 67.96 mm across the box before both move at m1 v0/(m1 + m2), and the
// horizontal momentum m1 v0 is kept throughout (the plane's force is normal to it). Both boxes
// are settled for 0.3 s before the throw. Each box is both colliding and collider, so the pair is
// two passes (the cube's samples on the box, the box's on the cube). Measured (BDF2, relative
// slide of the two contact faces' centres, averaged over 0.5–0.6 s after the throw):
//   Δt = 1e-3: explicit normals −0.58 %, reconstructed load −1.38 %, current load −0.92 %;
//   Δt = 1e-2: explicit normals −1.02 %, current load −0.34 %, reconstructed load −10.3 %.
// The default mode's excess friction at the coarse step is the first-order reconstruction of the
// stage-start distance at the cube's leading edge: a box sample that crosses into the cube's
// footprint during the stage is read as having been under the cube's bottom face at the stage
// start (φ + ∇Φ·(Y_n − Y) extends that face past the edge), so it carries a full sample's load for
// the whole stage where its true stage-start load was zero (one such sample: 23 N of friction load
// against the cube's weight 9.8 N). The excess is O(v Δt) per unit edge length: −10.3, −4.2, −1.3,
// −1.4, −0.8 % at Δt = 1e-2, 5e-3, 2e-3, 1e-3, 5e-4; with the cube alone colliding (single pass)
// −1.1 % at 1e-2 in every mode. Documented in the README ("Dissipation modes").
TEST_CASE("friction between two dynamic boxes: a cube thrown on a box over frictionless ground",
          "[core][physics][friction]") {
  const double mu = 0.5, v0 = 1.0, m1 = 1.0, m2 = 2.0;
  const double expected = v0 * v0 / (2 * mu * kG * (1 + m1 / m2));
  struct Case {
    int mode;
    double dt;
  };
  for (const Case& c : {Case{0, 1e-3}, Case{1, 1e-3}, Case{2, 1e-3}, Case{0, 1e-2}, Case{2, 1e-2}}) {
    DYNAMIC_SECTION(kModeNames[c.mode] << ", dt = " << c.dt) {
      SceneSettings settings;
      settings.integrator = IntegrationMethod::BDF2;
      settings.eval = Mode(c.mode);
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::StaticGround(1e9, 0.0), &e).IsValid());
      RigidActorDesc bottom = Box("box", Eigen::Vector3d(0.3, 0.3, 0.05), m2, mu);
      bottom.position = Eigen::Vector3d(0, 0, 0.05 + 2e-4);
      RigidActorDesc top = Box("cube", Eigen::Vector3d::Constant(0.1), m1, mu);
      top.position = Eigen::Vector3d(-0.1, 0, 0.2 + 4e-4);
      const ActorHandle hb = scene.AddRigidActor(bottom, &e);
      const ActorHandle ht = scene.AddRigidActor(top, &e);
      REQUIRE(ht.IsValid());
      // x of the cube's bottom face centre relative to the box's top face centre [m].
      auto relative = [&] {
        const RigidBodyState& a = scene.State(ht);
        const RigidBodyState& b = scene.State(hb);
        return (a.p + a.R * Eigen::Vector3d(0, 0, -0.1) - b.p - b.R * Eigen::Vector3d(0, 0, 0.05)).x();
      };
      auto step = [&] {
        StepReport rep;
        REQUIRE(scene.Step(c.dt, &rep, &e));
        REQUIRE(rep.status == StageStatus::Converged);
      };
      for (int i = 0; i < int(std::lround(0.3 / c.dt)); ++i) step();
      RigidBodyState thrown = scene.State(ht);
      thrown.v.x() += v0;
      REQUIRE(scene.SetState(ht, thrown, &e));
      const double p0 = m1 * scene.State(ht).v.x() + m2 * scene.State(hb).v.x();
      const double x0 = relative();
      double slide = 0.0, maxMomentumError = 0.0;
      int late = 0;
      const int steps = int(std::lround(0.6 / c.dt));
      for (int i = 1; i <= steps; ++i) {
        step();
        const double p = m1 * scene.State(ht).v.x() + m2 * scene.State(hb).v.x();
        maxMomentumError = std::max(maxMomentumError, std::abs(p - p0));
        if (i * c.dt > 0.5) {
          slide += relative() - x0;
          ++late;
        }
      }
      slide /= late;
      INFO("relative slide " << slide << " m, expected " << expected << " ("
                             << (slide / expected - 1) * 100 << " %); momentum error "
                             << maxMomentumError << " kg m/s");
      CHECK(maxMomentumError < 1e-9 * m1 * v0);
      CHECK(std::abs(slide - expected) < 0.02 * expected);
    }
  }
}
