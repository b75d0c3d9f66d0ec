// Cost of one step against the number of active contact samples.
//   superdex_bench_scaling [--quick]
// Scenes, all built in contact (no free fall), BDF2, Δt = 1e-2, default contact parameters:
//   spheres N   N spheres (r = 0.05 m, 1 kg) on a cubic lattice in a box-shaped heap, each
//               pressed 0.5 mm into its neighbours and the lowest layer into the ground
//   tori 200    200 non-convex tori (R = 0.1 m, r = 0.03 m, mesh shapes, Sdf colliders) in
//               stacks of two, each resting 0.5 mm into the one below or the ground
// SUPERDEX_EXPLICIT_NORMALS=1 runs the explicit-normals mode (exact potential, Cholesky);
// SUPERDEX_LINEAR_SOLVER=direct|iterative|auto sets the linear solver (default auto).
// Columns: steps timed (after one warm-up step), wall seconds per step, Newton iterations per
// step, active samples (penalty) at the end, and microseconds per active sample per Newton
// iteration: the figure that should stay flat if the cost is linear in the active samples; and
// the wall-time shares of assembly, linear solves and line search.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "core/scene.h"

using namespace superdex;

namespace {

std::shared_ptr<TriangleMesh> Torus(double R, double r, int nu, int nv) {
  auto m = std::make_shared<TriangleMesh>();
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      m->vertices.emplace_back((R + r * std::cos(v)) * std::cos(u),
                               (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m->faces.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      m->faces.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return m;
}

void Measure(const char* name, Scene& scene, int steps) {
  Error e;
  StepReport r;
  if (!scene.Step(1e-2, &r, &e)) {  // warm-up
    std::fprintf(stderr, "error: %s\n", e.message.c_str());
    return;
  }
  long newton = 0;
  int failed = 0;
  double assembly = 0, solve = 0, search = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) {
    scene.Step(1e-2, &r, &e);
    newton += r.newtonIterations;
    failed += r.status != StageStatus::Converged;
    assembly += r.assemblySeconds;
    solve += r.factorizationSeconds;
    search += r.lineSearchSeconds;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const int active = r.contact.activeSamples;
  std::printf("%-12s %7d %6d %12.4g %10.2f %10d %16.3f %5d   %3.0f/%3.0f/%3.0f\n", name,
              scene.NumActors(), steps, wall / steps, double(newton) / steps, active,
              1e6 * wall / std::max(1L, newton) / std::max(1, active), failed,
              100 * assembly / wall, 100 * solve / wall, 100 * search / wall);
  std::fflush(stdout);
}

SceneSettings Settings() {
  SceneSettings s;
  if (std::getenv("SUPERDEX_EXPLICIT_NORMALS")) s.eval.explicitNormals = true;
  if (const char* kind = std::getenv("SUPERDEX_LINEAR_SOLVER")) {
    if (!ParseLinearSolverKind(kind, &s.solver.linear.kind)) {
      std::fprintf(stderr, "SUPERDEX_LINEAR_SOLVER: must be auto, direct or iterative, got %s\n",
                   kind);
      std::exit(2);
    }
  }
  return s;
}

// A scene of Settings() with a static ground plane.
std::unique_ptr<Scene> SceneOnGround() {
  auto scene = std::make_unique<Scene>(Settings());
  Error e;
  RigidActorDesc ground;
  ground.name = "ground";
  ground.dynamic = false;
  ground.shape.kind = RigidShapeKind::Plane;
  scene->AddRigidActor(ground, &e);
  return scene;
}

std::unique_ptr<Scene> Spheres(int n) {
  auto scene = SceneOnGround();
  Error e;
  const int side = static_cast<int>(std::ceil(std::sqrt(n / 10.0)));
  const double r = 0.05, pitch = 2 * r - 5e-4;
  for (int k = 0; k < n; ++k) {
    const int layer = k / (side * side), i = k % side, j = (k / side) % side;
    RigidActorDesc d;
    d.name = "s" + std::to_string(k);
    d.shape.kind = RigidShapeKind::Sphere;
    d.shape.radius = r;
    d.shape.surfaceResolution = 2;
    d.mass = 1.0;
    d.position = Eigen::Vector3d(i * pitch, j * pitch, r - 5e-4 + layer * pitch);
    scene->AddRigidActor(d, &e);
  }
  return scene;
}

std::unique_ptr<Scene> Tori(int n) {
  auto scene = SceneOnGround();
  Error e;
  auto mesh = Torus(0.1, 0.03, 32, 12);
  const int side = static_cast<int>(std::ceil(std::sqrt(n / 2.0)));
  for (int k = 0; k < n; ++k) {
    const int level = k % 2, cell = k / 2;
    RigidActorDesc d;
    d.name = "t" + std::to_string(k);
    d.shape.kind = RigidShapeKind::Mesh;
    d.shape.mesh = mesh;
    d.mass = 0.5;
    d.colliderType = ColliderType::Sdf;
    d.position = Eigen::Vector3d((cell % side) * 0.3, (cell / side) * 0.3,
                                0.03 - 5e-4 + level * (0.06 - 5e-4));
    if (!scene->AddRigidActor(d, &e).IsValid()) std::fprintf(stderr, "error: %s\n", e.message.c_str());
  }
  return scene;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  std::printf("%-12s %7s %6s %12s %10s %10s %16s %5s   %s\n", "scene", "actors", "steps",
              "wall/step s", "Newton/st", "active", "us/sample/iter", "fail",
              "assembly/solve/line search %");
  Measure("spheres", *Spheres(1000), quick ? 1 : 3);
  if (!quick) Measure("spheres", *Spheres(4000), 2);
  Measure("tori (Sdf)", *Tori(200), quick ? 1 : 3);
  return 0;
}
