// Adjoint gradients (core/sensitivity/adjoint.h) and the step linearization they run on
// (core/sensitivity/step_linearization.h): the linearization against the recorded stage Jacobians and its
// own transpose, the adjoint gradient against the forward sensitivities (core/sensitivity/sensitivity.h,
// which tests/core/test_sensitivity.cpp checks against trajectory differences) and against
// trajectory differences directly.
#include <catch2/catch.hpp>
#include <functional>
#include <random>
#include <tbb/global_control.h>

#include "core/sensitivity/adjoint.h"
#include "core/sensitivity/step_linearization.h"
#include "sensitivity_scenes.h"

using namespace superdex;
using namespace superdex::test;

namespace {

// Four 1 kg boxes on the ground (μ = mu, c_n = 1 s/m, c_t = 0.2 s/m): "a" slides at 0.6 m/s into
// "b", whose face it already touches (0.5 mm overlap); "d" rests on "c", which spins about z,
// 1 m away. Two contact clusters: the colouring moves one box of each together.
Scene FourBoxes(IntegrationMethod method, DissipationMode mode, double mu = 0.5) {
  Scene scene(TightSettings(method, mode));
  Error error;
  RigidActorDesc ground = Ground(Eigen::Vector3d::UnitZ(), 1e7, mu, 1.0);
  ground.contact.viscousFrictionCoefficient = 0.2;
  REQUIRE(scene.AddRigidActor(ground, &error).IsValid());
  auto box = [&](const char* name, const Eigen::Vector3d& p, const Eigen::Vector3d& v,
                 const Eigen::Vector3d& w) {
    RigidActorDesc d = Cube(1e7, mu, 1.0);
    d.name = name;
    d.contact.viscousFrictionCoefficient = 0.2;
    d.position = p;
    d.linearVelocity = v;
    d.angularVelocity = w;
    REQUIRE(scene.AddRigidActor(d, &error).IsValid());
  };
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  box("a", {0.0, 0.0, 0.1 - 5e-4}, {0.6, 0.0, 0.0}, zero);
  box("b", {0.2 - 5e-4, 0.01, 0.1 - 5e-4}, zero, zero);
  box("c", {1.0, 0.0, 0.1 - 1e-3}, {0.0, 0.1, 0.0}, {0.0, 0.0, 2.0});
  box("d", {1.0, 0.0, 0.3 - 1.5e-3}, zero, zero);
  return scene;
}

// L = Σ_n Σ_a w_a · c_a(S_n): a weighted sum of every dynamic actor's centre of mass over the run.
struct ComLoss {
  std::vector<ActorHandle> actors;
  std::vector<Eigen::Vector3d> weights;
  explicit ComLoss(Scene& scene) {
    for (int i = 0; i < scene.NumActors(); ++i) {
      // Every actor with a state of its own: not a static rigid one, not a link's shape.
      if (scene.IsAttached({i})) continue;
      if (!scene.IsSoft({i}) && !scene.IsKind({i}) && !scene.Model({i}).dynamic) continue;
      actors.push_back({i});
      weights.emplace_back(1.0 + i, 0.5 - 0.3 * i, 2.0 + 0.1 * i);
    }
  }
  double Value(Scene& scene) const {
    double v = 0.0;
    for (size_t k = 0; k < actors.size(); ++k) v += weights[k].dot(scene.CenterOfMass(actors[k]));
    return v;
  }
  Eigen::VectorXd Gradient(Scene& scene) const {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(scene.StateSize());
    for (size_t k = 0; k < actors.size(); ++k)
      g += CenterOfMassMap(scene, actors[k]).transpose() * weights[k];
    return g;
  }
};

Eigen::VectorXd AdjointGradient(const std::function<Scene()>& build,
                                const std::vector<std::string>& names, int steps, double dt,
                                AdjointSensitivity* adjoint = nullptr) {
  Scene scene = build();
  const std::vector<SceneParameter> params = ParseParameters(scene, names);
  const ComLoss loss(scene);
  AdjointSensitivity own;
  AdjointSensitivity& adj = adjoint ? *adjoint : own;
  Error error;
  INFO(error.message);
  REQUIRE(adj.Run(&scene, std::vector<double>(steps, dt), nullptr, &error));
  Eigen::VectorXd g;
  const bool ok = adj.Gradient(
      params, [&](int, Scene& s, Eigen::VectorXd* dL) { *dL += loss.Gradient(s); }, &g, &error);
  INFO(error.message);
  REQUIRE(ok);
  return g;
}

Eigen::VectorXd ForwardGradient(const std::function<Scene()>& build,
                                const std::vector<std::string>& names, int steps, double dt) {
  Scene scene = build();
  const std::vector<SceneParameter> params = ParseParameters(scene, names);
  const ComLoss loss(scene);
  ForwardSensitivity fwd;
  Error error;
  REQUIRE(fwd.Begin(&scene, params, &error));
  Eigen::VectorXd g = fwd.StateJacobian().transpose() * loss.Gradient(scene);
  for (int n = 0; n < steps; ++n) {
    INFO(error.message);
    REQUIRE(fwd.Step(dt, nullptr, &error));
    g += fwd.StateJacobian().transpose() * loss.Gradient(scene);
  }
  return g;
}

double LossAlongTrajectory(const std::function<Scene()>& build, const std::string& name,
                           double value, int steps, double dt) {
  Scene scene = build();
  const std::vector<SceneParameter> p = ParseParameters(scene, {name});
  Error error;
  REQUIRE(SetParameterValue(&scene, p[0], value, &error));
  const ComLoss loss(scene);
  double L = loss.Value(scene);
  for (int n = 0; n < steps; ++n) {
    StepReport rep;
    REQUIRE(scene.Step(dt, &rep, &error));
    REQUIRE(rep.status == StageStatus::Converged);
    L += loss.Value(scene);
  }
  return L;
}

void CheckAgainstForward(const std::function<Scene()>& build, const std::vector<std::string>& names,
                         int steps, double dt, double tolerance) {
  AdjointSensitivity adjoint;
  const Eigen::VectorXd ga = AdjointGradient(build, names, steps, dt, &adjoint);
  const Eigen::VectorXd gf = ForwardGradient(build, names, steps, dt);
  for (size_t j = 0; j < names.size(); ++j) {
    const double err = std::abs(ga[j] - gf[j]) / std::abs(gf[j]);
    INFO(names[j] << ": adjoint " << ga[j] << ", forward " << gf[j] << ", relative " << err
                  << "; colours " << adjoint.MaxColors() << ", runs " << adjoint.InjectRuns());
    CHECK(gf[j] != 0.0);
    CHECK(err < tolerance);
  }
}

// dL/dθ by the adjoint against central differences of L over whole simulations; probe steps
// relative for model parameters, absolute for initial states.
void CheckAgainstTrajectoryDifferences(const std::function<Scene()>& build,
                                       const std::vector<std::pair<std::string, double>>& probes,
                                       int steps, double dt, double tolerance) {
  std::vector<std::string> names;
  for (const auto& p : probes) names.push_back(p.first);
  const Eigen::VectorXd g = AdjointGradient(build, names, steps, dt);
  for (size_t j = 0; j < probes.size(); ++j) {
    Scene probe = build();
    const SceneParameter p = ParseParameters(probe, {names[j]})[0];
    const double theta = ParameterValue(probe, p);
    const double h = p.IsInitialState() ? probes[j].second : probes[j].second * std::abs(theta);
    const double fd = (LossAlongTrajectory(build, names[j], theta + h, steps, dt) -
                       LossAlongTrajectory(build, names[j], theta - h, steps, dt)) /
                      (2 * h);
    const double err = std::abs(g[j] - fd) / std::abs(fd);
    INFO(names[j] << ": adjoint " << g[j] << ", trajectory differences " << fd << ", relative "
                  << err);
    CHECK(fd != 0.0);
    CHECK(err < tolerance);
  }
}

}  // namespace

TEST_CASE("Step linearization: the difference partials reproduce the stage Jacobians, every "
          "changed row is attributed, and the adjoint is the transpose of the tangent",
          "[adjoint]") {
  for (IntegrationMethod method : {IntegrationMethod::DIRK22, IntegrationMethod::BDF2}) {
    INFO(ToString(method));
    Scene scene = FourBoxes(method, DissipationMode::ReconstructedLoad);
    Error error;
    for (int n = 0; n < 10; ++n) REQUIRE(scene.Step(2e-3, nullptr, &error));
    const std::vector<SceneParameter> params =
        ParseParameters(scene, {"a.coulomb_friction_coefficient", "ground.penalty_coefficient"});
    StepLinearizer lin;
    StepReport rep;
    INFO(error.message);
    REQUIRE(lin.Linearize(&scene, 2e-3, params, &rep, &error));
    CHECK(lin.Colors() == 2);  // {a, c} and {b, d}
    CHECK(lin.Unattributed() == 0.0);
    // Runs: 4 × (2 colours × local directions (18 per state block: p, the three tangent
    // directions of R, v, Ṙ; 6 per stage) + a's slot for its μ + the ground's penalty
    // coefficient alone).
    const int locals = 18 * (method == IntegrationMethod::BDF2 ? 2 : 1) + 6 * lin.Stages();
    CHECK(lin.Runs() == 4 * (2 * locals + 1 + 1));
    // ∂ρ_i/∂δ_i by differences against the recorded J_i.
    const int ns = scene.StateSize();
    const int nd = lin.StageJacobian(0).rows();
    for (int i = 0; i < lin.Stages(); ++i) {
      const Eigen::MatrixXd fd = Eigen::MatrixXd(lin.Partials()).block(i * nd, ns + i * nd, nd, nd);
      const Eigen::MatrixXd J = Eigen::MatrixXd(lin.StageJacobian(i));
      const double err = (fd - J).lpNorm<Eigen::Infinity>() / J.lpNorm<Eigen::Infinity>();
      INFO("stage " << i << ": |FD − J| / |J| = " << err);
      CHECK(err < 1e-6);  // measured 2–3e-8
    }
    // λᵀ (T dS) = (Tᵀ λ)ᵀ dS for random vectors: the two products apply one linear map.
    std::mt19937 rng(3);
    std::normal_distribution<double> normal;
    Eigen::VectorXd dS(ns), lambda(ns), dTheta(params.size());
    for (int k = 0; k < ns; ++k) dS[k] = normal(rng), lambda[k] = normal(rng);
    for (int k = 0; k < dTheta.size(); ++k) dTheta[k] = normal(rng);
    dTheta *= 1e3;  // k is O(1e7)
    const Eigen::VectorXd t = lin.Tangent(dS, dTheta);
    Eigen::VectorXd lambdaPrev, gTheta;
    lin.Adjoint(lambda, &lambdaPrev, &gTheta);
    const double lhs = lambda.dot(t);
    const double rhs = lambdaPrev.dot(dS) + gTheta.dot(dTheta);
    INFO("λᵀ T dS = " << lhs << ", (Tᵀ λ)ᵀ dS = " << rhs);
    CHECK(std::abs(lhs - rhs) <= 1e-10 * (std::abs(lhs) + lambda.norm() * t.norm()));
  }
}

TEST_CASE("Adjoint gradients of four frictionless boxes match trajectory differences",
          "[adjoint]") {
  // Normal damping and viscous friction only: the stage residual is smooth in every input, and
  // the adjoint gradient agrees with central differences of the loss over whole simulations
  // (measured 1e-7 … 3e-6).
  const std::vector<std::pair<std::string, double>> probes = {
      {"a.normal_viscous_damping_coefficient", 1e-4}, {"c.penalty_coefficient", 1e-5},
      {"a.position.x", 1e-6}, {"b.velocity.y", 1e-5}, {"d.position.z", 1e-6}};
  for (const auto& [method, mode] :
       {std::pair{IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad},
        std::pair{IntegrationMethod::DIRK22, DissipationMode::ExplicitNormals}}) {
    INFO(ToString(method) << ", " << ToString(mode));
    CheckAgainstTrajectoryDifferences([method = method, mode = mode] {
      return FourBoxes(method, mode, 0.0);
    }, probes, 40, 2e-3, 1e-5);
  }
}

TEST_CASE("Adjoint gradients of four boxes with friction match the forward sensitivities",
          "[adjoint]") {
  // With Coulomb friction the resting contacts sit at V_t ≈ 0, where the friction force is only
  // C¹; both difference schemes evaluate it about the recorded slips (core/contact/slip_tape.h), and the
  // test below checks both against whole-simulation differences under every integrator.
  // Measured disagreement here: at most 3.9e-4 (d's viscous friction coefficient, DIRK22) and
  // 3.4e-4 (c's spin), both small remainders of this centre-of-mass loss (−0.0026 against
  // derivatives of order 100 for the positions); 1e-5 or less for the others.
  const std::vector<std::string> names = {
      "a.coulomb_friction_coefficient",   "b.normal_viscous_damping_coefficient",
      "ground.coulomb_friction_coefficient", "c.penalty_coefficient",
      "d.viscous_friction_coefficient",   "a.position.x",
      "b.velocity.y",                     "c.angular_velocity.z",
      "d.position.z"};
  SECTION("BDF2, reconstructed load") {
    CheckAgainstForward(
        [] { return FourBoxes(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad); },
        names, 40, 2e-3, 1e-3);
  }
  SECTION("DIRK22, explicit normals") {
    CheckAgainstForward(
        [] { return FourBoxes(IntegrationMethod::DIRK22, DissipationMode::ExplicitNormals); },
        names, 40, 2e-3, 1e-3);
  }
}

TEST_CASE("Adjoint gradients of a soft cube match trajectory differences", "[adjoint]") {
  CheckAgainstTrajectoryDifferences([] { return SoftCube(IntegrationMethod::BDF2); },
                                    {{"soft.youngs_modulus", 1e-5},
                                     {"soft.density", 1e-5},
                                     {"soft.coulomb_friction_coefficient", 1e-5},
                                     {"soft.velocity.x", 1e-6},
                                     {"soft.position.z", 1e-7}},
                                    60, 1e-3, 1e-5);
}

TEST_CASE("Adjoint gradients of a sliding and a bouncing box match trajectory differences",
          "[adjoint]") {
  // The scenes and difference steps of tests/core/test_sensitivity.cpp.
  SECTION("sliding box, BDF2, reconstructed load (slides to rest)") {
    CheckAgainstTrajectoryDifferences(
        [] { return SlidingBox(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad); },
        {{"cube.coulomb_friction_coefficient", 1e-5},
         {"cube.normal_viscous_damping_coefficient", 1e-5},
         {"cube.friction_falloff_vel", 1e-5},
         {"cube.velocity.x", 1e-6},
         {"cube.angular_velocity.y", 1e-6}},
        100, 2e-3, 1e-5);
  }
  SECTION("bouncing box, BDF2, reconstructed load") {
    CheckAgainstTrajectoryDifferences(
        [] { return BouncingBox(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad); },
        {{"cube.normal_viscous_damping_coefficient", 1e-5},
         {"cube.coulomb_friction_coefficient", 1e-5},
         {"cube.penalty_coefficient", 1e-5},
         {"cube.position.z", 1e-7},
         {"cube.velocity.z", 1e-6}},
        150, 1e-3, 1e-5);
  }
  SECTION("box pushed by an applied force, BDF2, reconstructed load: its mass") {
    CheckAgainstTrajectoryDifferences(
        [] { return PushedBox(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad); },
        {{"cube.mass", 1e-5}, {"cube.coulomb_friction_coefficient", 1e-5}}, 100, 2e-3, 1e-5);
  }
}

TEST_CASE("Adjoint gradients beside and through an articulated actor match trajectory differences",
          "[adjoint][articulated][attached]") {
  SECTION("a sliding box beside a driven pendulum, BDF2, reconstructed load") {
    CheckAgainstTrajectoryDifferences(
        [] {
          Scene s = SlidingBox(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad);
          Error e;
          REQUIRE(s.AddArticulatedActor(DrivenPendulumDesc(Eigen::Vector3d(5, 0, 2)), &e).IsValid());
          return s;
        },
        {{"cube.coulomb_friction_coefficient", 1e-5}, {"cube.velocity.x", 1e-6}}, 100, 2e-3, 1e-5);
  }
  SECTION("a driven pendulum: its link mass and drive gains, BDF2") {
    CheckAgainstTrajectoryDifferences([] { return DrivenPendulum(IntegrationMethod::BDF2); },
                                      {{"pendulum.link_mass.bob", 1e-5},
                                       {"pendulum.drive_stiffness.bob", 1e-5},
                                       {"pendulum.drive_damping.bob", 1e-5}},
                                      200, 2e-3, 1e-5);
  }
  // Through link shapes: the link of tests/core/test_sensitivity.cpp turning on a revolute joint
  // (its contact reaches the joints through a chart that turns with them), and sliding.
  SECTION("a link turning on a revolute joint, DIRK22, reconstructed load") {
    CheckAgainstTrajectoryDifferences(
        [] { return TurningLink(IntegrationMethod::DIRK22, DissipationMode::ReconstructedLoad); },
        {{"slider/block.coulomb_friction_coefficient", 1e-5},
         {"slider/block.penalty_coefficient", 1e-5},
         {"slider/block.normal_viscous_damping_coefficient", 1e-5}},
        100, 2e-3, 1e-5);
  }
  SECTION("a link sliding on a prismatic joint, BDF2, explicit normals") {
    CheckAgainstTrajectoryDifferences(
        [] { return SlidingLink(IntegrationMethod::BDF2, DissipationMode::ExplicitNormals); },
        {{"slider/block.coulomb_friction_coefficient", 1e-5},
         {"slider/block.viscous_friction_coefficient", 1e-5}},
        100, 2e-3, 1e-5);
  }
}

TEST_CASE("Adjoint: refusals", "[adjoint]") {
  Scene scene = SlidingBox(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad);
  AdjointSensitivity adjoint;
  Error error;
  Eigen::VectorXd g;
  const auto none = [](int, Scene&, Eigen::VectorXd*) {};
  CHECK_FALSE(adjoint.Gradient({}, none, &g, &error));
  CHECK(error.message.find("Run first") != std::string::npos);
  REQUIRE(scene.Step(1e-3, nullptr, &error));
  REQUIRE(adjoint.Run(&scene, {1e-3, 1e-3}, nullptr, &error));
  // The trajectory starts after a step: its initial state is not a parameter any more.
  CHECK_FALSE(adjoint.Gradient(ParseParameters(scene, {"cube.velocity.x"}), none, &g, &error));
  CHECK(error.message.find("initial-state parameter") != std::string::npos);
  std::vector<SceneParameter> mu = ParseParameters(scene, {"cube.coulomb_friction_coefficient"});
  REQUIRE(adjoint.Gradient(mu, none, &g, &error));
  CHECK(g.size() == 1);
  CHECK(g[0] == 0.0);  // a zero loss
  REQUIRE(SetParameterValue(&scene, mu[0], 0.0, &error));
  REQUIRE(adjoint.Run(&scene, {1e-3}, nullptr, &error));
  CHECK_FALSE(adjoint.Gradient(mu, none, &g, &error));
  CHECK(error.message.find("positive values only") != std::string::npos);
}


TEST_CASE("Step linearization: the partials do not depend on the number of threads", "[adjoint]") {
  Scene scene = FourBoxes(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad);
  Error error;
  for (int n = 0; n < 5; ++n) REQUIRE(scene.Step(2e-3, nullptr, &error));
  const std::vector<SceneParameter> params =
      ParseParameters(scene, {"b.coulomb_friction_coefficient", "ground.coulomb_friction_coefficient"});
  Scene copy = scene;
  StepLinearizer parallel, serial;
  REQUIRE(parallel.Linearize(&scene, 2e-3, params, nullptr, &error));
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    REQUIRE(serial.Linearize(&copy, 2e-3, params, nullptr, &error));
  }
  const Eigen::MatrixXd a = Eigen::MatrixXd(parallel.Partials());
  const Eigen::MatrixXd b = Eigen::MatrixXd(serial.Partials());
  CHECK(a.nonZeros() > 0);
  CHECK((a - b).cwiseAbs().maxCoeff() == 0.0);
  CHECK(scene.PackState() == copy.PackState());
}

namespace {

// L = Σ_n wᵀ S_n: fixed pseudo-random weights on every entry of the packed state (poses,
// velocities, rotation rates, history), so that the spin of the stacked boxes enters directly.
Eigen::VectorXd StateWeights(int size) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  Eigen::VectorXd w(size);
  for (int k = 0; k < size; ++k) w[k] = normal(rng);
  return w;
}

double StateLoss(const std::function<Scene()>& build, const SceneParameter& p, double value,
                 int steps, double dt) {
  Scene scene = build();
  Error error;
  REQUIRE(SetParameterValue(&scene, p, value, &error));
  const Eigen::VectorXd w = StateWeights(scene.StateSize());
  double L = w.dot(scene.PackState());
  for (int n = 0; n < steps; ++n) {
    StepReport rep;
    REQUIRE(scene.Step(dt, &rep, &error));
    REQUIRE(rep.status == StageStatus::Converged);
    L += w.dot(scene.PackState());
  }
  return L;
}

}  // namespace

TEST_CASE("Sensitivities of four boxes with friction match trajectory differences under every "
          "integrator", "[adjoint]") {
  // The spinning box c drags the resting box d on top of it until d sticks to it: sticking and
  // resting samples at V_t ≈ 0, where the friction force is only C¹. Both derivative schemes
  // difference the stage residual about the recorded solution with each sample's recorded slip
  // (core/contact/slip_tape.h); without it (the exact force differenced across the kink) the errors
  // against whole-simulation differences were up to 2.6e-2 (forward, SymplecticDIRK22, c's
  // velocity), 1.6e-2 (adjoint, DIRK33) and 3.5e-3 (forward, BackwardEuler). Measured with it:
  // at most 2.0e-4 (forward) and 1.4e-4 (adjoint), where the differences themselves move by up
  // to 1.4e-4 between probe steps h and 10h. The loss weighs every state entry, the boxes' spin
  // included (a centre-of-mass loss barely sees c's spin: its derivative is a small remainder).
  const std::vector<std::pair<std::string, double>> probes = {
      {"c.angular_velocity.z", 1e-5}, {"c.velocity.y", 1e-5},
      {"d.viscous_friction_coefficient", 1e-5}, {"ground.coulomb_friction_coefficient", 1e-5},
      {"a.position.x", 1e-6}};
  std::vector<std::string> names;
  for (const auto& p : probes) names.push_back(p.first);
  const int steps = 40;
  const double dt = 2e-3;
  for (IntegrationMethod method :
       {IntegrationMethod::BackwardEuler, IntegrationMethod::BDF2, IntegrationMethod::DIRK22,
        IntegrationMethod::DIRK33, IntegrationMethod::SymplecticDIRK12,
        IntegrationMethod::SymplecticDIRK22}) {
    for (DissipationMode mode :
         {DissipationMode::ExplicitNormals, DissipationMode::ReconstructedLoad}) {
      INFO(ToString(method) << ", " << ToString(mode));
      const auto build = [=] { return FourBoxes(method, mode); };
      Scene scene = build();
      const std::vector<SceneParameter> params = ParseParameters(scene, names);
      const Eigen::VectorXd w = StateWeights(scene.StateSize());
      Error error;
      Eigen::VectorXd ga, gf;
      {
        Scene s = build();
        AdjointSensitivity adjoint;
        REQUIRE(adjoint.Run(&s, std::vector<double>(steps, dt), nullptr, &error));
        REQUIRE(adjoint.Gradient(params, [&](int, Scene&, Eigen::VectorXd* dL) { *dL += w; },
                                 &ga, &error));
      }
      {
        Scene s = build();
        ForwardSensitivity forward;
        REQUIRE(forward.Begin(&s, params, &error));
        gf = forward.StateJacobian().transpose() * w;
        for (int n = 0; n < steps; ++n) {
          REQUIRE(forward.Step(dt, nullptr, &error));
          gf += forward.StateJacobian().transpose() * w;
        }
      }
      for (size_t j = 0; j < probes.size(); ++j) {
        const double theta = ParameterValue(scene, params[j]);
        const double h =
            params[j].IsInitialState() ? probes[j].second : probes[j].second * std::abs(theta);
        auto fdAt = [&](double e) {
          return (StateLoss(build, params[j], theta + e, steps, dt) -
                  StateLoss(build, params[j], theta - e, steps, dt)) / (2 * e);
        };
        const double fd = fdAt(h), fd10 = fdAt(10 * h);
        INFO(names[j] << ": differences " << fd << " (at 10 h " << fd10 << "), adjoint " << ga[j]
                      << ", forward " << gf[j]);
        REQUIRE(std::abs(fd10 - fd) <= 2.5e-4 * std::abs(fd));  // the reference holds
        CHECK(std::abs(ga[j] - fd) <= 5e-4 * std::abs(fd));
        CHECK(std::abs(gf[j] - fd) <= 5e-4 * std::abs(fd));
      }
    }
  }
}
