// Contact mechanics against analytic or independently computed expectations: friction between
// two dynamic bodies; the tipping angle of a tall box on the compliant contact.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/scene.h"
#include "energies/normal_penalty.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

constexpr double kG = 9.81;


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
    DYNAMIC_SECTION(test::kModeNames[c.mode] << ", dt = " << c.dt) {
      SceneSettings settings;
      settings.integrator = IntegrationMethod::BDF2;
      settings.eval = test::EvalParamsForMode(c.mode);
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

namespace {

// Statics of a rigid b × b × 2H box of mass m on an incline of angle θ, leaning by t toward the
// downhill side on the spec's penalty pressure λ_n(φ) = k h h' [Pa] (energies/normal_penalty.h),
// integrated across the base by the midpoint rule (the independent expectation of the tipping
// test). A base point at x [m] from the base centre, whose height above the plane is z0, sits at
// φ = z0 − x sin t; the pressure carries the weight's normal part and returns the moment
//   N = ∫ λ_n b dx = m g cos θ,     M = ∫ x cos t λ_n b dx                      [N], [N m]
// about the base centre. The creeping base's friction, m g sin θ spread like the pressure, acts
// on the tilted base and takes M tan t tan θ off it; equilibrium is
//   M (1 − tan t tan θ) = m g H sin(t + θ).
struct TippingStatics {
  double b = 0.1, H = 0.15, m = 1.0;
  PenaltyParams penalty;
  static constexpr int kCells = 500;

  // Normal force [N] and moment about the base centre [N m] at tilt t [rad], base-centre height z0.
  void ForceAndMoment(double t, double z0, double* F, double* M) const {
    *F = *M = 0.0;
    const double dx = b / kCells;
    for (int i = 0; i < kCells; ++i) {
      const double x = -0.5 * b + (i + 0.5) * dx;
      const double p = NormalPenaltyDensity(z0 - x * std::sin(t), penalty).lambdaN;
      *F += p * b * dx;
      *M += x * std::cos(t) * p * b * dx;
    }
  }
  // The base-centre height that carries m g cos θ at tilt t.
  double Height(double t, double theta) const {
    double lo = -0.05, hi = penalty.delta + b;
    for (int k = 0; k < 50; ++k) {
      const double mid = 0.5 * (lo + hi);
      double F, M;
      ForceAndMoment(t, mid, &F, &M);
      (F > m * kG * std::cos(theta) ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
  // Restoring minus overturning moment at tilt t [N m].
  double Imbalance(double t, double theta) const {
    double F, M;
    ForceAndMoment(t, Height(t, theta), &F, &M);
    return M * (1.0 - std::tan(t) * std::tan(theta)) - m * kG * H * std::sin(t + theta);
  }
  // The smallest equilibrium tilt (the stable one), or −1 if the box cannot stand.
  double EquilibriumTilt(double theta) const {
    double prev = 0.0;
    for (double t = 5e-4; t < 0.1; t += 5e-4) {
      if (Imbalance(t, theta) >= 0.0) {
        double lo = prev, hi = t;
        for (int k = 0; k < 30; ++k) {
          const double mid = 0.5 * (lo + hi);
          (Imbalance(mid, theta) >= 0.0 ? hi : lo) = mid;
        }
        return hi;
      }
      prev = t;
    }
    return -1.0;
  }
  // The steepest incline on which the box stands.
  double CriticalAngle() const {
    double lo = 0.0, hi = std::atan(0.5 * b / H);
    for (int k = 0; k < 25; ++k) {
      const double mid = 0.5 * (lo + hi);
      (EquilibriumTilt(mid) >= 0.0 ? lo : hi) = mid;
    }
    return lo;
  }
};

}  // namespace

// A 0.1 × 0.1 × 0.3 m, 1 kg box standing on an incline (μ = 1, so it cannot slide) tips where the
// moment of its weight about the base exceeds what the contact pressure can return. A rigid box
// tips at tan θ = b/(2H): 18.43°. The penalty's pressure k h h' is soft at light load (the C² ramp
// starts with zero slope: 0.58 mm in and 5e6 Pa/m under this box's 981 Pa), so the box leans into
// the plane and its centre of pressure cannot reach the edge: by the statics of the same pressure
// law across the base (TippingStatics, with the creeping base's friction moment) it stands up to
// 13.40°, leaning 2.17° there. Started at rest in its static pose, 0.5° below that angle it stays
// at the static lean (measured 1.416° against 1.406°, in every mode, BDF2 at Δt = 1e-2, surface
// resolution 8; 0.720° against 0.712° at 3° below), and 0.5° above it falls over. Released
// from rest undeformed instead, the box overshoots its lean and falls over from 12° up.
TEST_CASE("a tall box on an incline tips at the angle the compliant contact's statics predict",
          "[core][physics]") {
  static const TippingStatics statics;
  static const double critical = statics.CriticalAngle();  // once, not once per section
  REQUIRE(critical > 13.0 * M_PI / 180);
  REQUIRE(critical < 14.0 * M_PI / 180);
  for (int m = 0; m < 3; ++m) {
    for (double offset : {-0.5, 0.5}) {
      DYNAMIC_SECTION(test::kModeNames[m] << ", " << offset << " degree from the critical angle") {
        const double theta = critical + offset * M_PI / 180;
        // The static pose there (below the critical angle), or the critical pose (above).
        const double lean = statics.EquilibriumTilt(std::min(theta, critical));
        REQUIRE(lean > 0.0);
        SceneSettings settings;
        settings.integrator = IntegrationMethod::BDF2;
        settings.eval = test::EvalParamsForMode(m);
        Scene scene(settings);
        Error e;
        const Eigen::Vector3d n(std::sin(theta), 0, std::cos(theta));
        REQUIRE(scene.AddRigidActor(test::Ground(n, 1e9, 1.0, 0.0), &e).IsValid());
        RigidActorDesc box = Box("tall", Eigen::Vector3d(0.5 * statics.b, 0.5 * statics.b, statics.H),
                                 statics.m, 1.0);
        box.shape.surfaceResolution = 8;
        box.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(theta + lean, Eigen::Vector3d::UnitY()));
        box.position = statics.Height(lean, theta) * n +
                       statics.H * (box.orientation * Eigen::Vector3d::UnitZ());
        const ActorHandle h = scene.AddRigidActor(box, &e);
        REQUIRE(h.IsValid());
        const Eigen::Matrix3d onIncline =
            Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()).toRotationMatrix();
        double tilt = 0.0;
        for (int i = 0; i < 300; ++i) {
          StepReport rep;
          REQUIRE(scene.Step(1e-2, &rep, &e));
          REQUIRE(rep.status == StageStatus::Converged);
          tilt = Eigen::AngleAxisd(scene.State(h).R * onIncline.transpose()).angle();
        }
        INFO("critical angle " << critical * 180 / M_PI << " deg; incline " << theta * 180 / M_PI
                               << " deg: static lean " << lean * 180 / M_PI << " deg, after 3 s "
                               << tilt * 180 / M_PI << " deg");
        if (offset < 0)
          CHECK(std::abs(tilt - lean) < 0.03 * lean);
        else
          CHECK(tilt > M_PI / 3);
      }
    }
  }
}
