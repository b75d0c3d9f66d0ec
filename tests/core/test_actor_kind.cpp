// The generic actor layer (core/model/actor_kind.h) carries a kind written against the interface
// alone: a point mass defined here, in the test, with one colliding sample (the particle, weight
// w [m²]) and a sphere field of radius r [m] about it as its collider. No file of core/ knows it.
//
// Expectations, independent of the simulator's assembly:
//   rest on a plane:       w λ_n(φ*) = m g, λ_n the spec's normal load (energies/normal_penalty.h),
//                          so the particle rests at z = φ*;
//   two stacked particles: the lower one at z₁ with w λ_n(z₁) = (m₁ + m₂) g, the upper one at
//                          z₂ = z₁ + r + φ₂: both ordered pairs act (the upper's sample in the
//                          lower's field, and the lower's sample in the upper's field, at the same
//                          φ₂ = |x₂ − x₁| − r), so 2 w λ_n(φ₂) = m₂ g;
//   sliding down a rigid box tilted by θ with friction μ (|v| ≫ V_f): a = g (sin θ − μ cos θ).
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>

#include "core/scene.h"
#include "core/sensitivity/adjoint.h"
#include "core/sensitivity/sensitivity.h"
#include "scene_builders.h"
#include "sensitivity_scenes.h"

using namespace superdex;

namespace {

class PointMass : public ActorKind {
 public:
  PointMass(double mass, double area, double radius, const Eigen::Vector3d& x,
            const Eigen::Vector3d& v)
      : mass_(mass), area_(area), x_(x), v_(v) {
    field_.type = ColliderType::Sphere;
    field_.sphere.radius = radius;
    field_.boundingRadius = radius;
    name = "particle";
  }
  std::string KindName() const override { return "point mass"; }
  std::unique_ptr<ActorKind> Clone() const override { return std::make_unique<PointMass>(*this); }
  int NumDofs() const override { return 3; }
  KindState InitialState() const override { return {x_, v_}; }
  std::string Validate() const override {
    return mass_ > 0 ? std::string() : "point mass: mass must be > 0";
  }
  // Φ = m/(2Δt²)|q − q̂|² − m g·q [J].
  double StageEnergy(const KindStageData& s, const Eigen::VectorXd& q, int order, PsdProjection,
                     Eigen::VectorXd* g, std::vector<Eigen::Triplet<double>>* H) const override {
    const double w = mass_ / (s.dt * s.dt);
    const Eigen::Vector3d e = q - s.qHat;
    if (order >= 1) *g += w * e - mass_ * s.gravity;
    if (order >= 2)
      for (int i = 0; i < 3; ++i) H->emplace_back(i, i, w);
    return 0.5 * w * e.squaredNorm() - mass_ * s.gravity.dot(q);
  }
  double KineticEnergy(const KindState& s) const override {
    return 0.5 * mass_ * s.v.squaredNorm();
  }
  double GravityEnergy(const KindState& s, const Eigen::Vector3d& g) const override {
    return -mass_ * g.dot(s.x);
  }
  Eigen::Vector3d LinearMomentum(const KindState& s) const override { return mass_ * s.v; }
  Eigen::Vector3d AngularMomentum(const KindState& s) const override {
    return mass_ * Eigen::Vector3d(s.x).cross(Eigen::Vector3d(s.v));
  }
  Eigen::Vector3d CenterOfMass(const KindState& s) const override { return s.x; }
  Eigen::Vector3d CenterOfMassVelocity(const KindState& s) const override { return s.v; }
  Aabb Bounds(const Eigen::VectorXd& q) const override {
    Aabb b;
    b.Extend(q - Eigen::Vector3d::Constant(field_.sphere.radius));
    b.Extend(q + Eigen::Vector3d::Constant(field_.sphere.radius));
    return b;
  }
  int NumSamples() const override { return 1; }
  KindSample Sample(int, const Eigen::VectorXd& q) const override {
    KindSample s;
    s.y = q;
    s.weight = area_;
    s.map = SamplePointMap::Point();
    s.dof[0] = 0;
    return s;
  }
  const RigidCollider* Collider() const override { return &field_; }
  KindFrame ColliderFrame(const Eigen::VectorXd& q) const override {
    KindFrame f;
    f.pose.p = q;
    f.blocks = 1;
    f.dof[0] = 0;
    f.F.setZero(6, 3);
    f.F.topLeftCorner<3, 3>().setIdentity();
    return f;
  }

 private:
  double mass_, area_;
  Eigen::Vector3d x_, v_;
  RigidCollider field_;
};

constexpr double kG = 9.81;
constexpr double kRestTolerance = 1e-7;  // [m], see the first test

// The penetration φ < 0 at which w λ_n(φ) = load [N], by bisection on the monotone λ_n.
double BalanceDepth(double load, double w, const PenaltyParams& p) {
  double lo = -p.eps, hi = p.delta;  // λ_n(hi) = 0 < load; λ_n grows as φ falls
  while (w * NormalPenaltyDensity(lo, p).lambdaN < load) lo *= 2.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (w * NormalPenaltyDensity(mid, p).lambdaN < load ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// The pair's penalty parameters as the spec combines them for a kind on a static collider (k,
// from the colliding actor; ε, δ the collider's; δ padded: the particle's collider is a sphere,
// not None or PointCloud, so no padding).
PenaltyParams PairPenalty(const ContactParams& a, const ContactParams& b) {
  PenaltyParams p;
  p.k = a.penaltyCoefficient;
  p.eps = b.penaltySmoothingHalfDistance;
  p.delta = b.penaltyThresholdDefault;
  return p;
}

SceneSettings Settings(int mode) {
  SceneSettings s;
  s.gravity = Eigen::Vector3d(0, 0, -kG);
  s.integrator = IntegrationMethod::BackwardEuler;
  s.eval = test::EvalParamsForMode(mode);
  return s;
}

// A 0.2 kg point mass (w = 1e-4 m²) on a static box tilted by θ = 20° about x, released at the
// penalty balance with 0.5 m/s downhill; friction μ on both actors.
constexpr double kSlope = 20.0 * M_PI / 180.0;
const Eigen::Matrix3d kSlopeR =
    Eigen::AngleAxisd(kSlope, Eigen::Vector3d::UnitX()).toRotationMatrix();
const Eigen::Vector3d kSlopeNormal = kSlopeR.col(2), kDownhill = -kSlopeR.col(1);

Scene ParticleOnSlope(const SceneSettings& settings, double mu) {
  const double m = 0.2, w = 1e-4;
  Scene scene(settings);
  Error error;
  RigidActorDesc box;
  box.name = "slope";
  box.dynamic = false;
  box.shape.kind = RigidShapeKind::Box;
  box.shape.halfExtents = Eigen::Vector3d(2.0, 2.0, 0.1);
  box.orientation = Eigen::Quaterniond(kSlopeR);
  box.position = -0.1 * kSlopeNormal;  // top face through the origin
  box.contact.coulombFrictionCoefficient = mu;
  REQUIRE(scene.AddRigidActor(box, &error).IsValid());
  const PenaltyParams pp = PairPenalty(ContactParams(), ContactParams());
  const double phi = BalanceDepth(m * kG * std::cos(kSlope), w, pp);
  auto particle =
      std::make_unique<PointMass>(m, w, 0.01, phi * kSlopeNormal, 0.5 * kDownhill);
  particle->contact.coulombFrictionCoefficient = mu;
  REQUIRE(scene.AddActor(std::move(particle), &error).IsValid());
  return scene;
}

}  // namespace

TEST_CASE("a point-mass kind written in a test rests on a plane at the penalty balance",
          "[core][kind][physics]") {
  const double m = 0.2, w = 1e-4;
  Scene scene(Settings(1));
  Error error;
  const ActorHandle ground = scene.AddRigidActor(test::StaticGround(1e9, 0.0), &error);
  REQUIRE(ground.IsValid());
  auto particle = std::make_unique<PointMass>(m, w, 0.01, Eigen::Vector3d(0.1, -0.2, 0.02),
                                              Eigen::Vector3d::Zero());
  particle->contact.penaltyCoefficient = 1e9;
  const ContactParams pc = particle->contact;
  const ActorHandle p = scene.AddActor(std::move(particle), &error);
  REQUIRE(p.IsValid());
  for (int i = 0; i < 1500; ++i) {
    StepReport rep;
    REQUIRE(scene.Step(1e-3, &rep, &error));
    REQUIRE(rep.status == StageStatus::Converged);
  }
  const double zStar = BalanceDepth(m * kG, w, PairPenalty(pc, scene.GetContactParams(ground)));
  const KindState& s = scene.KindStateOf(p);
  INFO("rest height " << s.x.z() << " m, balance " << zStar << " m");
  CHECK(zStar < 0.0);
  // The stage tolerance (Newton decrement <= 1e-12 J at a stiffness m/Δt² + k w ≈ 3e5 N/m) leaves
  // ~3e-9 m per step: 1e-7 m (7e-5 of the depth) and 1e-5 m/s bound what it may accumulate.
  CHECK(std::abs(s.x.z() - zStar) <= kRestTolerance);
  CHECK(s.x.head<2>().isApprox(Eigen::Vector2d(0.1, -0.2), 1e-12));
  CHECK(s.v.norm() < 1e-5);
  CHECK(scene.ContactState().activeSamples == 1);
  // The reported energies and momentum come from the kind.
  CHECK(scene.Energies().gravity == Approx(m * kG * s.x.z()).epsilon(1e-12));
  CHECK(scene.TotalLinearMomentum().norm() < m * 1e-5);
}

TEST_CASE("two point masses stack: the collider role of a kind (its sphere field) carries one",
          "[core][kind][physics]") {
  const double m1 = 0.3, m2 = 0.1, w = 1e-4, r = 0.01;
  Scene scene(Settings(0));
  Error error;
  const ActorHandle ground = scene.AddRigidActor(test::StaticGround(1e9, 0.0), &error);
  auto lower = std::make_unique<PointMass>(m1, w, r, Eigen::Vector3d(0, 0, 0.001),
                                           Eigen::Vector3d::Zero());
  auto upper = std::make_unique<PointMass>(m2, w, r, Eigen::Vector3d(0, 0, 0.0125),
                                           Eigen::Vector3d::Zero());
  lower->contact.penaltyCoefficient = upper->contact.penaltyCoefficient = 1e9;
  upper->name = "upper particle";  // names are unique
  const ContactParams pc = lower->contact;
  const ActorHandle a = scene.AddActor(std::move(lower), &error);
  const ActorHandle b = scene.AddActor(std::move(upper), &error);
  REQUIRE((a.IsValid() && b.IsValid()));
  for (int i = 0; i < 2000; ++i) {
    StepReport rep;
    REQUIRE(scene.Step(1e-3, &rep, &error));
    REQUIRE(rep.status == StageStatus::Converged);
  }
  const double z1 = BalanceDepth((m1 + m2) * kG, w, PairPenalty(pc, scene.GetContactParams(ground)));
  // Both dynamic: k = √(k_A k_B) = k; ε, δ the collider's (equal here); two ordered pairs.
  const double phi2 = BalanceDepth(0.5 * m2 * kG, w, PairPenalty(pc, pc));
  const double zA = scene.KindStateOf(a).x.z(), zB = scene.KindStateOf(b).x.z();
  INFO("lower " << zA << " (expected " << z1 << "), upper " << zB << " (expected "
                << z1 + r + phi2 << ")");
  CHECK(std::abs(zA - z1) <= kRestTolerance);
  CHECK(std::abs(zB - (z1 + r + phi2)) <= kRestTolerance);
  // The lower particle's sample meets the plane, the upper one's the lower's field.
  int onPlane = 0, onParticle = 0;
  for (const ContactSampleRecord& rec : scene.ContactSamples()) {
    onPlane += rec.colliding == a.index && rec.collider == ground.index;
    onParticle += rec.colliding == b.index && rec.collider == a.index;
  }
  CHECK(onPlane == 1);
  CHECK(onParticle == 1);
  CHECK(scene.ContactState().activeSamples == 3);  // the plane's, and both ordered pairs'
}

TEST_CASE("a point mass slides down a tilted rigid box at g (sin θ − μ cos θ)",
          "[core][kind][friction][physics]") {
  const double mu = 0.2;
  for (int mode : {0, 1, 2}) {
    Scene scene = ParticleOnSlope(Settings(mode), mu);
    const ActorHandle p = scene.FindActor("particle");
    Error error;
    const double dt = 1e-3;
    double v1 = 0.0;
    for (int i = 1; i <= 400; ++i) {
      StepReport rep;
      REQUIRE(scene.Step(dt, &rep, &error));
      REQUIRE(rep.status == StageStatus::Converged);
      if (i == 100) v1 = scene.KindStateOf(p).v.dot(kDownhill);
    }
    const double v2 = scene.KindStateOf(p).v.dot(kDownhill);
    const double a = (v2 - v1) / (300 * dt);
    const double expected = kG * (std::sin(kSlope) - mu * std::cos(kSlope));
    INFO(test::kModeNames[mode] << ": a = " << a << " m/s², expected " << expected);
    // Friction at |v_t|/V_f >= 50 is μ λ_n to the falloff's 1e-3; the normal load balances gravity.
    CHECK(std::abs(a - expected) <= 2e-3 * expected);
    CHECK(std::abs(scene.KindStateOf(p).v.dot(kSlopeNormal)) < 1e-6);
  }
}

TEST_CASE("an actor kind is validated when added", "[core][kind][validation]") {
  Scene scene;
  Error error;
  auto bad = std::make_unique<PointMass>(-1.0, 1e-4, 0.01, Eigen::Vector3d::Zero(),
                                         Eigen::Vector3d::Zero());
  CHECK_FALSE(scene.AddActor(std::move(bad), &error).IsValid());
  CHECK(error.message.find("mass must be > 0") != std::string::npos);
  auto badContact = std::make_unique<PointMass>(1.0, 1e-4, 0.01, Eigen::Vector3d::Zero(),
                                                Eigen::Vector3d::Zero());
  badContact->contact.penaltyCoefficient = -1.0;
  CHECK_FALSE(scene.AddActor(std::move(badContact), &error).IsValid());
  CHECK(error.message.find("contact.penalty_coefficient") != std::string::npos);
  // A collider field must say how far its shape reaches (the assembler's cheap rejection).
  auto noReach = std::make_unique<PointMass>(1.0, 1e-4, 0.0, Eigen::Vector3d::Zero(),
                                             Eigen::Vector3d::Zero());
  CHECK_FALSE(scene.AddActor(std::move(noReach), &error).IsValid());
  CHECK(error.message.find("boundingRadius must be > 0") != std::string::npos);
}

namespace {

// A point mass whose collider frame's Jacobian F has `columns` columns, and rotates with its dofs
// when `rotates` (neither is allowed: F is 6 × 3·blocks, its rotation rows zero).
class BadFramePointMass : public PointMass {
 public:
  BadFramePointMass(int columns, bool rotates)
      : PointMass(1.0, 1e-4, 0.01, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
        columns_(columns),
        rotates_(rotates) {}
  std::unique_ptr<ActorKind> Clone() const override {
    return std::make_unique<BadFramePointMass>(*this);
  }
  KindFrame ColliderFrame(const Eigen::VectorXd& q) const override {
    KindFrame f = PointMass::ColliderFrame(q);
    f.F.conservativeResize(6, columns_);
    if (rotates_) f.F(3, 0) = 1.0;
    return f;
  }

 private:
  int columns_;
  bool rotates_;
};

}  // namespace

TEST_CASE("a kind's collider frame is validated when added: F's shape and its rotation rows",
          "[core][kind][validation]") {
  Scene scene;
  Error error;
  CHECK_FALSE(scene.AddActor(std::make_unique<BadFramePointMass>(6, false), &error).IsValid());
  CHECK(error.message.find("must have 3 columns per block") != std::string::npos);
  CHECK_FALSE(scene.AddActor(std::make_unique<BadFramePointMass>(3, true), &error).IsValid());
  CHECK(error.message.find("rotates with a general map") != std::string::npos);
  CHECK(scene.AddActor(std::make_unique<BadFramePointMass>(3, false), &error).IsValid());
}

namespace {

// A point mass pushed by a generalized load f [N] of `size` entries (ActorKind::StageLoad).
class PushedPointMass : public PointMass {
 public:
  PushedPointMass(double mass, const Eigen::Vector3d& f, int size)
      : PointMass(mass, 1e-4, 0.01, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
        f_(f),
        size_(size) {}
  std::unique_ptr<ActorKind> Clone() const override {
    return std::make_unique<PushedPointMass>(*this);
  }
  bool StageLoad(const KindStageData&, Eigen::VectorXd* f) const override {
    f->setZero(size_);
    f->head(std::min(size_, 3)) = f_.head(std::min(size_, 3));
    return true;
  }

 private:
  Eigen::Vector3d f_;
  int size_;
};

}  // namespace

TEST_CASE("a kind's stage load moves it as a force does, and a load of the wrong size is refused",
          "[core][kind][physics]") {
  // A 2 kg point mass without gravity, pushed by the constant load f = (1, −0.5, 0) N through
  // StageLoad (the stages are then not potentials: residual Newton, with the load's work along
  // the committed iterates in the minimizing start), for 1 s at Δt = 1e-2 under BDF2 and DIRK22:
  // x = f t² / (2 m). BDF2 starts with one BDF1 step (error f Δt² / (2 m) in x there, carried
  // as a shift of about that size); DIRK22 is exact for a constant force.
  for (IntegrationMethod method : {IntegrationMethod::BDF2, IntegrationMethod::DIRK22}) {
    SceneSettings s = Settings(1);
    s.integrator = method;
    s.gravity.setZero();
    Scene scene(s);
    Error error;
    const Eigen::Vector3d f(1.0, -0.5, 0.0);
    const ActorHandle p = scene.AddActor(std::make_unique<PushedPointMass>(2.0, f, 3), &error);
    REQUIRE(p.IsValid());
    for (int i = 0; i < 100; ++i) {
      StepReport rep;
      REQUIRE(scene.Step(1e-2, &rep, &error));
      REQUIRE(rep.status == StageStatus::Converged);
    }
    const KindState& st = scene.KindStateOf(p);
    const Eigen::Vector3d expected = f / 2.0 * 0.5;  // f t² / (2 m) at t = 1 s
    INFO("method " << static_cast<int>(method) << ": x " << st.x.transpose() << ", expected "
                   << expected.transpose());
    CHECK((st.x - expected).norm() < 2.0 * f.norm() * 1e-4 / (2.0 * 2.0));
    CHECK((st.v - f / 2.0).norm() < 1e-6);
  }
  Scene scene;
  Error error;
  CHECK_FALSE(scene.AddActor(std::make_unique<PushedPointMass>(1.0, Eigen::Vector3d::UnitX(), 6),
                             &error)
                  .IsValid());
  CHECK(error.message.find("StageLoad") != std::string::npos);
}

TEST_CASE("sensitivities reach a kind written in a test through the layer's default hooks",
          "[core][kind][sensitivity]") {
  // The particle slides down the slope throughout (|v_t| ≫ V_f). Backward Euler gives
  //   s_N = s_0 + N dt v_0 + a dt² N(N+1)/2,   a = g (sin θ − μ cos θ),
  // for its distance s downhill, and the pair's μ is √(μ_particle μ_slope), so
  //   ds_N/dμ_particle = −½ g cos θ dt² N(N+1)/2
  // to the friction falloff's 1e-3. The forward sensitivities are also checked against
  // trajectory differences (1e-5, as tests/core/test_sensitivity.cpp) and the adjoint gradient
  // against the forward one (1e-6: the same partials, transposed).
  const double mu = 0.2, dt = 1e-3;
  const int N = 200;
  const std::vector<std::string> names = {"particle.coulomb_friction_coefficient",
                                          "particle.penalty_coefficient"};
  for (int mode : {0, 1}) {
    INFO(test::kModeNames[mode]);
    SceneSettings settings = Settings(mode);
    settings.solver.absoluteTolerance = 1e-18;
    settings.solver.relativeTolerance = 1e-14;
    settings.solver.stepTolerance = 1e-14;
    Scene scene = ParticleOnSlope(settings, mu);
    const ActorHandle p = scene.FindActor("particle");
    const std::vector<SceneParameter> params = test::ParseParameters(scene, names);
    const Eigen::SparseMatrix<double> C = CenterOfMassMap(scene, p);
    // The default ∂c/∂q, by differences: c = q, so C = [I 0] over the particle's [q; v].
    CHECK((Eigen::MatrixXd(C) - Eigen::MatrixXd::Identity(3, 6)).cwiseAbs().maxCoeff() < 1e-9);
    Error error;
    ForwardSensitivity forward;
    REQUIRE(forward.Begin(&scene, params, &error));
    for (int n = 0; n < N; ++n) {
      StepReport rep;
      INFO(error.message);
      REQUIRE(forward.Step(dt, &rep, &error));
    }
    const Eigen::MatrixXd J = forward.CenterOfMassJacobian(p);
    const double dsdmu = kDownhill.dot(J.col(0));
    const double expected = -0.5 * kG * std::cos(kSlope) * dt * dt * N * (N + 1) / 2.0;
    INFO("ds/dmu = " << dsdmu << " m, expected " << expected);
    CHECK(std::abs(dsdmu - expected) <= 2e-3 * std::abs(expected));
    for (size_t j = 0; j < names.size(); ++j) {
      auto finalCom = [&](double value) {
        Scene probe = ParticleOnSlope(settings, mu);
        REQUIRE(SetParameterValue(&probe, params[j], value, &error));
        for (int n = 0; n < N; ++n) {
          StepReport rep;
          REQUIRE(probe.Step(dt, &rep, &error));
        }
        return probe.CenterOfMass(p);
      };
      const double theta = ParameterValue(scene, params[j]), h = 1e-5 * theta;
      const Eigen::Vector3d fd = (finalCom(theta + h) - finalCom(theta - h)) / (2 * h);
      INFO(names[j] << ": " << J.col(j).transpose() << " against " << fd.transpose());
      CHECK((J.col(j) - fd).lpNorm<Eigen::Infinity>() <= 1e-5 * fd.lpNorm<Eigen::Infinity>());
    }
    // The adjoint of L = downhill · c(S_N).
    Scene again = ParticleOnSlope(settings, mu);
    AdjointSensitivity adjoint;
    REQUIRE(adjoint.Run(&again, std::vector<double>(N, dt), nullptr, &error));
    Eigen::VectorXd g;
    REQUIRE(adjoint.Gradient(
        params,
        [&](int n, Scene& s, Eigen::VectorXd* dL) {
          if (n == N) *dL += CenterOfMassMap(s, p).transpose() * kDownhill;
        },
        &g, &error));
    const Eigen::VectorXd gForward = J.transpose() * kDownhill;
    INFO("adjoint " << g.transpose() << ", forward " << gForward.transpose());
    for (int j = 0; j < g.size(); ++j)
      CHECK(std::abs(g[j] - gForward[j]) <= 1e-6 * std::abs(gForward[j]));
  }
  // Initial-state parameters need the kind's MotionParameter, which the point mass leaves out.
  Scene scene = ParticleOnSlope(Settings(0), mu);
  SceneParameter param;
  Error error;
  CHECK_FALSE(ParseSceneParameter(scene, "particle.velocity.x", &param, &error));
  CHECK(error.message.find("(point mass) has no velocity") != std::string::npos);
}
