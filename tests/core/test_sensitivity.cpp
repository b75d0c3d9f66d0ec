// Trajectory sensitivities (core/sensitivity/sensitivity.h) against central finite differences of whole
// simulations: a sliding box, a bouncing box and a soft cube, across integrators and dissipation
// modes. Tolerance: 1e-5 relative to the largest entry of the compared derivative.
#include <catch2/catch.hpp>
#include <functional>
#include <tbb/global_control.h>

#include "core/sensitivity/sensitivity.h"
#include "sensitivity_scenes.h"

using namespace superdex;
using namespace superdex::test;

namespace {

using Builder = std::function<Scene()>;

// Final centre of mass of `actor` after `steps` steps of dt, with parameter `name` set to value.
Eigen::Vector3d FinalCom(const Builder& build, const std::string& name, double value,
                         const std::string& actor, int steps, double dt) {
  Scene scene = build();
  SceneParameter p;
  Error error;
  REQUIRE(ParseSceneParameter(scene, name, &p, &error));
  REQUIRE(SetParameterValue(&scene, p, value, &error));
  for (int n = 0; n < steps; ++n) {
    StepReport rep;
    REQUIRE(scene.Step(dt, &rep, &error));
    REQUIRE(rep.status == StageStatus::Converged);
  }
  return scene.CenterOfMass(scene.FindActor(actor));
}

// Checks every parameter's d(final COM)/dθ against a central difference of whole simulations.
// The difference steps are chosen per parameter where truncation and the solver's rounding
// balance (the initial height of a resting box, for one, changes its penetration: a step of 1e-5
// m already shows the curvature at 1e-3 relative).
struct Probe {
  std::string name;
  double h;  ///< difference step: relative for model parameters, absolute for initial states
};

void CheckAgainstTrajectoryDifferences(const Builder& build, const std::vector<Probe>& probes,
                                       const std::string& actor, int steps, double dt) {
  std::vector<std::string> names;
  for (const Probe& p : probes) names.push_back(p.name);
  Scene scene = build();
  const std::vector<SceneParameter> params = ParseParameters(scene, names);
  Error error;
  ForwardSensitivity sens;
  REQUIRE(sens.Begin(&scene, params, &error));
  for (int n = 0; n < steps; ++n) {
    StepReport rep;
    INFO(error.message);
    REQUIRE(sens.Step(dt, &rep, &error));
  }
  const Eigen::MatrixXd J = sens.CenterOfMassJacobian(scene.FindActor(actor));
  for (size_t j = 0; j < names.size(); ++j) {
    Scene probe = build();
    const double theta = ParameterValue(probe, params[j]);
    const double h = probes[j].h;
    const double step = params[j].IsInitialState() ? h : h * std::abs(theta);
    const Eigen::Vector3d fd = (FinalCom(build, names[j], theta + step, actor, steps, dt) -
                                FinalCom(build, names[j], theta - step, actor, steps, dt)) /
                               (2 * step);
    const double scale = fd.lpNorm<Eigen::Infinity>();
    const double err = (J.col(j) - fd).lpNorm<Eigen::Infinity>() / scale;
    INFO(names[j] << ": sensitivity " << J.col(j).transpose() << ", trajectory differences "
                  << fd.transpose() << ", relative error " << err);
    CHECK(scale > 0);
    CHECK(err < 1e-5);
  }
}

}  // namespace

TEST_CASE("Sensitivities of a sliding box match trajectory differences", "[sensitivity]") {
  // The box slides to rest within the run, so V_f matters at its end.
  const std::vector<Probe> probes = {
      {"cube.coulomb_friction_coefficient", 1e-5}, {"cube.normal_viscous_damping_coefficient", 1e-5},
      {"cube.viscous_friction_coefficient", 1e-5}, {"cube.friction_falloff_vel", 1e-5},
      {"cube.penalty_coefficient", 1e-5},          {"cube.velocity.x", 1e-6},
      {"cube.position.z", 1e-7},                   {"cube.angular_velocity.y", 1e-6}};
  SECTION("BDF2, reconstructed load") {
    CheckAgainstTrajectoryDifferences(
        [] { return SlidingBox(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad); },
        probes, "cube", 100, 2e-3);
  }
  SECTION("BackwardEuler, explicit normals") {
    CheckAgainstTrajectoryDifferences(
        [] { return SlidingBox(IntegrationMethod::BackwardEuler, DissipationMode::ExplicitNormals); },
        probes, "cube", 100, 2e-3);
  }
  SECTION("DIRK22, implicit load, slides to rest") {
    // 200 ms: the box comes to rest, its samples at V_t ≈ 0 where the friction force is only C¹;
    // the replays evaluate it about the recorded slips (core/contact/slip_tape.h). Measured: at most
    // 2.2e-6 (4.7e-4 off in the velocity direction when the exact force was differenced).
    CheckAgainstTrajectoryDifferences(
        [] { return SlidingBox(IntegrationMethod::DIRK22, DissipationMode::ImplicitLoad); },
        probes, "cube", 100, 2e-3);
  }
}

TEST_CASE("Sensitivities through a tree's link shape match trajectory differences",
          "[sensitivity][articulated][attached]") {
  // SlidingBox as a link on two sliders: its contact parameters reach the joints through the
  // reduction (core/dynamics/scene_stage.h), the articulation's centre of mass is compared.
  const std::vector<Probe> probes = {{"slider/block.coulomb_friction_coefficient", 1e-5},
                                     {"slider/block.normal_viscous_damping_coefficient", 1e-5},
                                     {"slider/block.viscous_friction_coefficient", 1e-5},
                                     {"slider/block.penalty_coefficient", 1e-5}};
  SECTION("BDF2, explicit normals") {
    CheckAgainstTrajectoryDifferences(
        [] { return SlidingLink(IntegrationMethod::BDF2, DissipationMode::ExplicitNormals); },
        probes, "slider", 100, 2e-3);
  }
  SECTION("DIRK22, reconstructed load") {
    CheckAgainstTrajectoryDifferences(
        [] { return SlidingLink(IntegrationMethod::DIRK22, DissipationMode::ReconstructedLoad); },
        probes, "slider", 100, 2e-3);
  }
  SECTION("turning on a revolute joint, BDF2, explicit normals") {
    CheckAgainstTrajectoryDifferences(
        [] { return TurningLink(IntegrationMethod::BDF2, DissipationMode::ExplicitNormals); },
        probes, "slider", 100, 2e-3);
  }
  SECTION("turning on a revolute joint, DIRK22, reconstructed load") {
    CheckAgainstTrajectoryDifferences(
        [] { return TurningLink(IntegrationMethod::DIRK22, DissipationMode::ReconstructedLoad); },
        probes, "slider", 100, 2e-3);
  }
}

TEST_CASE("Sensitivities to a link's mass and its drive's gains match trajectory differences",
          "[sensitivity][articulated]") {
  const std::vector<Probe> probes = {{"pendulum.link_mass.bob", 1e-5},
                                     {"pendulum.drive_stiffness.bob", 1e-5},
                                     {"pendulum.drive_damping.bob", 1e-5}};
  SECTION("BDF2") {
    CheckAgainstTrajectoryDifferences([] { return DrivenPendulum(IntegrationMethod::BDF2); },
                                      probes, "pendulum", 200, 2e-3);
  }
  SECTION("SymplecticDIRK22") {
    CheckAgainstTrajectoryDifferences(
        [] { return DrivenPendulum(IntegrationMethod::SymplecticDIRK22); }, probes, "pendulum",
        200, 2e-3);
  }
}

TEST_CASE("Sensitivities to a rigid body's mass match trajectory differences", "[sensitivity]") {
  // Pushed by an applied force, the box's path depends on its mass (x'' = F/m − μ g); sliding
  // under friction alone, only its resting penetration does.
  const std::vector<Probe> probes = {{"cube.mass", 1e-5}, {"cube.density", 1e-5},
                                     {"cube.coulomb_friction_coefficient", 1e-5}};
  SECTION("BDF2, reconstructed load, pushed") {
    CheckAgainstTrajectoryDifferences(
        [] { return PushedBox(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad); },
        probes, "cube", 100, 2e-3);
  }
  SECTION("DIRK22, explicit normals, sliding") {
    CheckAgainstTrajectoryDifferences(
        [] { return SlidingBox(IntegrationMethod::DIRK22, DissipationMode::ExplicitNormals); },
        {{"cube.mass", 1e-5}}, "cube", 100, 2e-3);
  }
}

TEST_CASE("Sensitivities of a bouncing box match trajectory differences", "[sensitivity]") {
  const std::vector<Probe> probes = {{"cube.normal_viscous_damping_coefficient", 1e-5},
                                     {"cube.coulomb_friction_coefficient", 1e-5},
                                     {"cube.penalty_coefficient", 1e-5},
                                     {"cube.position.z", 1e-7},
                                     {"cube.velocity.z", 1e-6}};
  SECTION("BDF2, reconstructed load") {
    CheckAgainstTrajectoryDifferences(
        [] { return BouncingBox(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad); },
        probes, "cube", 150, 1e-3);
  }
  SECTION("BDF3, explicit normals") {
    CheckAgainstTrajectoryDifferences(
        [] { return BouncingBox(IntegrationMethod::BDF3, DissipationMode::ExplicitNormals); },
        probes, "cube", 150, 1e-3);
  }
  SECTION("SymplecticDIRK22, implicit load") {
    CheckAgainstTrajectoryDifferences(
        [] { return BouncingBox(IntegrationMethod::SymplecticDIRK22, DissipationMode::ImplicitLoad); },
        probes, "cube", 150, 1e-3);
  }
}

TEST_CASE("Sensitivities of a soft cube match trajectory differences", "[sensitivity]") {
  const std::vector<Probe> probes = {{"soft.youngs_modulus", 1e-5},
                                     {"soft.density", 1e-5},
                                     {"soft.coulomb_friction_coefficient", 1e-5},
                                     {"soft.velocity.x", 1e-6},
                                     {"soft.position.z", 1e-7}};
  CheckAgainstTrajectoryDifferences([] { return SoftCube(IntegrationMethod::BDF2); }, probes,
                                    "soft", 60, 1e-3);
}

TEST_CASE("Sensitivities of a soft cube sliding to rest match trajectory differences",
          "[sensitivity]") {
  // Set down on the ground at 5 cm/s with μ = √(0.5 · 1.2): it stops sliding within about 40 ms
  // while it bounces on its own elastic mode (the centre moves ±2 mm vertically, ±1 cm/s
  // sideways), so its loaded samples cross V_t = 0 and V_f, where the friction force is only C¹;
  // the replays evaluate it about the recorded slips (core/contact/slip_tape.h). Measured: at
  // most 2.6e-7; with the soft pairs' force differenced exactly instead, 1.8e-4 (velocity.x and
  // position.x in both sections).
  const std::vector<Probe> probes = {{"soft.youngs_modulus", 1e-5},
                                     {"soft.coulomb_friction_coefficient", 1e-5},
                                     {"soft.friction_falloff_vel", 1e-5},
                                     {"soft.velocity.x", 1e-6},
                                     {"soft.position.x", 1e-7}};
  SECTION("BDF2, reconstructed load") {
    CheckAgainstTrajectoryDifferences(
        [] {
          return SoftCubeOnGround(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad,
                                  0.0499, 0.05, 1.2);
        },
        probes, "soft", 100, 1e-3);
  }
  SECTION("BackwardEuler, explicit normals") {
    CheckAgainstTrajectoryDifferences(
        [] {
          return SoftCubeOnGround(IntegrationMethod::BackwardEuler,
                                  DissipationMode::ExplicitNormals, 0.0499, 0.05, 1.2);
        },
        probes, "soft", 100, 1e-3);
  }
}

TEST_CASE("Sensitivities of a rigid box set down sliding on a soft slab match trajectory "
          "differences",
          "[sensitivity]") {
  // The box, set down at 5 cm/s with μ = √(0.5 · 1.2), sinks into the slab and rocks on it (pitch
  // rates up to 1.6 rad/s), its sideways velocity reversing twice in 0.1 s: the loaded samples
  // cross V_t = 0 and V_f repeatedly. The friction of both pair kinds with a soft actor (the
  // slab's samples on the box, and with the slab a collider the box's samples on the slab) is
  // evaluated about the recorded slips. Measured: at most 2.8e-6; without the recorded slips of the slab's samples
  // 1.1e-4 (implicit load, velocity.x), without those of the box's samples on the slab 8.6e-5
  // (position.x).
  const std::vector<Probe> probes = {{"slab.youngs_modulus", 1e-5},
                                     {"box.coulomb_friction_coefficient", 1e-5},
                                     {"box.friction_falloff_vel", 1e-5},
                                     {"box.velocity.x", 1e-6},
                                     {"box.position.x", 1e-7}};
  SECTION("BDF2, reconstructed load") {
    CheckAgainstTrajectoryDifferences(
        [] {
          return BoxOnSoftSlab(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad, 0.05,
                               1.2);
        },
        probes, "box", 100, 1e-3);
  }
  SECTION("BackwardEuler, implicit load") {
    CheckAgainstTrajectoryDifferences(
        [] {
          return BoxOnSoftSlab(IntegrationMethod::BackwardEuler, DissipationMode::ImplicitLoad,
                               0.05, 1.2);
        },
        probes, "box", 100, 1e-3);
  }
  SECTION("BDF2, reconstructed load, the slab also a collider") {
    CheckAgainstTrajectoryDifferences(
        [] {
          return BoxOnSoftSlab(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad, 0.05,
                               1.2, true);
        },
        probes, "box", 100, 1e-3);
  }
  // Not with explicit normals: their contact set and alignment decisions are taken at the stage
  // start (piecewise constant in the state), and here the trajectory differences themselves jump.
  // Measured under DIRK22, relative disagreement of the μ and V_f derivatives at difference steps
  // 1e-4, 1e-5, 3e-6, 1e-6: 5.3e-5, 7.4e-5, 8.6e-4, 5.0e-4 and 1.8e-5, 3.8e-5, 1.3e-3, 5.5e-3,
  // growing as the step shrinks (noise or a jump between θ ± h, not the sensitivity: under
  // BackwardEuler the slab's E derivative reads 1.1e-6, 1.2e-7, 1.7e-5, 3.6e-5, 1.0e-4 off at
  // steps 1e-3 … 1e-7, and without friction every derivative agrees to 2e-8).
}

TEST_CASE("Sensitivity parameters: parsing and refusals", "[sensitivity]") {
  Scene scene = SlidingBox(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad);
  SceneParameter p;
  Error error;
  CHECK_FALSE(ParseSceneParameter(scene, "nobody.density", &p, &error));
  CHECK(error.message.find("no actor named 'nobody'") != std::string::npos);
  CHECK_FALSE(ParseSceneParameter(scene, "cube.friction", &p, &error));
  CHECK(error.message.find("unknown name 'friction'") != std::string::npos);
  CHECK_FALSE(ParseSceneParameter(scene, "cube.youngs_modulus", &p, &error));
  CHECK(error.message.find("soft-actor material") != std::string::npos);
  CHECK_FALSE(ParseSceneParameter(scene, "cube.velocity", &p, &error));
  CHECK(error.message.find(".x, .y or .z") != std::string::npos);
  CHECK_FALSE(ParseSceneParameter(scene, "ground.position.x", &p, &error));
  CHECK(error.message.find("static") != std::string::npos);
  CHECK_FALSE(ParseSceneParameter(scene, "ground.mass", &p, &error));
  CHECK(error.message.find("mass is a soft or dynamic rigid actor's and 'ground' is not dynamic") !=
        std::string::npos);
  // A rigid body's density is m / V of its shape; setting it sets the mass.
  REQUIRE(ParseSceneParameter(scene, "cube.density", &p, &error));
  CHECK(ParameterValue(scene, p) == Approx(1.0 / 0.008).epsilon(1e-12));
  REQUIRE(SetParameterValue(&scene, p, 500.0, &error));
  CHECK(scene.Model(scene.FindActor("cube")).mass == Approx(4.0).epsilon(1e-12));
  CHECK_FALSE(SetParameterValue(&scene, p, -1.0, &error));
  CHECK(error.message.find("mass: must be > 0") != std::string::npos);
  REQUIRE(ParseSceneParameter(scene, "cube.coulomb_friction_coefficient", &p, &error));
  CHECK(ToString(scene, p) == "cube.coulomb_friction_coefficient");
  CHECK_FALSE(SetParameterValue(&scene, p, -0.1, &error));
  CHECK(error.message.find("coulomb_friction_coefficient") != std::string::npos);
  REQUIRE(SetParameterValue(&scene, p, 0.0, &error));
  ForwardSensitivity sens;
  CHECK_FALSE(sens.Begin(&scene, {p}, &error));
  CHECK(error.message.find("positive values only") != std::string::npos);
  // An articulated actor's link parameters: by link name, set through the scene.
  Scene tree = DrivenPendulum(IntegrationMethod::BDF2);
  REQUIRE(ParseSceneParameter(tree, "pendulum.drive_stiffness.bob", &p, &error));
  CHECK(ToString(tree, p) == "pendulum.drive_stiffness.bob");
  CHECK(ParameterValue(tree, p) == 20.0);
  REQUIRE(SetParameterValue(&tree, p, 30.0, &error));
  CHECK(ParameterValue(tree, p) == 30.0);
  CHECK_FALSE(SetParameterValue(&tree, p, -1.0, &error));
  CHECK(error.message == "link 'bob': joint_params.drive_stiffness: must be >= 0, got -1");
  REQUIRE(ParseSceneParameter(tree, "pendulum.link_mass.bob", &p, &error));
  REQUIRE(SetParameterValue(&tree, p, 2.0, &error));
  CHECK(ParameterValue(tree, p) == 2.0);
  CHECK_FALSE(ParseSceneParameter(tree, "pendulum.link_mass.arm", &p, &error));
  CHECK(error.message == "parameter 'pendulum.link_mass.arm': link_mass needs a link of "
                         "'pendulum' by name (link_mass.LINK), got 'arm'");
  CHECK_FALSE(ParseSceneParameter(scene, "cube.drive_damping.bob", &p, &error));
  CHECK(error.message == "parameter 'cube.drive_damping.bob': drive_damping is an articulated "
                         "actor's and 'cube' is not one");
}

TEST_CASE("Sensitivities do not depend on the number of threads", "[sensitivity]") {
  // Four parameters replay in parallel, each on one thread's copy of the scene.
  const std::vector<std::string> names = {"cube.coulomb_friction_coefficient",
                                          "cube.normal_viscous_damping_coefficient",
                                          "cube.viscous_friction_coefficient", "cube.velocity.x"};
  Eigen::MatrixXd jacobian[2];
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    Scene scene = SlidingBox(IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad);
    const std::vector<SceneParameter> params = ParseParameters(scene, names);
    Error error;
    ForwardSensitivity sens;
    REQUIRE(sens.Begin(&scene, params, &error));
    for (int n = 0; n < 20; ++n) REQUIRE(sens.Step(2e-3, nullptr, &error));
    jacobian[threads - 1] = sens.StateJacobian();
  }
  CHECK(jacobian[0].cwiseAbs().maxCoeff() > 0.0);
  CHECK((jacobian[0] - jacobian[1]).cwiseAbs().maxCoeff() == 0.0);
}
