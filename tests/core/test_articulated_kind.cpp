// The articulated kind (core/model/articulated_kind.h): links in reduced coordinates carried by
// the generic actor layer.
//
// Expectations:
//   - the stage energy's gradient and exact Hessian in the joints' tangent step equal central
//     differences of Φ(q ⊕ δ) on a tree of every joint type (relative 1e-7 and 1e-5), with a
//     joint beyond its limit, damped and driven along a moving target, and one driven past its
//     force limit; the projected Hessian is positive semi-definite;
//   - a lower limit holds a pendulum at its balance k (x_lim − x) = m g L_c sin x, within 1e-7 rad
//     (the penalty's compliance: 2.4e-4 rad from the limit at k = 1e4 N·m/rad);
//   - a PD drive with k_d = 2√(k_p I) (critical damping, I the link's inertia about the joint)
//     follows x* − (x* − x₀)(1 + t/τ) e^{−t/τ}, τ = √(I/k_p), within 1e-3 rad over 1 s (BDF2,
//     Δt = 1e-3 s); with a force limit F_max it starts at the constant acceleration F_max/I
//     (x − x₀ = F_max t²/(2I) within 1 % at 0.05 s); a drive holding a pendulum horizontal reports
//     the gravity torque m g L_c (1e-6 relative);
//   - viscous damping c on a small-amplitude pendulum decays its amplitude by e^{−c t/(2I)}
//     (within 0.5 % over 4 s);
//   - a compound pendulum (a sphere of radius r = 0.05 m and mass 1 kg whose centre hangs L = 1 m
//     below a revolute pivot; inertia about its centre 2/5 m r²) swings with the period of the
//     equivalent simple pendulum of length L_eq = L + k²/L, k² = 2/5 r²:
//       T(θ₀) = 4 √(L_eq/g) K(sin(θ₀/2))   (K the complete elliptic integral of the first kind,
//       by the arithmetic–geometric mean: K(k) = π / (2 AGM(1, √(1 − k²)))),
//     small amplitude (θ₀ = 0.01 rad, T within θ₀²/16 = 6.25e-6 of 2π√(L_eq/g)) and θ₀ = 90°, within 0.1 % at
//     Δt = 1e-3 s under BDF2 and SymplecticDIRK22 (the period from the mean of upward zero
//     crossings over three swings);
//   - a double pendulum (two such links, released horizontal) under SymplecticDIRK22 at
//     Δt = 1e-3 s keeps its energy within 1e-4 of its initial height above rest (m g L summed)
//     over 10 s (measured 1.5e-6);
//   - a free-floating 5-link chain without gravity (a free root, spherical, revolute and prismatic
//     joints, spinning) keeps its linear and angular momentum to 1e-9 relative under
//     SymplecticDIRK22 with stages started cold (measured 3e-12 and 7e-12; warm-started, to the
//     solver's tolerance: 1e-8), and its linear momentum under BDF2 (its
//     angular momentum is no BDF2 invariant: 2e-5 over 2 s at Δt = 1e-2);
//   - bad descriptions are refused with the link and the rule named.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <random>

#include <Eigen/Eigenvalues>

#include "core/model/articulated_kind.h"
#include "core/model/rigid_math.h"
#include "core/scene.h"
#include "derivative_check.h"
#include "seeded_random.h"

namespace superdex {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Matrix3d SphereInertia(double mass, double radius) {
  return 0.4 * mass * radius * radius * Eigen::Matrix3d::Identity();
}

/// A link hanging `length` below its joint (centre of mass at −length ẑ in the link frame).
ArticulatedLinkDesc Bob(JointType type, int parent, const Eigen::Vector3d& jointAt,
                        double length) {
  ArticulatedLinkDesc link;
  link.joint.type = type;
  link.joint.parent = parent;
  link.joint.origin.p = jointAt;
  link.joint.axis = Eigen::Vector3d::UnitY();
  link.mass = 1.0;
  link.centerOfMass = Eigen::Vector3d(0, 0, -length);
  link.inertia = SphereInertia(1.0, 0.05);
  return link;
}

double CompleteEllipticK(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 40 && std::abs(a - b) > 1e-16 * a; ++i) {
    const double an = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = an;
  }
  return kPi / (2.0 * a);
}

/// Steps `scene` for `duration` s at dt and returns whether every stage converged.
template <typename Visit>
bool Run(Scene* scene, double dt, double duration, Visit&& visit) {
  const int steps = static_cast<int>(std::lround(duration / dt));
  for (int i = 0; i < steps; ++i) {
    StepReport r;
    Error e;
    if (!scene->Step(dt, &r, &e) || r.status != StageStatus::Converged) {
      UNSCOPED_INFO("step " << i << ": " << e.message << r.message);
      return false;
    }
    visit();
  }
  return true;
}

TEST_CASE("an articulated kind's stage energy has the exact gradient and Hessian in its joints",
          "[core][articulated]") {
  std::mt19937 rng(17);
  ArticulatedActorDesc desc;
  const JointType types[4] = {JointType::Free, JointType::Revolute, JointType::Spherical,
                              JointType::Prismatic};
  for (int l = 0; l < 4; ++l) {
    ArticulatedLinkDesc link = Bob(types[l], l - 1, 0.3 * test::UniformVector(3, rng), 0.2);
    link.joint.origin.R = ExpSo3(test::UniformVector(3, rng));
    link.joint.axis = test::UniformVector(3, rng).normalized();
    link.centerOfMass = 0.2 * test::UniformVector(3, rng);
    link.inertia = Eigen::Vector3d(0.02, 0.03, 0.04).asDiagonal();
    desc.links.push_back(link);
  }
  // Joint terms on the two 1-dof joints: the revolute one beyond a limit, damped and driven; the
  // prismatic one driven past its force limit.
  JointParams& hinge = desc.links[1].jointParams;
  hinge.upperLimit = -2.0;
  hinge.damping = 3.0;
  hinge.driveStiffness = 50.0;
  hinge.driveDamping = 2.0;
  hinge.driveTargetPosition = {{0.0, 0.1}, {1.0, 0.7}};
  JointParams& slider = desc.links[3].jointParams;
  slider.driveStiffness = 400.0;
  slider.driveForceLimit = 1.0;
  slider.driveTargetPosition = {{0.0, 3.0}};
  Error error;
  auto kind = ArticulatedKind::Build(desc, &error);
  REQUIRE(kind);
  const int m = kind->NumTangentDofs();
  Eigen::VectorXd q;
  kind->Retract(kind->InitialState().x, test::UniformVector(m, rng), &q);
  KindStageData stage;
  stage.dt = 0.01;
  stage.time = 0.3;
  stage.q0 = q + 0.05 * test::UniformVector(q.size(), rng);
  stage.gravity = Eigen::Vector3d(0, 0, -9.81);
  Eigen::VectorXd qTarget;  // the links' targets: another configuration, moved off the manifold
  kind->Retract(q, 0.3 * test::UniformVector(m, rng), &qTarget);
  stage.qHat = qTarget + 0.05 * test::UniformVector(qTarget.size(), rng);
  const auto value = [&](const Eigen::VectorXd& d) {
    Eigen::VectorXd q1;
    kind->Retract(q, d, &q1);
    return kind->StageEnergy(stage, q1, 0, PsdProjection::None, nullptr, nullptr);
  };
  const auto dense = [&](PsdProjection projection, Eigen::VectorXd* g) {
    std::vector<Eigen::Triplet<double>> t;
    g->setZero(m);
    kind->StageEnergy(stage, q, 2, projection, g, &t);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m, m);
    for (const auto& e : t) H(e.row(), e.col()) += e.value();
    return H;
  };
  Eigen::VectorXd g;
  const Eigen::MatrixXd H = dense(PsdProjection::None, &g);
  const test::DerivativeCheck c = test::CheckDerivatives(value, g, H, 1e-5);
  CHECK(c.gradientError <= 1e-7);
  CHECK(c.hessianError <= 1e-5);
  const Eigen::MatrixXd Hp = dense(PsdProjection::Clamp, &g);
  CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Hp).eigenvalues().minCoeff() >=
        -1e-9 * Hp.norm());
}

double PendulumPeriod(IntegrationMethod method, double amplitude) {
  ArticulatedActorDesc desc;
  desc.links.push_back(Bob(JointType::Revolute, -1, Eigen::Vector3d(0, 0, 1), 1.0));
  desc.jointPositions = Eigen::VectorXd::Constant(1, amplitude);
  Error error;
  auto kind = ArticulatedKind::Build(desc, &error);
  REQUIRE(kind);
  SceneSettings settings;
  settings.integrator = method;
  Scene scene(settings);
  const ActorHandle h = scene.AddActor(std::move(kind), &error);
  REQUIRE(error.ok());
  const auto* pendulum = dynamic_cast<const ArticulatedKind*>(&scene.Kind(h));
  REQUIRE(pendulum);
  std::vector<double> crossings;
  double last = amplitude, t = 0.0;
  const double dt = 1e-3;
  const bool converged = Run(&scene, dt, 9.5, [&] {
    t += dt;
    const double theta = pendulum->JointPositions(scene.KindStateOf(h).x)[0];
    if (last < 0.0 && theta >= 0.0) crossings.push_back(t - dt * theta / (theta - last));
    last = theta;
  });
  CHECK(converged);
  REQUIRE(crossings.size() >= 4);
  return (crossings[3] - crossings[0]) / 3.0;
}

TEST_CASE("a revolute pendulum swings with the compound pendulum's period",
          "[core][articulated]") {
  const double g = 9.81, L = 1.0, r = 0.05;
  const double Leq = L + 0.4 * r * r / L;
  for (IntegrationMethod method : {IntegrationMethod::BDF2, IntegrationMethod::SymplecticDIRK22}) {
    for (double amplitude : {0.01, 0.5 * kPi}) {
      const double expected = 4.0 * std::sqrt(Leq / g) * CompleteEllipticK(std::sin(amplitude / 2));
      if (amplitude < 0.1) CHECK(std::abs(expected / (2 * kPi * std::sqrt(Leq / g)) - 1) <= 7e-6);
      const double period = PendulumPeriod(method, amplitude);
      INFO(ToString(method) << ", amplitude " << amplitude << " rad: period "
                                        << period << " s, expected " << expected << " s");
      CHECK(std::abs(period / expected - 1.0) <= 1e-3);
    }
  }
}

TEST_CASE("a double pendulum under SymplecticDIRK22 keeps its energy", "[core][articulated]") {
  ArticulatedActorDesc desc;
  desc.links.push_back(Bob(JointType::Revolute, -1, Eigen::Vector3d(0, 0, 2), 1.0));
  desc.links.push_back(Bob(JointType::Revolute, 0, Eigen::Vector3d(0, 0, -1), 1.0));
  desc.jointPositions = Eigen::Vector2d(0.5 * kPi, 0.0);
  Error error;
  auto kind = ArticulatedKind::Build(desc, &error);
  REQUIRE(kind);
  SceneSettings settings;
  settings.integrator = IntegrationMethod::SymplecticDIRK22;
  Scene scene(settings);
  const ActorHandle h = scene.AddActor(std::move(kind), &error);
  REQUIRE(error.ok());
  const auto* pendulum = dynamic_cast<const ArticulatedKind*>(&scene.Kind(h));
  REQUIRE(pendulum);
  const auto energy = [&] {
    const KindState& s = scene.KindStateOf(h);
    return pendulum->KineticEnergy(s) + pendulum->GravityEnergy(s, settings.gravity);
  };
  const double e0 = energy();
  const double scale = 9.81 * (1.0 + 2.0);  // the height of both bobs above their rest, m g L
  double drift = 0.0;
  const bool converged =
      Run(&scene, 1e-3, 10.0, [&] { drift = std::max(drift, std::abs(energy() - e0) / scale); });
  CHECK(converged);
  INFO("largest relative energy change " << drift);
  CHECK(drift <= 1e-4);
}

TEST_CASE("a free-floating chain keeps its momentum", "[core][articulated]") {
  ArticulatedActorDesc desc;
  const JointType types[5] = {JointType::Free, JointType::Spherical, JointType::Revolute,
                              JointType::Prismatic, JointType::Revolute};
  for (int l = 0; l < 5; ++l) {
    ArticulatedLinkDesc link = Bob(types[l], l - 1, Eigen::Vector3d(0.05, 0.1 * l, -0.3), 0.15);
    link.joint.axis = Eigen::Vector3d(1, l, 2).normalized();
    link.inertia = Eigen::Vector3d(0.01, 0.02, 0.025).asDiagonal();
    link.mass = 0.5 + 0.2 * l;
    desc.links.push_back(link);
  }
  std::mt19937 rng(23);
  desc.jointVelocities = 2.0 * test::UniformVector(6 + 3 + 1 + 1 + 1, rng);
  for (IntegrationMethod method : {IntegrationMethod::SymplecticDIRK22, IntegrationMethod::BDF2}) {
    Error error;
    auto kind = ArticulatedKind::Build(desc, &error);
    REQUIRE(kind);
    SceneSettings settings;
    settings.integrator = method;
    settings.gravity.setZero();
    // Momentum is kept by the stages' exact solutions; the rule is measured with stages started
    // cold, whose last committed correction is an exact-Hessian Newton step. (Warm-started, the
    // first correction from the projected model already meets the decrement tolerance, 1e-12 J,
    // and 1e-8 of the momentum is left: the stage solver's tolerance, not the rule.)
    settings.warmStart = false;
    Scene scene(settings);
    const ActorHandle h = scene.AddActor(std::move(kind), &error);
    REQUIRE(error.ok());
    const auto* chain = dynamic_cast<const ArticulatedKind*>(&scene.Kind(h));
    REQUIRE(chain);
    const Eigen::Vector3d P0 = chain->LinearMomentum(scene.KindStateOf(h));
    const Eigen::Vector3d L0 = chain->AngularMomentum(scene.KindStateOf(h));
    double dP = 0.0, dL = 0.0;
    const bool converged = Run(&scene, 1e-2, 2.0, [&] {
      dP = std::max(dP, (chain->LinearMomentum(scene.KindStateOf(h)) - P0).norm() / P0.norm());
      dL = std::max(dL, (chain->AngularMomentum(scene.KindStateOf(h)) - L0).norm() / L0.norm());
    });
    INFO(ToString(method) << ": linear " << dP << ", angular " << dL);
    CHECK(converged);
    CHECK(dP <= 1e-9);
    if (method == IntegrationMethod::SymplecticDIRK22) CHECK(dL <= 1e-9);
  }
}

TEST_CASE("an articulated description names the link and the rule it breaks",
          "[core][articulated][validation]") {
  ArticulatedActorDesc desc;
  desc.name = "arm";
  desc.links.push_back(Bob(JointType::Revolute, -1, Eigen::Vector3d::Zero(), 1.0));
  desc.links.push_back(Bob(JointType::Revolute, 0, Eigen::Vector3d(0, 0, -1), 1.0));
  desc.links[1].name = "forearm";
  Error error;
  SECTION("no links") {
    desc.links.clear();
    CHECK_FALSE(ArticulatedKind::Build(desc, &error));
    CHECK_THAT(error.message, Catch::Contains("'arm'") && Catch::Contains("at least one link"));
  }
  SECTION("a negative mass") {
    desc.links[1].mass = -1.0;
    CHECK_FALSE(ArticulatedKind::Build(desc, &error));
    CHECK_THAT(error.message, Catch::Contains("'forearm'") && Catch::Contains("mass"));
  }
  SECTION("an inertia against the triangle inequality") {
    desc.links[1].inertia = Eigen::Vector3d(1.0, 0.1, 0.1).asDiagonal();
    CHECK_FALSE(ArticulatedKind::Build(desc, &error));
    CHECK_THAT(error.message, Catch::Contains("'forearm'") && Catch::Contains("triangle"));
  }
  SECTION("a joint that moves no mass") {
    desc.links[1].mass = 0.0;
    desc.links[1].inertia.setZero();
    CHECK_FALSE(ArticulatedKind::Build(desc, &error));
    CHECK_THAT(error.message, Catch::Contains("'forearm'") && Catch::Contains("moves no mass"));
  }
  SECTION("joint positions of the wrong size") {
    desc.jointPositions = Eigen::VectorXd::Zero(3);
    CHECK_FALSE(ArticulatedKind::Build(desc, &error));
    CHECK_THAT(error.message, Catch::Contains("joint_positions") && Catch::Contains("2 finite"));
  }
  SECTION("a spherical joint's position that is no rotation") {
    desc.links[1].joint.type = JointType::Spherical;
    desc.jointPositions = Eigen::VectorXd::Zero(10);
    CHECK_FALSE(ArticulatedKind::Build(desc, &error));
    CHECK_THAT(error.message, Catch::Contains("'forearm'") && Catch::Contains("rotation matrix"));
  }
  SECTION("a parent that is not an earlier link") {
    desc.links[0].joint.parent = 1;
    CHECK_FALSE(ArticulatedKind::Build(desc, &error));
    CHECK_THAT(error.message, Catch::Contains("earlier link"));
  }
}

}  // namespace
}  // namespace superdex

namespace superdex {
namespace {

/// A scene of one articulated actor; the kind in the scene, its handle and the scene.
struct OneArticulation {
  explicit OneArticulation(const ArticulatedActorDesc& desc, SceneSettings settings = {})
      : scene(settings) {
    Error error;
    handle = scene.AddActor(ArticulatedKind::Build(desc, &error), &error);
    REQUIRE(error.ok());
    kind = dynamic_cast<const ArticulatedKind*>(&scene.Kind(handle));
    REQUIRE(kind);
  }
  double Position(int k = 0) const { return kind->JointPositions(scene.KindStateOf(handle).x)[k]; }
  Scene scene;
  ActorHandle handle;
  const ArticulatedKind* kind = nullptr;
};

/// A link of mass 1 kg whose centre lies L_c = 0.5 m from a revolute joint about y at the origin
/// (a sphere of radius 0.05 m): inertia about the joint I = m L_c² + 2/5 m r².
ArticulatedLinkDesc Arm() {
  ArticulatedLinkDesc link = Bob(JointType::Revolute, -1, Eigen::Vector3d::Zero(), 0.5);
  return link;
}
constexpr double kArmInertia = 0.25 + 0.4 * 0.05 * 0.05;

TEST_CASE("a joint limit holds a pendulum at the penalty's balance", "[core][articulated]") {
  ArticulatedActorDesc desc;
  desc.links.push_back(Arm());
  desc.links[0].jointParams.lowerLimit = 0.5;
  desc.links[0].jointParams.limitStiffness = 1e4;
  desc.links[0].jointParams.damping = 2.0;
  desc.jointPositions = Eigen::VectorXd::Constant(1, 0.5);
  OneArticulation a(desc);
  CHECK(Run(&a.scene, 1e-2, 3.0, [] {}));
  // Balance: k (0.5 − x) = m g L_c sin x, by Newton.
  const double k = 1e4, mgl = 9.81 * 0.5;
  double x = 0.5;
  for (int i = 0; i < 20; ++i) x -= (k * (0.5 - x) - mgl * std::sin(x)) / (-k - mgl * std::cos(x));
  INFO("rests at " << a.Position() << " rad, balance " << x << " rad");
  CHECK(std::abs(a.Position() - x) <= 1e-7);
  CHECK(0.5 - x == Approx(mgl * std::sin(0.5) / k).epsilon(1e-2));
}

TEST_CASE("a critically damped PD drive settles with its time constant", "[core][articulated]") {
  const double kp = 100.0, tau = std::sqrt(kArmInertia / kp);
  SceneSettings settings;
  settings.gravity.setZero();
  ArticulatedActorDesc desc;
  desc.links.push_back(Arm());
  JointParams& drive = desc.links[0].jointParams;
  drive.driveStiffness = kp;
  drive.driveDamping = 2.0 * std::sqrt(kp * kArmInertia);
  drive.driveTargetPosition = {{0.0, 1.0}};
  OneArticulation a(desc, settings);
  double t = 0.0, err = 0.0;
  CHECK(Run(&a.scene, 1e-3, 1.0, [&] {
    t += 1e-3;
    const double expected = 1.0 - (1.0 + t / tau) * std::exp(-t / tau);
    err = std::max(err, std::abs(a.Position() - expected));
  }));
  INFO("largest deviation " << err << " rad, tau " << tau << " s");
  CHECK(err <= 1e-3);
}

TEST_CASE("a drive's force limit caps its acceleration", "[core][articulated]") {
  SceneSettings settings;
  settings.gravity.setZero();
  ArticulatedActorDesc desc;
  desc.links.push_back(Arm());
  JointParams& drive = desc.links[0].jointParams;
  drive.driveStiffness = 1e4;
  drive.driveDamping = 10.0;
  drive.driveForceLimit = 0.5;
  drive.driveTargetPosition = {{0.0, 1.0}};
  OneArticulation a(desc, settings);
  CHECK(Run(&a.scene, 1e-3, 0.05, [] {}));
  const double expected = 0.5 / kArmInertia * 0.05 * 0.05 / 2.0;
  CHECK(a.Position() == Approx(expected).epsilon(1e-2));
  CHECK(a.kind->DriveForces(a.scene.KindStateOf(a.handle), a.scene.Time())[0] ==
        Approx(0.5).epsilon(1e-12));
}

TEST_CASE("a drive holding a pendulum horizontal reports the gravity torque",
          "[core][articulated]") {
  ArticulatedActorDesc desc;
  desc.links.push_back(Arm());
  JointParams& drive = desc.links[0].jointParams;
  drive.driveStiffness = 1e3;
  drive.driveDamping = 20.0;
  drive.driveTargetPosition = {{0.0, 0.5 * kPi}};
  desc.jointPositions = Eigen::VectorXd::Constant(1, 0.5 * kPi);
  OneArticulation a(desc);
  CHECK(Run(&a.scene, 1e-2, 3.0, [] {}));
  const double x = a.Position();
  const double F = a.kind->DriveForces(a.scene.KindStateOf(a.handle), a.scene.Time())[0];
  CHECK(F == Approx(9.81 * 0.5 * std::sin(x)).epsilon(1e-6));
  CHECK(0.5 * kPi - x == Approx(9.81 * 0.5 / 1e3).epsilon(1e-3));
}

TEST_CASE("joint damping decays a small swing at the viscous rate", "[core][articulated]") {
  const double c = 0.02;
  ArticulatedActorDesc desc;
  desc.links.push_back(Arm());
  desc.links[0].jointParams.damping = c;
  desc.jointPositions = Eigen::VectorXd::Constant(1, 0.01);
  SceneSettings settings;
  settings.integrator = IntegrationMethod::SymplecticDIRK22;
  OneArticulation a(desc, settings);
  // Peaks of |x|: the amplitude, sampled at the extremes.
  std::vector<std::pair<double, double>> peaks;
  double t = 0.0, x1 = a.Position(), x2 = x1;
  CHECK(Run(&a.scene, 1e-3, 4.5, [&] {
    t += 1e-3;
    const double x = a.Position();
    if (std::abs(x1) >= std::abs(x2) && std::abs(x1) > std::abs(x) && t > 0.1)
      peaks.emplace_back(t - 1e-3, std::abs(x1));
    x2 = x1;
    x1 = x;
  }));
  REQUIRE(peaks.size() >= 4);
  const auto& [t0, a0] = peaks.front();
  const auto& [tn, an] = peaks.back();
  const double expected = std::exp(-c * (tn - t0) / (2.0 * kArmInertia));
  INFO(peaks.size() << " peaks from " << t0 << " s to " << tn << " s");
  CHECK(an / a0 == Approx(expected).epsilon(5e-3));
}

}  // namespace
}  // namespace superdex

namespace superdex {
namespace {

/// The world position of the last link's centre after `duration` s of a damped three-link chain
/// (revolute, spherical, revolute; the hinges damped) under `method` at step dt.
Eigen::Vector3d ChainTip(IntegrationMethod method, double dt, double duration) {
  ArticulatedActorDesc desc;
  const JointType types[3] = {JointType::Revolute, JointType::Spherical, JointType::Revolute};
  for (int l = 0; l < 3; ++l) {
    ArticulatedLinkDesc link = Bob(types[l], l - 1, Eigen::Vector3d(0, 0, l == 0 ? 1.0 : -0.5), 0.5);
    link.centerOfMass = Eigen::Vector3d(0.1, 0.05, -0.5);
    link.inertia = Eigen::Vector3d(0.02, 0.03, 0.01).asDiagonal();
    if (types[l] == JointType::Revolute) link.jointParams.damping = 0.2;
    desc.links.push_back(link);
  }
  desc.jointPositions = Eigen::VectorXd::Zero(1 + 9 + 1);
  desc.jointPositions[0] = 1.2;
  Eigen::Map<Eigen::Matrix3d>(desc.jointPositions.data() + 1) =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  desc.jointVelocities = Eigen::VectorXd::Zero(5);
  desc.jointVelocities.segment<3>(1) = Eigen::Vector3d(0.5, -1.0, 2.0);
  SceneSettings settings;
  settings.integrator = method;
  OneArticulation a(desc, settings);
  REQUIRE(Run(&a.scene, dt, duration, [] {}));
  const KindState& s = a.scene.KindStateOf(a.handle);
  return a.kind->LinkCenter(s.x, 2);
}

TEST_CASE("a damped chain with a spherical joint keeps each DIRK's second order",
          "[core][articulated][order]") {
  // Errors against the same method at dt = 2.5e-5 s after 0.5 s; halving dt must divide them by
  // 2^1.8 at least (measured: 2^1.97 to 2^2.0).
  for (IntegrationMethod method : {IntegrationMethod::SymplecticDIRK22, IntegrationMethod::DIRK22,
                                   IntegrationMethod::BDF2}) {
    const Eigen::Vector3d ref = ChainTip(method, 2.5e-5, 0.5);
    const double e1 = (ChainTip(method, 4e-3, 0.5) - ref).norm();
    const double e2 = (ChainTip(method, 2e-3, 0.5) - ref).norm();
    const double e3 = (ChainTip(method, 1e-3, 0.5) - ref).norm();
    INFO(ToString(method) << ": tip errors " << e1 << ", " << e2 << ", " << e3 << " m");
    CHECK(std::log2(e1 / e2) >= 1.8);
    CHECK(std::log2(e2 / e3) >= 1.8);
  }
}

}  // namespace
}  // namespace superdex
