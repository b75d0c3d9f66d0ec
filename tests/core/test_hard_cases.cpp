// Hard cases: each asserts no NaN, every stage converged, and a stated penetration or motion bound.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>

#include "core/scene.h"
#include "hard_case_scenes.h"

using namespace superdex;

namespace {

struct Outcome {
  int notConverged = 0;
  double maxPenetration = 0.0;  // max over steps of −min φ [m]
  bool finite = true;
  int fallbacks = 0;  // stages re-solved with explicit normals
};

Outcome Run(Scene& scene, double dt, double duration) {
  Outcome o;
  Error e;
  const int steps = static_cast<int>(std::lround(duration / dt));
  for (int i = 0; i < steps; ++i) {
    StepReport r;
    REQUIRE(scene.Step(dt, &r, &e));
    o.notConverged += r.status != StageStatus::Converged;
    o.fallbacks += r.fallbacks;
    if (r.status != StageStatus::Converged) WARN("step " << i << ": " << r.message);
    o.maxPenetration = std::max(o.maxPenetration, -r.contact.minSignedDistance);
    for (ActorHandle h : scene.RigidActors()) {
      const RigidBodyState s = scene.State(h);
      o.finite &= s.p.allFinite() && s.R.allFinite();
    }
  }
  return o;
}

}  // namespace

TEST_CASE("hard case: 1000:1 mass ratio, a 1000 kg box on a 1 kg box", "[core][hard]") {
  Scene scene = test::MassRatioStack();
  const Outcome o = Run(scene, 1e-2, 2.0);
  INFO("max penetration " << o.maxPenetration * 1e3 << " mm, heavy at z = "
                          << scene.State({2}).p.z());
  CHECK(o.finite);
  CHECK(o.notConverged == 0);
  CHECK(o.maxPenetration < 0.01);
  CHECK(std::abs(scene.State({2}).p.z() - 0.3) < 0.01);
}

TEST_CASE("hard case: mu = 1 box on a 40 degree incline with V_f = 1e-5 m/s holds",
          "[core][hard][friction]") {
  const double th = test::kSteepInclineAngle;
  const Eigen::Vector3d down(std::cos(th), 0, -std::sin(th));
  Scene scene = test::SteepIncline();
  const auto bottom = [&]() -> Eigen::Vector3d {
    return scene.State({1}).p + scene.State({1}).R * Eigen::Vector3d(0, 0, -0.05);
  };
  Outcome o = Run(scene, 1e-2, 0.5);  // release transient
  const Eigen::Vector3d b0 = bottom();
  const Outcome o2 = Run(scene, 1e-2, 1.0);
  const double creep = (bottom() - b0).dot(down);  // over 1 s
  INFO("creep " << creep * 1e3 << " mm/s after the release; penetration "
                << std::max(o.maxPenetration, o2.maxPenetration) * 1e3 << " mm");
  CHECK(o.finite);
  CHECK(o.notConverged + o2.notConverged == 0);
  CHECK(std::abs(creep) < 1e-5);
}

TEST_CASE("hard case: stiff contact k = 1e11 and a coarse step 1/30 s", "[core][hard]") {
  SECTION("k = 1e11, box resting") {
    Scene scene = test::StiffRestingBox();
    const Outcome o = Run(scene, 5e-3, 1.0);
    CHECK(o.finite);
    CHECK(o.notConverged == 0);
    CHECK(o.maxPenetration < 1e-3);
  }
  SECTION("dt = 1/30 s, a stack of 5 boxes stands") {
    Scene scene = test::FiveBoxStack();
    const Outcome o = Run(scene, 1.0 / 30, 3.0);
    INFO("top at z = " << scene.State({5}).p.z());
    CHECK(o.finite);
    CHECK(o.notConverged == 0);
    CHECK(std::abs(scene.State({5}).p.z() - 0.9) < 0.01);
    CHECK(std::abs(scene.State({5}).p.x()) < 1e-3);
  }
}

TEST_CASE("hard case: a box spinning on a plane stops at the friction-torque rate",
          "[core][hard][friction]") {
  // Uniform pressure m g / A on the bottom face; sliding friction torque Σ μ (m g / A) w_q |r_q|
  // over the bottom samples (the quadrature's own ∫|r| dA), I = m a²/6.
  Scene scene = test::SpinningBox();
  double integral = 0.0;  // Σ w |r| over the bottom face
  for (const SurfaceSample& s : scene.Model({1}).samples)
    if (s.normal.z() < -0.5) integral += s.weight * s.X.head<2>().norm();
  const double I = 1.0 * 0.04 / 6.0, A = 0.04;
  const double expected = 0.5 * 9.81 * 1.0 / A * integral / I;  // [rad/s²]
  Run(scene, 2e-3, 0.05);  // settle the spin-up of the contact
  const double w0 = scene.State({1}).Rdot.norm() / std::sqrt(2.0);
  const double t0 = scene.Time();
  const Outcome o = Run(scene, 2e-3, 0.15);
  const double w1 = scene.State({1}).Rdot.norm() / std::sqrt(2.0);
  const double rate = (w0 - w1) / (scene.Time() - t0);
  INFO("spin-down " << rate << " rad/s², expected " << expected << "; ω " << w0 << " → " << w1);
  CHECK(o.notConverged == 0);
  CHECK(std::abs(rate - expected) < 0.02 * expected);
}

TEST_CASE("hard case: a 20 m/s sphere does not tunnel through a 1 cm static plate",
          "[core][hard]") {
  // Sphere r = 0.05 m, 1 kg; plate 1 × 1 × 0.01 m. At Δt = 1e-4 s the sphere moves 2 mm per
  // step, a fifth of the plate, so its samples cannot skip the plate's interior. The penalty
  // must also be able to absorb the 200 J within half the plate (beyond the mid-plane the box
  // SDF pushes towards the far face): with the default k = 1e9 Pa/m the work over 5 mm is about
  // ½ k d (π 2 r d) d ≈ 20 J and the sphere tunnels (measured); k = 1e11 stops it.
  Scene scene = test::SphereAtPlate();
  const Outcome o = Run(scene, 1e-4, 0.05);
  INFO("ball at z = " << scene.State({1}).p.z() << ", v_z = " << scene.State({1}).v.z()
                      << ", max penetration " << o.maxPenetration * 1e3 << " mm, "
                      << o.fallbacks << " stages re-solved with explicit normals");
  CHECK(o.finite);
  CHECK(o.notConverged == 0);
  CHECK(scene.State({1}).p.z() > 0.005);  // above the plate
  CHECK(scene.State({1}).v.z() > 0.0);    // bounced
  // (−φ inside a box is at most its half thickness, 5 mm here: the bounce is the criterion.)
  // The impact's residual solve fails once and that stage is re-solved with explicit normals
  // (docs/benchmarks.md, hard cases): this case keeps the fallback path (StageDriver) exercised.
  CHECK(o.fallbacks >= 1);
}

TEST_CASE("hard case: a 105-box pyramid stands for 5 s at dt = 1/100 s", "[core][hard]") {
  // 14 rows (14 boxes at the base, 1 at the top) of 0.2 m, 1 kg boxes, 1 mm gaps within a row:
  // the "100-box pyramid". Same layout as scenes/data/pyramid.json.
  Scene scene = test::BoxPyramid();
  REQUIRE(scene.NumActors() == 106);
  const ActorHandle top{105};
  const Outcome o = Run(scene, 1e-2, 5.0);
  INFO("max penetration " << o.maxPenetration * 1e3 << " mm, top at "
                          << scene.State(top).p.transpose());
  CHECK(o.finite);
  CHECK(o.notConverged == 0);
  CHECK(o.maxPenetration < 2e-3);
  CHECK(std::abs(scene.State(top).p.z() - 2.7) < 0.01);  // settles by 3.4 mm (14 contact layers)
  CHECK(std::abs(scene.State(top).p.x()) < 1e-3);
}

TEST_CASE("hard case: a 160-sphere column falling at dt = 1/50 s neither stalls nor tunnels",
          "[core][hard]") {
  // The container of scenes/data/pile.json (a 0.1 m floor slab, four 0.1 m walls, 1.3 m inside)
  // with a 4 × 4 × 10 column of its spheres (r = 0.05 m, density 1000, 0.11 m pitch, 4 mm jitter)
  // falling onto its floor: the upper layers arrive at about 2 m/s, 4 cm per step. Newton
  // corrections then crossed the medial plane of another sphere or of a wall (the distance
  // field's gradient flips there and the body is pushed out the far side) and stalled along
  // shortened steps that were no descent direction: 46-50 mm penetration and stopped stages
  // before the trust region of SceneStageProblem::TrustStep (measured; 3.9 mm after).
  for (const int mode : {0, 1}) {
    DYNAMIC_SECTION(test::kModeNames[mode]) {
      Scene scene = test::SphereColumn(mode);
      const Outcome o = Run(scene, 0.02, 0.24);
      double inside = 0.0;  // largest |x|, |y| of a centre, and the lowest centre
      double lowest = INFINITY;
      const std::vector<ActorHandle> rigid = scene.RigidActors();
      for (size_t i = 5; i < rigid.size(); ++i) {
        const Eigen::Vector3d p = scene.State(rigid[i]).p;
        inside = std::max({inside, std::abs(p.x()), std::abs(p.y())});
        lowest = std::min(lowest, p.z());
      }
      INFO("max penetration " << o.maxPenetration * 1e3 << " mm, " << o.notConverged
                              << " stages not converged, " << o.fallbacks
                              << " re-solved with explicit normals; centres within |x|, |y| <= "
                              << inside << " m, lowest at z = " << lowest << " m");
      CHECK(o.finite);
      CHECK(o.notConverged == 0);
      CHECK(o.maxPenetration < 0.01);
      CHECK(inside < 0.6);     // no sphere left the container (inner faces at ±0.65 m)
      CHECK(lowest > 0.035);   // nor sank into the floor
    }
  }
}
