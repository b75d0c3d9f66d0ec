// Cost of trajectory gradients against the forward simulation they differentiate.
//   superdex_bench_sensitivity
// For 1000-step trajectories (the thrown box of scenes/data/fit_throw.json at dt = 4e-4 s, a
// 2 × 2 × 2-cell soft cube dropped on the ground at dt = 1e-3 s, and 16 boxes sliding on the
// ground at dt = 2e-3 s), prints the wall time of the plain simulation, of the simulation carrying
// dS/dθ for P parameters (forward sensitivities, core/sensitivity/sensitivity.h), and of the gradient of a
// loss over the whole trajectory for all P at once (adjoint, core/sensitivity/adjoint.h: the run with its
// checkpoints plus the backward pass), with the ratio to the plain simulation.
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "core/sensitivity/adjoint.h"
#include "core/sensitivity/sensitivity.h"
#include "scenes/scene_file.h"

using namespace superdex;

namespace {

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The named parameters of the scene; exits with the message on an unknown one.
std::vector<SceneParameter> ParseOrExit(const Scene& scene, const std::vector<std::string>& names) {
  std::vector<SceneParameter> params(names.size());
  Error error;
  for (size_t j = 0; j < names.size(); ++j)
    if (!ParseSceneParameter(scene, names[j], &params[j], &error)) {
      std::fprintf(stderr, "%s\n", error.message.c_str());
      std::exit(2);
    }
  return params;
}

// Runs `steps` steps of a copy of `base`, carrying sensitivities for `names` (none: plain).
double Run(const Scene& base, const std::vector<std::string>& names, double dt, int steps,
           double* tangentShare) {
  Scene scene = base;
  Error error;
  const std::vector<SceneParameter> params = ParseOrExit(scene, names);
  ForwardSensitivity sens;
  const auto t0 = std::chrono::steady_clock::now();
  if (!names.empty() && !sens.Begin(&scene, params, &error)) {
    std::fprintf(stderr, "%s\n", error.message.c_str());
    std::exit(2);
  }
  for (int n = 0; n < steps; ++n) {
    StepReport rep;
    const bool ok = names.empty() ? scene.Step(dt, &rep, &error) : sens.Step(dt, &rep, &error);
    if (!ok || rep.status != StageStatus::Converged) {
      std::fprintf(stderr, "step %d failed: %s\n", n, error.message.c_str());
      std::exit(3);
    }
  }
  const double wall = Seconds(t0);
  if (tangentShare) *tangentShare = names.empty() ? 0.0 : sens.TangentSeconds() / wall;
  return wall;
}

// The adjoint gradient of L = Σ_n Σ_a c_a(S_n)·(1, 1, 1) for `names`; wall seconds of Run +
// Gradient.
double Adjoint(const Scene& base, const std::vector<std::string>& names, double dt, int steps,
               int* colors, double* runsPerStep) {
  Scene scene = base;
  Error error;
  const std::vector<SceneParameter> params = ParseOrExit(scene, names);
  std::vector<Eigen::SparseMatrix<double>> com;
  for (int a = 0; a < scene.NumActors(); ++a) com.push_back(CenterOfMassMap(scene, {a}));
  AdjointSensitivity adjoint;
  Eigen::VectorXd g;
  const auto t0 = std::chrono::steady_clock::now();
  const bool ok =
      adjoint.Run(&scene, std::vector<double>(steps, dt), nullptr, &error) &&
      adjoint.Gradient(params, [&](int, Scene&, Eigen::VectorXd* dL) {
        for (const auto& C : com) *dL += C.transpose() * Eigen::Vector3d::Ones();
      }, &g, &error);
  if (!ok) {
    std::fprintf(stderr, "adjoint: %s\n", error.message.c_str());
    std::exit(3);
  }
  *colors = adjoint.MaxColors();
  *runsPerStep = double(adjoint.InjectRuns()) / steps;
  return Seconds(t0);
}

void Table(const char* title, const Scene& base, double dt, const std::vector<std::string>& all,
           int steps = 1000) {
  std::printf("\n%s: %d steps of %g s\n", title, steps, dt);
  std::printf("| gradient | parameters | wall s | ratio to forward | share in replays |\n"
              "|---|---|---|---|---|\n");
  const double forward = Run(base, {}, dt, steps, nullptr);
  std::printf("| none (forward simulation) | 0 | %.3f | 1 | - |\n", forward);
  std::vector<size_t> counts = {1, 2, all.size()};
  if (all.size() > 8) counts = {1, 8, all.size()};
  for (size_t P : counts) {
    std::vector<std::string> names(all.begin(), all.begin() + P);
    double share = 0.0;
    const double wall = Run(base, names, dt, steps, &share);
    std::printf("| forward sensitivities | %zu | %.3f | %.1f | %.0f%% |\n", P, wall,
                wall / forward, 100 * share);
  }
  int colors = 0;
  double runs = 0.0;
  const double wall = Adjoint(base, all, dt, steps, &colors, &runs);
  std::printf("| adjoint (%d colours, %.0f residual runs per step) | %zu | %.3f | %.1f | - |\n",
              colors, runs, all.size(), wall, wall / forward);
}

// A static ground plane z <= 0 (k = 1e7 Pa/m, μ = 0.5, c_n = 1 s/m).
RigidActorDesc Ground() {
  RigidActorDesc ground;
  ground.name = "ground";
  ground.dynamic = false;
  ground.shape.kind = RigidShapeKind::Plane;
  ground.contact.penaltyCoefficient = 1e7;
  ground.contact.coulombFrictionCoefficient = 0.5;
  ground.contact.normalViscousDampingCoefficient = 1.0;
  return ground;
}

// 16 boxes (0.2 m, 1 kg, μ = 0.5, c_n = 1 s/m) on a 4 × 4 grid of pitch 0.5 m, resting 0.5 mm
// into the ground and sliding in different directions at up to 1 m/s.
Scene SlidingBoxes(std::vector<std::string>* parameters) {
  SceneSettings settings;
  Scene scene(settings);
  Error error;
  scene.AddRigidActor(Ground(), &error);
  for (int k = 0; k < 16; ++k) {
    RigidActorDesc d;
    d.name = "b" + std::to_string(k);
    d.shape.kind = RigidShapeKind::Box;
    d.shape.halfExtents = Eigen::Vector3d::Constant(0.1);
    d.shape.surfaceResolution = 2;
    d.mass = 1.0;
    d.contact.penaltyCoefficient = 1e7;
    d.contact.coulombFrictionCoefficient = 0.5;
    d.contact.normalViscousDampingCoefficient = 1.0;
    d.position = Eigen::Vector3d(0.5 * (k % 4), 0.5 * (k / 4), 0.1 - 5e-4);
    const double angle = 0.4 * k;
    d.linearVelocity = (0.3 + 0.05 * k) * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0);
    if (!scene.AddRigidActor(d, &error).IsValid()) {
      std::fprintf(stderr, "%s\n", error.message.c_str());
      std::exit(2);
    }
    for (const char* n : {"coulomb_friction_coefficient", "normal_viscous_damping_coefficient",
                          "position.x", "position.y", "velocity.x", "velocity.y"})
      parameters->push_back(d.name + "." + n);
  }
  return scene;
}

}  // namespace

int main() {
  SceneFile file;
  Error error;
  if (!LoadSceneFile(SUPERDEX_SOURCE_DIR "/scenes/data/fit_throw.json", &file, &error)) {
    std::fprintf(stderr, "%s\n", error.message.c_str());
    return 2;
  }
  Table("thrown box (rigid, BDF2, reconstructed load)", *file.scene, 4e-4,
        {"box.coulomb_friction_coefficient", "box.normal_viscous_damping_coefficient",
         "box.penalty_coefficient", "box.velocity.x", "box.position.z"});

  SceneSettings settings;
  Scene soft(settings);
  soft.AddRigidActor(Ground(), &error);
  SoftActorDesc d;
  d.name = "soft";
  d.mesh = std::make_shared<TetMesh>(
      MakeTetBox(Eigen::Vector3d::Constant(0.05), Eigen::Vector3i::Constant(2)));
  d.position = Eigen::Vector3d(0, 0, 0.06);
  d.linearVelocity = Eigen::Vector3d(0.3, 0, 0);
  d.material.youngsModulus = 1e5;
  d.material.poissonRatio = 0.3;
  d.contact.penaltyCoefficient = 1e7;
  d.contact.normalViscousDampingCoefficient = 1.0;
  if (!soft.AddSoftActor(d, &error).IsValid()) {
    std::fprintf(stderr, "%s\n", error.message.c_str());
    return 2;
  }
  Table("soft cube (27 nodes, BDF2, reconstructed load)", soft, 1e-3,
        {"soft.youngs_modulus", "soft.coulomb_friction_coefficient", "soft.density",
         "soft.velocity.x", "soft.position.z"});
  std::vector<std::string> boxParameters;
  const Scene boxes = SlidingBoxes(&boxParameters);
  Table("16 sliding boxes (BDF2, reconstructed load)", boxes, 2e-3, boxParameters);
  return 0;
}
