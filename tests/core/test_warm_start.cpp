// The warm start of stage solves (core/dynamics/warm_start.h): the prediction, the tangent step, the limited
// move, and on whole scenes the same solutions in fewer Newton iterations.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>

#include "core/dynamics/integrators.h"
#include "core/model/rigid_math.h"
#include "core/scene.h"
#include "core/dynamics/warm_start.h"
#include "core/model/rigid_kind.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

RigidBodyState StateWith(const Eigen::Vector3d& p, const Eigen::Matrix3d& R,
                         const Eigen::Vector3d& v, const Eigen::Vector3d& omega) {
  RigidBodyState s;
  s.p = p;
  s.R = R;
  s.v = v;
  s.Rdot = Skew(omega) * R;
  return s;
}

/// A problem on R^n with x ← x + d whose step limit halves every step longer than `limit`.
class Toy : public StageProblem {
 public:
  Toy(int n, double limit) : x(Eigen::VectorXd::Zero(n)), limit_(limit) {}
  int NumDofs() const override { return static_cast<int>(x.size()); }
  double Value(const Eigen::VectorXd& d) override { return 0.5 * (x + d).squaredNorm(); }
  double Evaluate(Eigen::VectorXd* g, Eigen::SparseMatrix<double>*, PsdProjection) override {
    ++evaluations;
    *g = x;
    return Value(Eigen::VectorXd::Zero(x.size()));
  }
  void Commit(const Eigen::VectorXd& d) override { x += d; }
  bool LimitStep(Eigen::VectorXd* d) override {
    bool changed = false;
    for (Eigen::Index i = 0; i < d->size(); ++i)
      if (std::abs((*d)[i]) > limit_) {
        (*d)[i] *= 0.5;
        changed = true;
      }
    return changed;
  }
  Eigen::VectorXd x;
  int evaluations = 0;

 private:
  double limit_;
};

struct Run {
  std::vector<RigidBodyState> end;
  long newton = 0;
  int notConverged = 0;
};

Run RunScene(Scene& scene, double dt, int steps) {
  Run run;
  Error e;
  for (int i = 0; i < steps; ++i) {
    StepReport r;
    REQUIRE(scene.Step(dt, &r, &e));
    run.newton += r.newtonIterations;
    if (r.status != StageStatus::Converged) ++run.notConverged;
  }
  for (int a = 0; a < scene.NumActors(); ++a) run.end.push_back(scene.State(ActorHandle{a}));
  return run;
}

}  // namespace

TEST_CASE("PredictRigidPose continues the last step's acceleration exactly", "[warm_start]") {
  const Eigen::Matrix3d R = ExpSo3(Eigen::Vector3d(0.3, -0.2, 0.5));
  const Eigen::Vector3d a(0.5, -1.0, -9.81), alpha(0.2, 0.1, -0.4);
  const Eigen::Vector3d v(1.0, 2.0, -0.5), omega(0.7, -0.1, 0.3);
  const double hPrev = 0.02, tau = 0.03;
  const RigidBodyState current = StateWith({1, 2, 3}, R, v, omega);
  const RigidBodyState previous = StateWith({0, 0, 0}, R, v - hPrev * a, omega - hPrev * alpha);
  const RigidPose pred = PredictRigidPose(current, &previous, hPrev, tau, nullptr, 0.0);
  const Eigen::Vector3d pExact = current.p + tau * v + 0.5 * tau * tau * a;
  CHECK((pred.p - pExact).norm() < 1e-14);
  CHECK((pred.R - ExpSo3(tau * omega + 0.5 * tau * tau * alpha) * R).norm() < 1e-14);
  // Without history the prediction is the constant velocity one.
  const RigidPose flat = PredictRigidPose(current, nullptr, 0.0, tau, nullptr, 0.0);
  CHECK((flat.p - (current.p + tau * v)).norm() < 1e-14);
  CHECK((flat.R - ExpSo3(tau * omega) * R).norm() < 1e-14);
  // A static rigid actor's predicted stage keeps its pose.
  RigidBodyModel ground;
  ground.dynamic = false;
  const RigidKind kind(ground, current);
  Eigen::VectorXd q;
  kind.PredictStage(RigidKind::Pack(current), nullptr, 0.0, tau, RigidKind::Pack(current).x, tau,
                    &q);
  CHECK(q == RigidKind::Pack(current).x);
}

TEST_CASE("RigidKind::TangentBetween moves one pose onto another", "[warm_start]") {
  RigidBodyModel body;
  const RigidKind kind(body, RigidBodyState());
  for (int i = 0; i < 3; ++i) {
    RigidBodyState from, to;
    from.p = Eigen::Vector3d(i, -i, 0.5 * i);
    from.R = ExpSo3(Eigen::Vector3d(0.1 * i, 0.4, -0.3));
    to.p = from.p + Eigen::Vector3d(0.01, 0.02 * i, -0.03);
    to.R = ExpSo3(Eigen::Vector3d(-0.2, 0.1 * i, 0.6)) * from.R;
    Eigen::VectorXd d, moved;
    kind.TangentBetween(RigidKind::Pack(from).x, RigidKind::Pack(to).x, &d);
    REQUIRE(d.size() == 6);
    CHECK((from.p + d.head<3>() - to.p).norm() < 1e-14);
    CHECK((ExpSo3(d.tail<3>()) * from.R - to.R).norm() < 1e-12);
    kind.Retract(RigidKind::Pack(from).x, d, &moved);  // and Retract undoes it
    CHECK((moved - RigidKind::Pack(to).x).norm() < 1e-12);
  }
}

TEST_CASE("WarmStart takes the predicted step shortened by the step limit", "[warm_start]") {
  Toy toy(2, 1.0);
  CHECK(WarmStart(toy, Eigen::Vector2d(0.5, 3.0)));
  CHECK((toy.x - Eigen::Vector2d(0.5, 1.5)).norm() < 1e-15);  // the second block limited
  CHECK(toy.evaluations == 0);
  // A step at or below negligibleStep (StepNorm: max-norm here) is not taken.
  Toy rest(2, 1.0);
  CHECK_FALSE(WarmStart(rest, Eigen::Vector2d(1e-12, -1e-12), 1e-12));
  CHECK(rest.x.isZero());
  CHECK_FALSE(WarmStart(rest, Eigen::Vector2d(NAN, 0.0)));
  CHECK(rest.x.isZero());
}

TEST_CASE("RigidForceChange tells steady motion from a change of the forces", "[warm_start]") {
  RigidBodyModel body;
  body.mass = 2.0;
  body.secondMoment = Eigen::Vector3d(0.03, 0.02, 0.01).asDiagonal();  // asymmetric [kg·m²]
  RigidBodyModel ground;
  ground.dynamic = false;
  const std::vector<RigidBodyModel> models = {body, body, body, body, body, ground};
  // Each body steady when its force change is within SteadyBound (RigidKind::ForceChange, as
  // the stage driver asks it).
  auto steadyOf = [&](const std::vector<RigidBodyState>& current,
                      const std::vector<RigidBodyState>& previous, double hPrevious,
                      const std::vector<RigidBodyState>& before, double hBefore,
                      const Eigen::Vector3d& g) {
    std::vector<char> out;
    for (size_t i = 0; i < models.size(); ++i) {
      const RigidKind kind(models[i], current[i]);
      out.push_back(kind.ForceChange(RigidKind::Pack(current[i]), RigidKind::Pack(previous[i]),
                                     hPrevious, RigidKind::Pack(before[i]), hBefore) <=
                    SteadyBound(g));
    }
    return out;
  };
  const Eigen::Vector3d g(0, 0, -9.81);
  const double h0 = 0.02, h1 = 0.01;  // unequal steps
  const double rho = RmsRadius(body);
  const double bound = kSteadyAcceleration * g.norm();
  // Three states h0 and h1 apart under the accelerations a1, a2 and the torques t1, t2 [N·m].
  const Eigen::Matrix3d R0 = ExpSo3(Eigen::Vector3d(0.4, -0.3, 0.2));
  const Eigen::Vector3d v0(1.0, -2.0, 3.0), w0(2.0, 5.0, -1.0);
  auto motion = [&](const Eigen::Vector3d& a1, const Eigen::Vector3d& a2, const Eigen::Vector3d& t1,
                    const Eigen::Vector3d& t2) {
    const Eigen::Vector3d L0 = WorldInertia(R0, body.secondMoment) * w0;
    const Eigen::Matrix3d R1 = ExpSo3(h0 * w0) * R0;
    const Eigen::Vector3d L1 = L0 + h0 * t1;
    const Eigen::Vector3d w1 = WorldInertia(R1, body.secondMoment).inverse() * L1;
    const Eigen::Matrix3d R2 = ExpSo3(h1 * w1) * R1;
    const Eigen::Vector3d w2 = WorldInertia(R2, body.secondMoment).inverse() * (L1 + h1 * t2);
    return std::vector<RigidBodyState>{StateWith({0, 0, 1}, R0, v0, w0),
                                       StateWith({0, 0, 1}, R1, v0 + h0 * a1, w1),
                                       StateWith({0, 0, 1}, R2, v0 + h0 * a1 + h1 * a2, w2)};
  };
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero(), up(0, 0, 1);
  const Eigen::Vector3d slide = g + Eigen::Vector3d(3.0, 0.0, 8.0);  // a contact's steady force
  const Eigen::Vector3d torque = 2.0 * bound * body.mass * rho * Eigen::Vector3d(1, 0, 0);
  const std::vector<std::vector<RigidBodyState>> runs = {
      motion(g, g, zero, zero),                     // free flight, torque-free tumbling
      motion(slide, slide, zero, zero),             // steady sliding
      motion(g, g + 1.5 * bound * up, zero, zero),  // an impact: the force changed past the bound
      motion(g, g + 0.5 * bound * up, zero, zero),  // within it
      motion(g, g, zero, torque),                   // a torque appeared: 2× the bound at ρ
  };
  // (A test on ω instead of L would call the tumbling body unsteady: ω changes 10× the bound.)
  REQUIRE((runs[0][2].AngularVelocity() - runs[0][1].AngularVelocity()).norm() / h1 * rho >
          10.0 * bound);
  std::vector<RigidBodyState> before, previous, current;
  for (const auto& r : runs) {
    before.push_back(r[0]);
    previous.push_back(r[1]);
    current.push_back(r[2]);
  }
  const RigidBodyState rest = StateWith({0, 0, 0}, R0, zero, zero);
  before.push_back(rest);
  previous.push_back(rest);
  current.push_back(rest);
  const std::vector<char> steady = steadyOf(current, previous, h1, before, h0, g);
  REQUIRE(steady.size() == 6);
  CHECK(steady[0]);
  CHECK(steady[1]);
  CHECK_FALSE(steady[2]);
  CHECK(steady[3]);
  CHECK_FALSE(steady[4]);
  CHECK(steady[5]);  // static
}

namespace {

/// Bodies of 6 dofs on R^(6k) with x ← x + d: the step limit halves every entry longer than
/// `limit`; the trust region scales a body's block to a norm of at most `trust`.
class BodiesToy : public Toy {
 public:
  BodiesToy(int bodies, double limit, double trust) : Toy(6 * bodies, limit), trust_(trust) {}
  bool TrustStep(Eigen::VectorXd* d) override {
    bool changed = false;
    for (Eigen::Index o = 0; o < d->size(); o += 6) {
      const double move = d->segment<6>(o).norm();
      if (move <= trust_) continue;
      d->segment<6>(o) *= trust_ / move;
      changed = true;
    }
    return changed;
  }

 private:
  double trust_;
};

}  // namespace

TEST_CASE("WarmStart bounds the predictions that extrapolate a change of the forces",
          "[warm_start]") {
  BodiesToy toy(4, 1.0, 0.5);
  // Units of six dofs (unit 1 static: no stage dofs).
  const std::vector<std::vector<int>> units = {
      {0, 1, 2, 3, 4, 5}, {-1, -1, -1}, {6, 7, 8, 9, 10, 11}, {12, 13, 14, 15, 16, 17},
      {18, 19, 20, 21, 22, 23}};
  std::vector<char> steady = {1, 0, 0, 1, 1};  // a static unit's flag changes nothing
  Eigen::VectorXd d = Eigen::VectorXd::Zero(24), scratch;
  d.segment<6>(0).setConstant(0.4);   // steady, within the limit: taken whole (norm 0.98 > 0.5)
  d.segment<6>(6).setConstant(0.4);   // its forces changed (an impact): bounded to norm 0.5
  d[11] = 4.0;                         // ... before the step limit (4 → 2 · 0.5/|d_1|, < 1)
  d.segment<6>(12).setZero();
  d[12] = 3.0;                         // steady: only the step limit applies (3 → 1.5)
  d.segment<6>(18).setConstant(0.1);  // steady, small
  Eigen::VectorXd expected = d;
  expected.segment<6>(6) *= 0.5 / d.segment<6>(6).norm();
  expected[12] = 1.5;
  REQUIRE(WarmStart(toy, &d, &scratch, 0.0, units, steady));
  CHECK((toy.x - expected).norm() < 1e-15);
  CHECK((d - expected).norm() < 1e-15);
  CHECK(toy.evaluations == 0);
  // All steady and unlimited: the prediction unchanged.
  BodiesToy flight(4, 10.0, 0.5);
  std::vector<char> allSteady(5, 1);
  Eigen::VectorXd e = Eigen::VectorXd::Constant(24, 0.4);
  REQUIRE(WarmStart(flight, &e, &scratch, 0.0, units, allSteady));
  CHECK((flight.x - Eigen::VectorXd::Constant(24, 0.4)).norm() == 0.0);
}

TEST_CASE("Warm-started stages reach the cold start's solutions in fewer Newton iterations",
          "[warm_start]") {
  // A cube sliding down a 30° incline (μ = 0.5, BDF2, Δt = 0.05 s, 1 s): the prediction
  // continues a constant acceleration; the cold start is a whole step's motion away.
  auto incline = [](bool warm) {
    SceneSettings settings;
    settings.warmStart = warm;
    Scene scene(settings);
    Error e;
    const double theta = M_PI / 6;
    const Eigen::Vector3d n(std::sin(theta), 0, std::cos(theta));
    REQUIRE(scene.AddRigidActor(test::Ground(n, 1e9, 0.5, 1.0), &e).IsValid());
    REQUIRE(scene.AddRigidActor(test::CubeOnIncline(theta, 1e9, 0.5, 1.0), &e).IsValid());
    return RunScene(scene, 0.05, 20);
  };
  // A resting heap of 50 spheres with small sliding velocities (explicit normals, DIRK22).
  auto heap = [](bool warm) {
    SceneSettings settings;
    settings.warmStart = warm;
    settings.integrator = IntegrationMethod::DIRK22;
    settings.eval.explicitNormals = true;
    Scene scene(settings);
    Error e;
    REQUIRE(scene.AddRigidActor(test::StaticGround(), &e).IsValid());
    for (int k = 0; k < 50; ++k) REQUIRE(scene.AddRigidActor(test::HeapSphere(k), &e).IsValid());
    return RunScene(scene, 1e-2, 10);
  };
  struct Case {
    const char* name;
    Run cold, warm;
    double maxRatio;  // warm / cold Newton iterations at most
  };
  Case cases[] = {{"incline", incline(false), incline(true), 0.5},
                  {"heap", heap(false), heap(true), 1.0}};
  for (const Case& c : cases) {
    INFO(c.name << ": cold " << c.cold.newton << ", warm " << c.warm.newton << " Newton iterations");
    CHECK(c.cold.notConverged == 0);
    CHECK(c.warm.notConverged == 0);
    CHECK(double(c.warm.newton) <= c.maxRatio * double(c.cold.newton));
    // Both runs stop within the same convergence tests (step below 1e-9 m/s, ...): the states
    // agree far below the motion (the cube slides 0.3 m).
    double dp = 0.0, dR = 0.0, dv = 0.0;
    for (size_t a = 0; a < c.cold.end.size(); ++a) {
      dp = std::max(dp, (c.cold.end[a].p - c.warm.end[a].p).norm());
      dR = std::max(dR, (c.cold.end[a].R - c.warm.end[a].R).norm());
      dv = std::max(dv, (c.cold.end[a].v - c.warm.end[a].v).norm());
    }
    INFO("max |dp| " << dp << " m, |dR| " << dR << ", |dv| " << dv << " m/s");
    CHECK(dp < 1e-8);
    CHECK(dR < 1e-7);
    CHECK(dv < 1e-6);
  }
}

TEST_CASE("PredictRigidPose through the stage's slope gives the stage's own solution under "
          "constant acceleration",
          "[warm_start]") {
  // Backward Euler from rest (v_{n-1} = v_n − h a): the stage solves p = p_n + h v_{n+1} with
  // v_{n+1} = v_n + h a; the continuous-time extrapolation p_n + h v_n + ½ h² a is ½ h² a short
  // of it.
  const Eigen::Matrix3d R = ExpSo3(Eigen::Vector3d(0.3, -0.2, 0.5));
  const Eigen::Vector3d a(0.5, -1.0, -9.81), v(1.0, 2.0, -0.5), omega(0.7, -0.1, 0.3);
  const double h = 0.02;
  const RigidBodyState current = StateWith({1, 2, 3}, R, v, omega);
  const RigidBodyState previous = StateWith({0, 0, 0}, R, v - h * a, omega);
  const Eigen::Vector3d stageSolution = current.p + h * (v + h * a);
  const RigidPose stage = PredictRigidPose(current, &previous, h, h, &current.p, h);
  CHECK((stage.p - stageSolution).norm() < 1e-14);
  const RigidPose plain = PredictRigidPose(current, &previous, h, h, nullptr, 0.0);
  CHECK((plain.p - stageSolution).norm() == Approx(0.5 * h * h * a.norm()).epsilon(1e-9));
  CHECK((stage.R - plain.R).norm() == 0.0);  // the rotation is the same
  // A DIRK stage with start p⁰ (the step start plus earlier slopes), step Δt_i at time τ.
  const Eigen::Vector3d start = current.p + Eigen::Vector3d(0.01, -0.02, 0.03);
  const double dtStage = 0.29 * h, tau = 0.71 * h;
  const RigidPose dirk = PredictRigidPose(current, &previous, h, tau, &start, dtStage);
  CHECK((dirk.p - (start + dtStage * (v + tau * a))).norm() < 1e-14);
}

TEST_CASE("In free flight every warm-started stage takes one Newton iteration", "[warm_start]") {
  // A falling box far from anything: the predicted position is the stage's solution
  // (PredictRigidPose), so each stage's first Newton direction already passes the convergence
  // tests. Before the stage-consistent prediction the DIRK methods took two per stage.
  for (IntegrationMethod method :
       {IntegrationMethod::BackwardEuler, IntegrationMethod::BDF2, IntegrationMethod::DIRK22,
        IntegrationMethod::DIRK33, IntegrationMethod::SymplecticDIRK12,
        IntegrationMethod::SymplecticDIRK22}) {
    DYNAMIC_SECTION(ToString(method)) {
      SceneSettings settings;
      settings.integrator = method;
      settings.closedFormFreeStages = false;  // Newton on every stage: the warm start under test
      Scene scene(settings);
      Error e;
      RigidActorDesc box = test::Cube(1e9, 0.5, 1.0);
      box.position = Eigen::Vector3d(0, 0, 100);
      box.linearVelocity = Eigen::Vector3d(1.0, -0.5, 2.0);
      REQUIRE(scene.AddRigidActor(box, &e).IsValid());
      const int stages = IsMultistep(method) ? 1 : TableauOf(method).stages;
      Run warmup = RunScene(scene, 1e-2, 3);  // history for the acceleration
      CHECK(warmup.notConverged == 0);
      const Run run = RunScene(scene, 1e-2, 20);
      INFO(run.newton << " Newton iterations in 20 steps of " << stages << " stage(s)");
      CHECK(run.notConverged == 0);
      CHECK(run.newton == 20 * stages);
    }
  }
}
