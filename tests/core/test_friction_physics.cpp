// Friction and damping against analytic expectations: the incline (sliding acceleration and the
// creep of regularized static friction) in every dissipation mode.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/scene.h"
#include "energies/contact_dissipation.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

constexpr double kG = 9.81;
const double kTheta = M_PI / 6;  // 30°

struct InclineRun {
  std::vector<double> t, s;  // time [s], distance travelled down the slope by the centre of the
                             // cube's bottom face [m] (insensitive to the cube's rocking)
  int worstStatus = 0;
  double maxRock = 0.0;      // largest rotation away from the initial orientation [rad]
  double maxSpinLate = 0.0;  // largest |ω| after the first 2 s [rad/s]
};

// A 0.2 m, 1 kg cube on a 30° incline (plane through the origin with normal (sin θ, 0, cos θ)),
// released at rest, face down.
InclineRun RunIncline(const ExperimentalEvalParams& eval, double mu, double vf, double cn,
                      double duration, double dt,
                      IntegrationMethod method = IntegrationMethod::BDF2) {
  SceneSettings settings;
  settings.integrator = method;
  settings.eval = eval;
  Scene scene(settings);
  Error e;
  const Eigen::Vector3d n(std::sin(kTheta), 0, std::cos(kTheta));
  const Eigen::Vector3d down(std::cos(kTheta), 0, -std::sin(kTheta));
  REQUIRE(scene.AddRigidActor(test::Ground(n, 1e9, mu, cn), &e).IsValid());
  RigidActorDesc cube = test::CubeOnIncline(kTheta, 1e9, mu, cn);
  cube.contact.frictionFalloffVel = vf;
  REQUIRE(scene.AddRigidActor(cube, &e).IsValid());
  const ActorHandle h{1};
  const Eigen::Vector3d p0 = scene.State(h).p;
  const Eigen::Matrix3d R0 = scene.State(h).R;
  const Eigen::Vector3d bottom0 = p0 + R0 * Eigen::Vector3d(0, 0, -0.1);
  InclineRun run;
  const int steps = static_cast<int>(std::lround(duration / dt));
  for (int i = 0; i < steps; ++i) {
    StepReport r;
    REQUIRE(scene.Step(dt, &r, &e));
    INFO("step " << i << ": " << r.message);
    REQUIRE(r.status == StageStatus::Converged);
    run.t.push_back(scene.Time());
    const Eigen::Vector3d bottom = scene.State(h).p + scene.State(h).R * Eigen::Vector3d(0, 0, -0.1);
    run.s.push_back((bottom - bottom0).dot(down));
    const Eigen::AngleAxisd rock(scene.State(h).R * R0.transpose());
    run.maxRock = std::max(run.maxRock, std::abs(rock.angle()));
    if (scene.Time() > 2.0) run.maxSpinLate = std::max(run.maxSpinLate, scene.State(h).AngularVelocity().norm());
  }
  return run;
}

// Least-squares fit s = c0 + c1 t + c2 t² over t in [t0, t1]; returns (c1, 2 c2) at t = 0 basis.
Eigen::Vector3d QuadraticFit(const InclineRun& run, double t0, double t1) {
  Eigen::MatrixXd A(0, 3);
  std::vector<Eigen::Vector3d> rows;
  std::vector<double> b;
  for (size_t i = 0; i < run.t.size(); ++i)
    if (run.t[i] >= t0 && run.t[i] <= t1) {
      rows.emplace_back(1.0, run.t[i], run.t[i] * run.t[i]);
      b.push_back(run.s[i]);
    }
  A.resize(rows.size(), 3);
  Eigen::VectorXd y(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    A.row(i) = rows[i].transpose();
    y[i] = b[i];
  }
  return A.colPivHouseholderQr().solve(y);
}


// A solid 1 kg ball of radius r [m] (surface resolution 3: 642 samples), Coulomb coefficient mu.

}  // namespace

// What the cube does: released face down, it pitches forward onto its downhill edge region (the
// friction torque μ N h exceeds what a linear pressure profile over the face can balance, N L/6)
// and rocks at about 17 Hz (period 0.059 s measured under BDF2 at Δt = 1e-3, pitch rates up to
// 0.36 rad/s), because at the default smoothing ε = 5 mm the
// contact is soft at the rest load (rotational stiffness ~1.6e2 N·m/rad); c_n = 1 s/m damps it
// only weakly. The bottom-face centre barely moves with the rocking, so distances are measured
// there. In the two stage-start-load modes the load lags the current one by a step; correlated
// with the rocking's normal damping it biases the mean friction by O(Δt): measured a = 0.6484
// (−1.3%) at Δt = 2e-3, 0.6536 (−0.54%) at 1e-3, 0.6565 (−0.09%) at 5e-4; without normal damping
// the three modes agree within 0.22% at 2e-3. The implicit-load mode: −0.02% at 2e-3. That the
// rocking persists at all is the lag's doing too (the 12 s test below: with the current load it
// decays, as in the converged reference).
TEST_CASE("incline, mu = 0.5: sliding acceleration g (sin30 - mu cos30) within 1%",
          "[core][physics][friction]") {
  const double expected = kG * (std::sin(kTheta) - 0.5 * std::cos(kTheta));
  for (int m = 0; m < 3; ++m) {
    DYNAMIC_SECTION(test::kModeNames[m]) {
      const InclineRun run = RunIncline(test::EvalParamsForMode(m), 0.5, 0.01, 1.0, 1.0, 1e-3);
      const Eigen::Vector3d c = QuadraticFit(run, 0.3, 1.0);
      const double a = 2 * c[2];
      INFO("measured a = " << a << " m/s^2, expected " << expected << ", max rocking "
                           << run.maxRock << " rad");
      CHECK(std::abs(a - expected) < 0.01 * expected);
    }
  }
}

TEST_CASE("incline, mu = 0.7: regularized friction creeps at the speed where "
          "mu cos30 rho'(v) = sin30",
          "[core][physics][friction]") {
  // ρ'(v) = 2u − u², u = v/V_f: u = 1 − √(1 − tan30/μ).
  const double mu = 0.7, vf = 0.01;
  const double u = 1 - std::sqrt(1 - std::tan(kTheta) / mu);
  const double expected = u * vf;
  for (int m = 0; m < 3; ++m) {
    DYNAMIC_SECTION(test::kModeNames[m]) {
      const InclineRun run = RunIncline(test::EvalParamsForMode(m), mu, vf, 1.0, 1.0, 2e-3);
      const Eigen::Vector3d c = QuadraticFit(run, 0.5, 1.0);
      const double v = c[1] + 2 * c[2] * 1.0;  // speed at t = 1 s
      INFO("creep speed " << v << " m/s, expected " << expected << "; acceleration " << 2 * c[2]);
      CHECK(std::abs(v - expected) < 0.03 * expected);
    }
  }
  SECTION("V_f = 1e-4 m/s: the cube moves less than 0.1 mm in 1 s (BackwardEuler)") {
    // Under BackwardEuler the release pitch is damped at once and the face creeps at the
    // regularized speed (5.8e-5 m/s). Under BDF2 (not asserted here; see the closing notes) the
    // release pitch lets the face slip about 0.5 mm within 0.05 s and the undamped rocking that
    // follows unloads the face periodically, so it creeps at about 1.2e-4 m/s.
    const InclineRun run = RunIncline(test::EvalParamsForMode(1), mu, 1e-4, 1.0, 1.0, 2e-3,
                                      IntegrationMethod::BackwardEuler);
    INFO("moved " << run.s.back() * 1e3 << " mm in 1 s");
    CHECK(std::abs(run.s.back()) < 1e-4);
    CHECK(run.s.back() > 0.5 * 1e-4 * u);  // it does creep, at the regularized speed's order
  }
}

// A cube that slides for 12 s (to 8 m/s) carries its load on its downhill half: the friction
// moment μ N h shifts the centre of pressure μh = 5 cm forward, so the pitch and yaw modes are
// damped only by the spread of the load about that point. Scaled by the current normal load the
// friction keeps them damped at any step. Scaled by a load that lags by a step (the stage-start
// load of the two other modes) it is a delayed feedback that undamps them: measured at Δt = 0.1,
// yaw rate 3e-5 → 0.013 → 7.3 rad/s at t = 2, 4, 6 s, then 30 rad/s under BackwardEuler (10 rad/s
// under BDF2); at Δt = 1e-3 (DIRK33, BDF2, SymplecticDIRK22) a rocking limit cycle with pitch
// rates of 0.23–0.36 rad/s. The converged reference (DIRK33 at Δt = 1e-4) decays in either mode
// (pitch rate 0.3 → 1e-3 rad/s in 12 s), so those motions are the lag's, not the model's. The
// two runs below with the reconstructed stage-start load instead: largest |ω| 33.7 rad/s and a
// 5.2 % high (BackwardEuler), 0.94 rad/s and a 8.0 % low (BDF2).
TEST_CASE("incline, mu = 0.5, current load: a cube sliding for 12 s neither rocks nor spins up",
          "[core][physics][friction]") {
  const double expected = kG * (std::sin(kTheta) - 0.5 * std::cos(kTheta));
  struct Case {
    IntegrationMethod method;
    double dt;
    const char* name;
  };
  for (const Case& c : {Case{IntegrationMethod::BackwardEuler, 0.1, "BackwardEuler, dt = 0.1"},
                        Case{IntegrationMethod::BDF2, 0.01, "BDF2, dt = 0.01"}}) {
    DYNAMIC_SECTION(c.name) {
      const InclineRun run =
          RunIncline(test::EvalParamsForMode(2), 0.5, 0.01, 1.0, 12.0, c.dt, c.method);
      const Eigen::Vector3d fit = QuadraticFit(run, 2.0, 12.0);
      const double a = 2 * fit[2];
      INFO("largest |w| after 2 s " << run.maxSpinLate << " rad/s; a = " << a << " m/s^2 (expected "
                                    << expected << ")");
      CHECK(run.maxSpinLate < 1e-3);  // measured 5.8e-7 (BackwardEuler), 2.1e-6 (BDF2)
      CHECK(std::abs(a - expected) < 1e-3 * expected);
    }
  }
}

// A solid ball (r = 0.1 m, 1 kg, I = 2/5 m r²) thrown along a plane at v0 = 2 m/s without spin,
// μ = 0.3: friction μ m g decelerates it and spins it up until v = ω r, at t* = 2 v0 / (7 μ g),
// and it rolls on at v = 5/7 v0. On the penalty model it then rolls with a little resistance: the
// samples of the penetrated cap above the lowest point slip at ω z (z their height above it), so
// friction dissipates about μ m g ω ⟨z⟩, a deceleration of (5/7) μ g ⟨z⟩ / r — measured 4.4e-3
// m/s² (⟨z⟩ ≈ 0.2 mm, a load-weighted height in the 2.4 mm deep cap), with the contact point
// slipping back at about 5 mm/s.
// Measured at Δt = 1e-3 (BackwardEuler, BDF2): rolling from t = 0.198, 0.189 s (t* = 0.194) at
// 1.4293, 1.4264 m/s (5/7 v0 = 1.4286), then decelerating at 4.3e-3, 4.7e-3 m/s².
TEST_CASE("a ball thrown without spin rolls at 5/7 of its speed after 2 v0 / (7 mu g)",
          "[core][physics][friction]") {
  const double v0 = 2.0, mu = 0.3, r = 0.1;
  const double tStar = 2 * v0 / (7 * mu * kG);
  for (IntegrationMethod method : {IntegrationMethod::BackwardEuler, IntegrationMethod::BDF2}) {
    DYNAMIC_SECTION(ToString(method)) {
      SceneSettings settings;
      settings.integrator = method;
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::StaticGround(1e9, mu), &e).IsValid());
      RigidActorDesc ball = test::Ball(r, mu);
      ball.position = Eigen::Vector3d(0, 0, r - 2e-4);
      ball.linearVelocity = Eigen::Vector3d(v0, 0, 0);
      const ActorHandle h = scene.AddRigidActor(ball, &e);
      REQUIRE(h.IsValid());
      const double dt = 1e-3;
      double tRoll = -1, vRoll = 0, vHalf = 0;
      for (int i = 1; i <= 2000; ++i) {
        StepReport rep;
        REQUIRE(scene.Step(dt, &rep, &e));
        REQUIRE(rep.status == StageStatus::Converged);
        const double v = scene.State(h).v.x();
        const double wr = scene.State(h).AngularVelocity().y() * r;
        if (tRoll < 0 && v - wr < 0.01) {  // slip below 1 cm/s: rolling
          tRoll = scene.Time();
          vRoll = v;
        }
        if (i == 500) vHalf = v;
      }
      const double vEnd = scene.State(h).v.x();
      const double deceleration = (vHalf - vEnd) / 1.5;
      INFO("rolls from t = " << tRoll << " s (expected " << tStar << ") at " << vRoll
                             << " m/s (expected " << 5.0 / 7.0 * v0 << "); rolling deceleration "
                             << deceleration << " m/s^2");
      CHECK(std::abs(tRoll - tStar) < 0.05 * tStar);
      CHECK(std::abs(vRoll - 5.0 / 7.0 * v0) < 0.01 * 5.0 / 7.0 * v0);
      CHECK(deceleration > 0.0);
      CHECK(deceleration < 0.01 * mu * kG);  // rolling resistance: far below sliding friction
    }
  }
}

// A ball (r = 0.1 m, 1 kg, solid) released on a 20° incline with μ = 0.5 (> 2/7 tan 20° = 0.10)
// rolls without slipping at a = 5/7 g sin θ. At Δt = 1e-3 the fit over 0.5–1.5 s (ω up to
// 36 rad/s) measured −0.50 % (BackwardEuler) and −0.56 % (BDF2), about half of it the rolling
// resistance of the test above. At large ω Δt the stage velocity (Y − Y⁰)/Δt_i of a material point
// on the spinning ball differs from its velocity by O(r ω³ Δt²) — at the contact point
// r ω³ Δt²/6 under BackwardEuler, r ω³ Δt²/3 under BDF2, 6.5 and 13 cm/s at ω = 34 rad/s and
// Δt = 1e-2 — which the friction law reads as slip: there the same fit reads −4.9 % and −13 %
// (−1.5 % under BDF2 at Δt = 3e-3; −1.6 % at 1e-2 over 0.1–0.6 s, ω ≤ 14 rad/s). Not asserted.
TEST_CASE("a ball rolls down a 20 degree incline at 5/7 g sin(theta)", "[core][physics][friction]") {
  const double theta = 20.0 * M_PI / 180.0, r = 0.1, mu = 0.5;
  const Eigen::Vector3d n(std::sin(theta), 0, std::cos(theta));
  const Eigen::Vector3d down(std::cos(theta), 0, -std::sin(theta));
  const double expected = 5.0 / 7.0 * kG * std::sin(theta);
  for (IntegrationMethod method : {IntegrationMethod::BackwardEuler, IntegrationMethod::BDF2}) {
    DYNAMIC_SECTION(ToString(method)) {
      SceneSettings settings;
      settings.integrator = method;
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::Ground(n, 1e9, mu, 0.0), &e).IsValid());
      RigidActorDesc ball = test::Ball(r, mu);
      ball.position = n * (r - 2e-3);
      const ActorHandle h = scene.AddRigidActor(ball, &e);
      REQUIRE(h.IsValid());
      const Eigen::Vector3d p0 = scene.State(h).p;
      InclineRun run;  // distance down the slope of the centre
      for (int i = 0; i < 1500; ++i) {
        StepReport rep;
        REQUIRE(scene.Step(1e-3, &rep, &e));
        REQUIRE(rep.status == StageStatus::Converged);
        run.t.push_back(scene.Time());
        run.s.push_back((scene.State(h).p - p0).dot(down));
      }
      const double a = 2 * QuadraticFit(run, 0.5, 1.5)[2];
      INFO("a = " << a << " m/s^2, expected " << expected << " (relative " << (a - expected) / expected
                  << ")");
      CHECK(std::abs(a - expected) < 0.01 * expected);
    }
  }
}

// A 0.2 m, 1 kg box thrown at 2 m/s along a plane (μ = 0.5) slides v0²/(2 μ g) = 0.4077 m. At
// Δt = 1e-2 (BDF2) with the current load it stops there however its contact starts: measured
// 0.4071 m from 0.1 mm pressed in, 0.4074 m from 0.5 mm above (1 s: stopped at 0.42 s, then
// rocked back to rest). With the stage-start load the
// first step's friction is scaled by the start's load — too large pressed in, zero above — and
// the box stops at 0.3874 m (−5.0 %) and 0.4315 m (+5.8 %) (0.4058 and 0.4074 m at Δt = 1e-3).
TEST_CASE("current load: a box thrown at 2 m/s slides v0^2 / (2 mu g) at dt = 1e-2 from any start",
          "[core][physics][friction]") {
  const double v0 = 2.0, mu = 0.5;
  const double expected = v0 * v0 / (2 * mu * kG);
  for (double gap : {-1e-4, 5e-4}) {
    DYNAMIC_SECTION("starting " << gap * 1e3 << " mm from the plane") {
      SceneSettings settings;
      settings.integrator = IntegrationMethod::BDF2;
      settings.eval.implicitNormalForceForDissipation = true;
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::StaticGround(1e9, mu), &e).IsValid());
      RigidActorDesc box = test::Cube(1e9, mu, 0.0);
      box.position = Eigen::Vector3d(0, 0, 0.1 + gap);
      box.linearVelocity = Eigen::Vector3d(v0, 0, 0);
      const ActorHandle h = scene.AddRigidActor(box, &e);
      REQUIRE(h.IsValid());
      for (int i = 0; i < 100; ++i) {  // it stops at 0.42 s and rocks back to rest
        StepReport rep;
        REQUIRE(scene.Step(1e-2, &rep, &e));
        REQUIRE(rep.status == StageStatus::Converged);
      }
      const double travelled = scene.State(h).p.x();
      INFO("stopped after " << travelled << " m (expected " << expected << "), speed "
                            << scene.State(h).v.transpose() << " m/s");
      CHECK(std::abs(travelled - expected) < 0.005 * expected);
      CHECK(scene.State(h).v.norm() < 1e-3);
    }
  }
}

// Viscous friction alone (μ = 0, c_t = 0.2 s/m on both actors): the traction c_t λ_n V_t sums to
// c_t (m g) v, so a box sliding on a level plane slows as v0 e^(−c_t g t). Measured decay rate
// over 0.2–1 s against c_t g = 1.962 /s, BDF2 at Δt = 1e-2: 1.9627 in the two stage-start-load
// modes, 1.9628 with the current load (+0.04 %); at Δt = 1e-3 the stage-start load's rocking
// moves it to +0.72 %.
TEST_CASE("viscous friction: a box slides to rest as v0 exp(-c_t g t)", "[core][physics][friction]") {
  const double ct = 0.2, expected = ct * kG;
  for (int m = 0; m < 3; ++m) {
    DYNAMIC_SECTION(test::kModeNames[m]) {
      SceneSettings settings;
      settings.integrator = IntegrationMethod::BDF2;
      settings.eval = test::EvalParamsForMode(m);
      Scene scene(settings);
      Error e;
      RigidActorDesc ground = test::StaticGround(1e9, 0.0);
      ground.contact.viscousFrictionCoefficient = ct;
      REQUIRE(scene.AddRigidActor(ground, &e).IsValid());
      RigidActorDesc box = test::Cube(1e9, 0.0, 0.0);
      box.contact.viscousFrictionCoefficient = ct;
      box.position = Eigen::Vector3d(0, 0, 0.1 + 5e-4);
      box.linearVelocity = Eigen::Vector3d(1.0, 0, 0);
      const ActorHandle h = scene.AddRigidActor(box, &e);
      REQUIRE(h.IsValid());
      double v02 = 0.0;
      for (int i = 1; i <= 100; ++i) {
        StepReport rep;
        REQUIRE(scene.Step(1e-2, &rep, &e));
        REQUIRE(rep.status == StageStatus::Converged);
        if (i == 20) v02 = scene.State(h).v.x();
      }
      const double rate = std::log(v02 / scene.State(h).v.x()) / 0.8;
      INFO("decay rate " << rate << " /s, expected " << expected);
      CHECK(std::abs(rate - expected) < 0.01 * expected);
    }
  }
}

// Thrown up the 30° incline at 2 m/s with μ = 0.3 (< tan 30°), the cube decelerates at
// g (sin θ + μ cos θ) = 7.454 m/s², stops at t = 0.268 s and slides back down at
// g (sin θ − μ cos θ) = 2.356 m/s²: friction reverses with the slip. Measured (quadratic fits on
// 0.05–0.22 s and 0.47–1.5 s): BDF2, Δt = 1e-3, reconstructed load +5.0e-4 and −1.0e-3;
// BackwardEuler, Δt = 1e-2, current load −8e-6 and +2e-6.
TEST_CASE("incline, mu = 0.3: thrown uphill, friction reverses when the cube turns back",
          "[core][physics][friction]") {
  const double mu = 0.3;
  const double aUp = kG * (std::sin(kTheta) + mu * std::cos(kTheta));
  const double aDown = kG * (std::sin(kTheta) - mu * std::cos(kTheta));
  const double tStop = 2.0 / aUp;
  struct Case {
    IntegrationMethod method;
    double dt;
    int mode;
    const char* name;
  };
  for (const Case& c : {Case{IntegrationMethod::BDF2, 1e-3, 1, "BDF2, dt = 1e-3, reconstructed load"},
                        Case{IntegrationMethod::BackwardEuler, 1e-2, 2,
                             "BackwardEuler, dt = 1e-2, current load"}}) {
    DYNAMIC_SECTION(c.name) {
      SceneSettings settings;
      settings.integrator = c.method;
      settings.eval = test::EvalParamsForMode(c.mode);
      Scene scene(settings);
      Error e;
      const Eigen::Vector3d n(std::sin(kTheta), 0, std::cos(kTheta));
      const Eigen::Vector3d up(-std::cos(kTheta), 0, std::sin(kTheta));
      REQUIRE(scene.AddRigidActor(test::Ground(n, 1e9, mu, 1.0), &e).IsValid());
      RigidActorDesc cube = test::CubeOnIncline(kTheta, 1e9, mu, 1.0);
      cube.linearVelocity = 2.0 * up;
      const ActorHandle h = scene.AddRigidActor(cube, &e);
      REQUIRE(h.IsValid());
      const Eigen::Vector3d p0 = scene.State(h).p;
      InclineRun climb, descent;  // distance up the slope
      const int steps = static_cast<int>(std::lround(1.5 / c.dt));
      for (int i = 0; i < steps; ++i) {
        StepReport rep;
        REQUIRE(scene.Step(c.dt, &rep, &e));
        REQUIRE(rep.status == StageStatus::Converged);
        const double t = scene.Time(), s = (scene.State(h).p - p0).dot(up);
        InclineRun& run = t < tStop ? climb : descent;
        run.t.push_back(t);
        run.s.push_back(s);
      }
      const double measuredUp = -2 * QuadraticFit(climb, 0.05, tStop - 0.05)[2];
      const double measuredDown = -2 * QuadraticFit(descent, tStop + 0.2, 1.5)[2];
      INFO("deceleration uphill " << measuredUp << " (expected " << aUp << "), acceleration down "
                                  << measuredDown << " (expected " << aDown << ")");
      CHECK(std::abs(measuredUp - aUp) < 0.005 * aUp);
      CHECK(std::abs(measuredDown - aDown) < 0.005 * aDown);
    }
  }
}

// A ball (r = 0.1 m, 1 kg) hits a plane obliquely without gravity, 2 m/s along and into it, with
// μ = 0.1: it slides throughout the impact (2 > 7/2 μ (1 + e) v_n = 1.4 m/s), so the friction
// impulse is μ times the normal one: Δv_t = μ (1 + e) v_n and ω = 5/2 μ (1 + e) v_n / r (rigid
// impact theory). Measured (SymplecticDIRK22, Δt = 1e-4, e = 1.0000, penetration up to 6 mm):
// with fade_friction off Δv_t is μ (1 + e) v_n to +1.4e-4 and ω is 1.03 % low (the lever arm is
// the distance to the penetrated cap, not r); with it on (the default), friction on a cap sample
// is attenuated by its alignment cos α, and Δv_t is 1.04 % low, ω 2.06 %.
TEST_CASE("oblique impact: the friction impulse is mu times the normal impulse",
          "[core][physics][friction]") {
  const double mu = 0.1, r = 0.1;
  for (bool fade : {false, true}) {
    DYNAMIC_SECTION("fade_friction " << fade) {
      SceneSettings settings;
      settings.integrator = IntegrationMethod::SymplecticDIRK22;
      settings.gravity.setZero();
      settings.eval.fadeFriction = fade;
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::StaticGround(1e9, mu), &e).IsValid());
      RigidActorDesc ball = test::Ball(r, mu);
      ball.position = Eigen::Vector3d(0, 0, r + 0.02);
      ball.linearVelocity = Eigen::Vector3d(2.0, 0, -2.0);
      const ActorHandle h = scene.AddRigidActor(ball, &e);
      REQUIRE(h.IsValid());
      for (int i = 0; i < 1000; ++i) {
        StepReport rep;
        REQUIRE(scene.Step(1e-4, &rep, &e));
        REQUIRE(rep.status == StageStatus::Converged);
      }
      const Eigen::Vector3d v = scene.State(h).v;
      const double w = scene.State(h).AngularVelocity().y();
      REQUIRE(v.z() > 1.9);  // it bounced (e near 1: no normal damping)
      const double normalImpulse = v.z() + 2.0;  // m (1 + e) v_n
      const double impulseRatio = (2.0 - v.x()) / (mu * normalImpulse);
      const double spinRatio = w / (2.5 * mu * normalImpulse / r);
      INFO("friction impulse / (mu normal impulse) = " << impulseRatio
                                                       << ", spin / rigid-impact spin = " << spinRatio);
      if (!fade) {
        CHECK(std::abs(impulseRatio - 1.0) < 1e-3);
        CHECK(std::abs(spinRatio - 1.0) < 0.02);
      } else {
        CHECK(impulseRatio < 1.0);
        CHECK(impulseRatio > 0.97);
        CHECK(std::abs(spinRatio - 1.0) < 0.03);
      }
    }
  }
}
