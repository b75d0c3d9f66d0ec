// What the generic actor layer costs: the same heap of rigid spheres as built-in rigid actors and
// as rigid kinds (core/model/rigid_kind.h), which the stage, the integrators and the one contact
// assembler carry without knowing them.
//   superdex_bench_kinds [--quick | --only built-in|kinds N]
// (--only: one layer at N³ spheres, for profiling it.)
// Scene: n³ spheres (r = 0.05 m, 1 kg, surface resolution 2) on a cubic lattice, each pressed
// 0.5 mm into its neighbours and the lowest layer into a static ground, BDF2, Δt = 1e-2, default
// contact parameters (friction 0.5), every stage solved by Newton from the last state (no warm
// start, no closed-form free stages) in both, so that both solve the same stages.
// Columns: spheres, layer, wall seconds per step, Newton iterations per step, active samples at
// the end, the kinds' time over the built-in time, and the largest difference of the sphere
// centres between the two runs [m].
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "core/model/rigid_kind.h"
#include "core/scene.h"

using namespace superdex;

namespace {

struct Run {
  double secondsPerStep = 0.0;
  double newtonPerStep = 0.0;
  int active = 0;
  std::vector<Eigen::Vector3d> centres;
};

Run Measure(int n, bool kinds, int steps) {
  SceneSettings s;
  s.warmStart = false;
  s.closedFormFreeStages = false;
  Scene scene(s);
  Error e;
  RigidActorDesc ground;
  ground.name = "ground";
  ground.dynamic = false;
  ground.shape.kind = RigidShapeKind::Plane;
  std::vector<ActorHandle> spheres;
  auto add = [&](const RigidActorDesc& d) {
    if (!kinds) return scene.AddRigidActor(d, &e);
    return scene.AddActor(RigidKind::Build(d, &e), &e, d.contactLayer);
  };
  if (!add(ground).IsValid()) std::fprintf(stderr, "error: %s\n", e.message.c_str());
  const double r = 0.05, pitch = 2 * r - 5e-4;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        RigidActorDesc d;
        d.name = "s" + std::to_string(spheres.size());
        d.shape.radius = r;
        d.shape.surfaceResolution = 2;
        d.mass = 1.0;
        d.position = Eigen::Vector3d(i * pitch, j * pitch, r - 5e-4 + k * pitch);
        spheres.push_back(add(d));
      }
  Run run;
  StepReport rep;
  long newton = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int step = 0; step < steps; ++step) {
    if (!scene.Step(1e-2, &rep, &e)) std::fprintf(stderr, "error: %s\n", e.message.c_str());
    newton += rep.newtonIterations;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  run.secondsPerStep = wall / steps;
  run.newtonPerStep = double(newton) / steps;
  run.active = rep.contact.activeSamples;
  for (ActorHandle h : spheres) run.centres.push_back(scene.CenterOfMass(h));
  return run;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const int steps = quick ? 5 : 20;
  if (argc > 3 && std::strcmp(argv[1], "--only") == 0) {
    const bool kinds = std::strcmp(argv[2], "kinds") == 0;
    const int n = std::atoi(argv[3]);
    const Run run = Measure(n, kinds, steps);
    std::printf("%8d %-9s %12.4g %10.2f %8d\n", n * n * n, kinds ? "kinds" : "built-in",
                run.secondsPerStep, run.newtonPerStep, run.active);
    return 0;
  }
  std::printf("%8s %-9s %12s %10s %8s %12s %12s\n", "spheres", "layer", "s/step", "newton/st",
              "active", "kinds/built", "max |Δx| [m]");
  for (int n : quick ? std::vector<int>{2, 3} : std::vector<int>{2, 3, 4}) {
    const Run built = Measure(n, false, steps);
    const Run kinds = Measure(n, true, steps);
    double diff = 0.0;
    for (size_t i = 0; i < built.centres.size(); ++i)
      diff = std::max(diff, (built.centres[i] - kinds.centres[i]).norm());
    std::printf("%8d %-9s %12.4g %10.2f %8d %12s %12s\n", n * n * n, "built-in",
                built.secondsPerStep, built.newtonPerStep, built.active, "", "");
    std::printf("%8d %-9s %12.4g %10.2f %8d %12.2f %12.2e\n", n * n * n, "kinds",
                kinds.secondsPerStep, kinds.newtonPerStep, kinds.active,
                kinds.secondsPerStep / built.secondsPerStep, diff);
    std::fflush(stdout);
  }
  return 0;
}
