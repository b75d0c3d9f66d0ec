// Fitting (scenes/fit.h): recovering μ and c_n of a thrown box from a synthetic trajectory made
// with known values, without and with 1 mm observation noise, and the input errors.
#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sys/wait.h>

#include "scenes/fit.h"

using namespace superdex;

namespace {

const char* kScene = SUPERDEX_SOURCE_DIR "/scenes/data/fit_throw.json";

// The observed run: the scene with the box at μ = 0.4, c_n = 4 s/m, centres of mass every 10
// steps (0.02 s), plus Gaussian noise of standard deviation `noise` [m] per coordinate.
ObservedTrajectory Synthetic(double mu, double cn, double noise) {
  SceneFile file;
  Error error;
  REQUIRE(LoadSceneFile(kScene, &file, &error));
  Scene& scene = *file.scene;
  SceneParameter p;
  REQUIRE(ParseSceneParameter(scene, "box.coulomb_friction_coefficient", &p, &error));
  REQUIRE(SetParameterValue(&scene, p, mu, &error));
  REQUIRE(ParseSceneParameter(scene, "box.normal_viscous_damping_coefficient", &p, &error));
  REQUIRE(SetParameterValue(&scene, p, cn, &error));
  ObservedTrajectory obs;
  obs.actors = file.actorNames;
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0.0, noise);
  const int steps = static_cast<int>(std::round(file.duration / file.dt));
  for (int n = 1; n <= steps; ++n) {
    StepReport rep;
    REQUIRE(scene.Step(file.dt, &rep, &error));
    REQUIRE(rep.status == StageStatus::Converged);
    if (n % 10) continue;
    ObservedFrame f;
    f.time = scene.Time();
    f.position.assign(obs.actors.size(), std::nullopt);
    const Eigen::Vector3d c = scene.CenterOfMass(scene.FindActor("box"));
    f.position[1] = c + (noise > 0 ? Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng))
                                   : Eigen::Vector3d::Zero());
    obs.frames.push_back(f);
  }
  return obs;
}

}  // namespace

TEST_CASE("Fitting recovers friction and normal damping from a thrown box", "[fit]") {
  SceneFile file;
  Error error;
  REQUIRE(LoadSceneFile(kScene, &file, &error));
  FitOptions options;
  options.parameters = {"box.coulomb_friction_coefficient",
                        "box.normal_viscous_damping_coefficient"};
  const double mu = 0.4, cn = 4.0;
  SECTION("exact observations: within 1%") {
    FitResult r;
    REQUIRE(FitSceneParameters(file, Synthetic(mu, cn, 0.0), options, &r, &error));
    INFO(r.message << "; fitted " << r.fitted[0] << ", " << r.fitted[1] << " from "
                   << r.initial[0] << ", " << r.initial[1]);
    CHECK(r.converged);
    CHECK(std::abs(r.fitted[0] / mu - 1) < 0.01);
    CHECK(std::abs(r.fitted[1] / cn - 1) < 0.01);
    CHECK(r.rmsResidual < 1e-5);
  }
  SECTION("1 mm noise: within three standard errors") {
    FitResult r;
    REQUIRE(FitSceneParameters(file, Synthetic(mu, cn, 1e-3), options, &r, &error));
    INFO(r.message << "; fitted " << r.fitted[0] << " ± " << r.standardError[0] << ", "
                   << r.fitted[1] << " ± " << r.standardError[1] << "; rms "
                   << r.rmsResidual);
    CHECK(r.converged);
    // The residual is the noise: rms ≈ 1 mm.
    CHECK(r.rmsResidual > 0.8e-3);
    CHECK(r.rmsResidual < 1.2e-3);
    CHECK(std::abs(r.fitted[0] - mu) < 3 * r.standardError[0]);
    CHECK(std::abs(r.fitted[1] - cn) < 3 * r.standardError[1]);
    // Measured with this seed: μ 0.4016 ± 0.0018, c_n 4.017 ± 0.056 (0.4% off each).
    CHECK(std::abs(r.fitted[0] / mu - 1) < 0.01);
    CHECK(std::abs(r.fitted[1] / cn - 1) < 0.03);
  }
}

TEST_CASE("Fitting: bad input is refused with the reason", "[fit]") {
  SceneFile file;
  Error error;
  REQUIRE(LoadSceneFile(kScene, &file, &error));
  ObservedTrajectory obs = Synthetic(0.4, 4.0, 0.0);
  FitOptions options;
  FitResult r;
  options.parameters = {"box.stiffness"};
  CHECK_FALSE(FitSceneParameters(file, obs, options, &r, &error));
  CHECK(error.message.find("unknown name 'stiffness'") != std::string::npos);
  options.parameters = {"box.coulomb_friction_coefficient"};
  ObservedTrajectory off = obs;
  off.frames[0].time += 1e-4;
  CHECK_FALSE(FitSceneParameters(file, off, options, &r, &error));
  CHECK(error.message.find("not a multiple of dt") != std::string::npos);
  ObservedTrajectory stranger = obs;
  stranger.actors[1] = "crate";
  CHECK_FALSE(FitSceneParameters(file, stranger, options, &r, &error));
  CHECK(error.message.find("'crate' is not in the scene") != std::string::npos);

  const std::string path = SUPERDEX_BINARY_DIR "/fit_bad_observed.jsonl";
  std::ofstream(path) << "{\"actors\": [{\"name\": \"ground\"}, {\"name\": \"box\"}]}\n"
                      << "{\"t\": 0.02, \"actors\": [null]}\n";
  ObservedTrajectory bad;
  CHECK_FALSE(ReadObservedTrajectory(path, &bad, &error));
  CHECK(error.message.find(":2: a frame needs \"actors\" with one entry per header actor") !=
        std::string::npos);
  CHECK_FALSE(ReadObservedTrajectory("missing.jsonl", &bad, &error));
  CHECK(error.message.find("cannot read") != std::string::npos);
}

TEST_CASE("superdex fit recovers the shipped measurement's parameters", "[fit][cli]") {
  const std::string out = SUPERDEX_BINARY_DIR "/fit_throw_fitted.json";
  const std::string fittedScene = SUPERDEX_BINARY_DIR "/fit_throw_fitted_scene.json";
  std::remove(out.c_str());
  std::remove(fittedScene.c_str());
  const std::string cmd = std::string(SUPERDEX_CLI) + " fit " + SUPERDEX_SOURCE_DIR +
                          "/scenes/data/fit_throw.json --observed " + SUPERDEX_SOURCE_DIR +
                          "/scenes/data/fit_throw_observed.jsonl --params "
                          "box.coulomb_friction_coefficient,box.normal_viscous_damping_coefficient"
                          " --out " + out + " --scene-out " + fittedScene + " > /dev/null 2>&1";
  REQUIRE(std::system(cmd.c_str()) == 0);
  std::ifstream in(out);
  REQUIRE(in);
  const nlohmann::json j = nlohmann::json::parse(in);
  CHECK(j["converged"].get<bool>());
  // --scene-out: the scene file with the fitted values.
  SceneFile fitted;
  Error error;
  REQUIRE(LoadSceneFile(fittedScene, &fitted, &error));
  const ContactParams& c = fitted.scene->GetContactParams(fitted.scene->FindActor("box"));
  CHECK(c.coulombFrictionCoefficient ==
        j["parameters"]["box.coulomb_friction_coefficient"]["fitted"].get<double>());
  CHECK(c.normalViscousDampingCoefficient ==
        j["parameters"]["box.normal_viscous_damping_coefficient"]["fitted"].get<double>());
  // The measurement was made at μ = 0.4, c_n = 4 with 1 mm noise: within 3 standard errors.
  const auto& mu = j["parameters"]["box.coulomb_friction_coefficient"];
  const auto& cn = j["parameters"]["box.normal_viscous_damping_coefficient"];
  CHECK(std::abs(mu["fitted"].get<double>() - 0.4) < 3 * mu["standard_error"].get<double>());
  CHECK(std::abs(cn["fitted"].get<double>() - 4.0) < 3 * cn["standard_error"].get<double>());
}

TEST_CASE("The adjoint cost gradient matches central differences of the cost", "[fit]") {
  // The gradient Σ_k r_k · dc_k/dθ sums 50 observations whose residuals (1 mm noise, and the
  // guess's error) partly cancel, and the box slides to rest, where the friction force is only
  // C¹ in the slip velocity (differenced about the recorded slips, core/contact/slip_tape.h). Measured
  // against differences of the cost (which agree between steps 1e-6 and 1e-5 of θ): adjoint
  // 1e-6 … 5.9e-6 relative (3e-6 … 3.1e-5 when the exact force was differenced, and then the
  // forward sensitivities' Jᵀr, what Levenberg–Marquardt uses, 2e-6 … 1.6e-5).
  SceneFile file;
  Error error;
  REQUIRE(LoadSceneFile(kScene, &file, &error));
  const ObservedTrajectory obs = Synthetic(0.4, 4.0, 1e-3);
  FitOptions options;
  options.parameters = {"box.coulomb_friction_coefficient", "box.normal_viscous_damping_coefficient",
                        "box.velocity.x", "box.angular_velocity.z"};
  TrajectoryGradient g;
  REQUIRE(ComputeTrajectoryGradient(file, obs, options, &g, &error));
  REQUIRE(g.gradient.size() == 4);
  CHECK(g.residuals == 3 * static_cast<int>(obs.frames.size()));
  for (size_t j = 0; j < options.parameters.size(); ++j) {
    SceneParameter p;
    REQUIRE(ParseSceneParameter(*file.scene, options.parameters[j], &p, &error));
    const double theta = g.values[j];
    const double h = p.IsInitialState() ? 1e-6 : 1e-5 * theta;
    double cost[2];
    for (int k = 0; k < 2; ++k) {
      SceneFile moved;
      REQUIRE(LoadSceneFile(kScene, &moved, &error));
      REQUIRE(SetParameterValue(moved.scene.get(), p, theta + (k ? -h : h), &error));
      TrajectoryGradient at;
      REQUIRE(ComputeTrajectoryGradient(moved, obs, options, &at, &error));
      cost[k] = at.cost;
    }
    const double fd = (cost[0] - cost[1]) / (2 * h);
    INFO(options.parameters[j] << ": adjoint " << g.gradient[j] << ", differences " << fd);
    CHECK(std::abs(g.gradient[j] - fd) < 1e-4 * std::abs(fd));
  }
}

TEST_CASE("Fitting by L-BFGS with adjoint gradients recovers friction and normal damping",
          "[fit]") {
  SceneFile file;
  Error error;
  REQUIRE(LoadSceneFile(kScene, &file, &error));
  FitOptions options;
  options.parameters = {"box.coulomb_friction_coefficient",
                        "box.normal_viscous_damping_coefficient"};
  options.method = FitMethod::Lbfgs;
  options.maxIterations = 100;
  FitResult r;
  REQUIRE(FitSceneParameters(file, Synthetic(0.4, 4.0, 0.0), options, &r, &error));
  INFO(r.message << "; fitted " << r.fitted[0] << ", " << r.fitted[1] << " from " << r.initial[0]
                 << ", " << r.initial[1] << " in " << r.iterations << " iterations");
  CHECK(r.converged);
  CHECK(std::abs(r.fitted[0] / 0.4 - 1) < 0.01);
  CHECK(std::abs(r.fitted[1] / 4.0 - 1) < 0.01);
  CHECK(std::isnan(r.standardError[0]));
  FitMethod m;
  CHECK(ParseFitMethod("lbfgs", &m));
  CHECK(m == FitMethod::Lbfgs);
  CHECK_FALSE(ParseFitMethod("newton", &m));
}

TEST_CASE("superdex gradient prints the cost gradient; fit --method is validated", "[fit][cli]") {
  const std::string base = std::string(SUPERDEX_CLI);
  const std::string input = std::string(" ") + SUPERDEX_SOURCE_DIR +
                            "/scenes/data/fit_throw.json --observed " + SUPERDEX_SOURCE_DIR +
                            "/scenes/data/fit_throw_observed.jsonl --params "
                            "box.coulomb_friction_coefficient,box.velocity.x";
  const std::string out = SUPERDEX_BINARY_DIR "/gradient_out.txt";
  REQUIRE(std::system((base + " gradient" + input + " > " + out + " 2>&1").c_str()) == 0);
  std::ifstream in(out);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text.find("box.coulomb_friction_coefficient") != std::string::npos);
  CHECK(text.find("adjoint pass") != std::string::npos);
  const int status = std::system((base + " fit" + input + " --method newton > /dev/null 2>&1").c_str());
  CHECK(WEXITSTATUS(status) == 2);
}
