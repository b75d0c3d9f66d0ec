// Cost of trajectory sensitivities against the forward simulation they differentiate.
//   superdex_bench_sensitivity
// For 1000-step trajectories (the thrown box of scenes/data/fit_throw.json at dt = 4e-4 s, and a
// 2 × 2 × 2-cell soft cube dropped on the ground at dt = 1e-3 s), prints the wall time of the
// plain simulation and of the simulation carrying dS/dθ for P = 1, 2 and 5 parameters, and the
// ratio (gradient cost / forward cost).
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "core/sensitivity.h"
#include "scenes/scene_file.h"

using namespace superdex;

namespace {

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Runs `steps` steps of a copy of `base`, carrying sensitivities for `names` (none: plain).
double Run(const Scene& base, const std::vector<std::string>& names, double dt, int steps,
           double* tangentShare) {
  Scene scene = base;
  Error error;
  std::vector<SceneParameter> params(names.size());
  for (size_t j = 0; j < names.size(); ++j)
    if (!ParseSceneParameter(scene, names[j], &params[j], &error)) {
      std::fprintf(stderr, "%s\n", error.message.c_str());
      std::exit(2);
    }
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

void Table(const char* title, const Scene& base, double dt, const std::vector<std::string>& all) {
  const int steps = 1000;
  std::printf("\n%s: %d steps of %g s\n", title, steps, dt);
  std::printf("| parameters | wall s | ratio to forward | share in replays |\n|---|---|---|---|\n");
  const double forward = Run(base, {}, dt, steps, nullptr);
  std::printf("| 0 (forward) | %.3f | 1 | - |\n", forward);
  for (size_t P : {size_t(1), size_t(2), all.size()}) {
    std::vector<std::string> names(all.begin(), all.begin() + P);
    double share = 0.0;
    const double wall = Run(base, names, dt, steps, &share);
    std::printf("| %zu | %.3f | %.1f | %.0f%% |\n", P, wall, wall / forward, 100 * share);
  }
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
  RigidActorDesc ground;
  ground.name = "ground";
  ground.dynamic = false;
  ground.shape.kind = RigidShapeKind::Plane;
  ground.contact.penaltyCoefficient = 1e7;
  ground.contact.normalViscousDampingCoefficient = 1.0;
  soft.AddRigidActor(ground, &error);
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
  return 0;
}
