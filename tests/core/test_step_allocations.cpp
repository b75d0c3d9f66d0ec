// Scene::Step allocates nothing once a step has run: its buffers, the stage problem's workspace
// and the Newton solvers' workspaces are kept from step to step (core/scene.h StepBuffers,
// core/dynamics/scene_stage.h StageWorkspace, optim/newton_solver.h NewtonWorkspace).
//
// Counted by interposing glibc's allocation functions in this test executable (operator new and
// Eigen both end in malloc); elsewhere, and under AddressSanitizer (which owns malloc and calls
// it before this file's statics exist), the count is skipped with a warning.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstddef>

#include "core/scene.h"
#include "scene_builders.h"

#if defined(__SANITIZE_ADDRESS__)
#define SUPERDEX_COUNT_ALLOCATIONS 0
#elif defined(__GLIBC__)
#define SUPERDEX_COUNT_ALLOCATIONS 1
#else
#define SUPERDEX_COUNT_ALLOCATIONS 0
#endif

#if SUPERDEX_COUNT_ALLOCATIONS
#include <cerrno>

extern "C" {
void* __libc_malloc(size_t size);
void* __libc_calloc(size_t count, size_t size);
void* __libc_realloc(void* p, size_t size);
void* __libc_memalign(size_t alignment, size_t size);
}

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
void Count() {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

extern "C" {
void* malloc(size_t size) {
  Count();
  return __libc_malloc(size);
}
void* calloc(size_t count, size_t size) {
  Count();
  return __libc_calloc(count, size);
}
void* realloc(void* p, size_t size) {
  Count();
  return __libc_realloc(p, size);
}
void* memalign(size_t alignment, size_t size) {
  Count();
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(size_t alignment, size_t size) {
  Count();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, size_t alignment, size_t size) {
  Count();
  void* p = __libc_memalign(alignment, size);
  if (!p) return ENOMEM;
  *out = p;
  return 0;
}
}
#endif

using namespace superdex;

namespace {

// Allocations during `steps` steps of dt, after `warmup` steps that size every buffer; the last
// step's report in *last (if given).
long AllocationsPerRun(Scene& scene, double dt, int warmup, int steps, StepReport* last = nullptr) {
  Error e;
  StepReport report;
  for (int k = 0; k < warmup; ++k) REQUIRE(scene.Step(dt, &report, &e));
#if SUPERDEX_COUNT_ALLOCATIONS
  allocations = 0;
  counting = true;
#else
  WARN("allocations are not counted in this build (not glibc, or AddressSanitizer)");
#endif
  bool ok = true;
  for (int k = 0; k < steps && ok; ++k) ok = scene.Step(dt, &report, &e);
#if SUPERDEX_COUNT_ALLOCATIONS
  counting = false;
#endif
  if (last) *last = report;
  REQUIRE(ok);
  CHECK(report.status == StageStatus::Converged);
#if SUPERDEX_COUNT_ALLOCATIONS
  return allocations.load();
#else
  return 0;
#endif
}

// A μ = 0.5 cube over the ground at `position`, moving at `velocity`.
Scene CubeOverGround(const SceneSettings& settings, const Eigen::Vector3d& position,
                     const Eigen::Vector3d& velocity) {
  Scene scene(settings);
  Error e;
  const RigidActorDesc ground = test::Ground(Eigen::Vector3d::UnitZ(), 1e9, 0.5, 1.0);
  REQUIRE(scene.AddRigidActor(ground, &e).IsValid());
  RigidActorDesc box = test::Cube(1e9, 0.5, 1.0);
  box.position = position;
  box.linearVelocity = velocity;
  REQUIRE(scene.AddRigidActor(box, &e).IsValid());
  return scene;
}

}  // namespace

TEST_CASE("A rigid step allocates nothing once its buffers are sized", "[core][performance]") {
#if !defined(__GLIBC__)
  SKIP("allocation counting needs glibc");
#endif
  for (IntegrationMethod method :
       {IntegrationMethod::BackwardEuler, IntegrationMethod::BDF2, IntegrationMethod::DIRK33,
        IntegrationMethod::SymplecticDIRK22}) {
    DYNAMIC_SECTION(ToString(method) << ", a box in free flight above the ground") {
      SceneSettings settings;
      settings.integrator = method;
      Scene scene = CubeOverGround(settings, {0, 0, 100}, {1.0, -0.5, 2.0});
      CHECK(AllocationsPerRun(scene, 1e-3, 3, 20) == 0);
    }
  }
}

TEST_CASE("A step of a box sliding on the ground allocates nothing", "[core][performance]") {
#if !defined(__GLIBC__)
  SKIP("allocation counting needs glibc");
#endif
  for (bool explicitNormals : {false, true}) {
    DYNAMIC_SECTION((explicitNormals ? "explicit normals" : "reconstructed load")) {
      SceneSettings settings;
      settings.eval.explicitNormals = explicitNormals;
      Scene scene = CubeOverGround(settings, {0, 0, 0.1}, {0.3, 0, 0});  // lands and slides
      // The warm-up sizes the buffers; the contact's stencils then keep the matrices' structure
      // (optim/triplet_assembly.h), and the solver workspaces their sizes.
      CHECK(AllocationsPerRun(scene, 1e-3, 10, 20) == 0);
    }
  }
}

TEST_CASE("A sphere in free flight keeps its matrix structure and allocates nothing",
          "[core][performance]") {
#if !defined(__GLIBC__)
  SKIP("allocation counting needs glibc");
#endif
  // The shipped drop's ball after its first bounce: a round-off spin, whose rotation-block
  // entries are exact zeros at one stage and round-off at the next. The assembly keeps the
  // whole rotation block in its pattern (core/dynamics/scene_stage.cpp), so no stage rebuilds it. (Newton
  // on every stage: with the closed-form free stage a flight stage forms no matrix at all.)
  for (IntegrationMethod method : {IntegrationMethod::BDF2, IntegrationMethod::SymplecticDIRK22}) {
    DYNAMIC_SECTION(ToString(method)) {
      SceneSettings settings;
      settings.integrator = method;
      settings.closedFormFreeStages = false;
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::StaticGround(), &e).IsValid());
      RigidActorDesc ball = test::Ball(0.1, 0.0);
      ball.position = {0, 0, 1.1};
      ball.linearVelocity = {0, 0, 4.4};
      ball.angularVelocity = {4.463446836372748e-16, -9.34621706318406e-16, -4.58e-36};
      REQUIRE(scene.AddRigidActor(ball, &e).IsValid());
      CHECK(AllocationsPerRun(scene, 2e-3, 3, 200) == 0);
    }
  }
}

TEST_CASE("A step on the Krylov path allocates nothing once its buffers are sized",
          "[core][performance]") {
#if !defined(__GLIBC__)
  SKIP("allocation counting needs glibc");
#endif
  // Nine boxes (54 unknowns: above the dense solvers' 48) landing and sliding on the ground with
  // the Krylov solvers forced: conjugate gradients (explicit normals, a potential) and BiCGSTAB
  // (the reconstructed load's unsymmetric Jacobian), block-Jacobi preconditioned.
  for (bool explicitNormals : {false, true}) {
    DYNAMIC_SECTION((explicitNormals ? "conjugate gradients" : "BiCGSTAB")) {
      SceneSettings settings;
      settings.eval.explicitNormals = explicitNormals;
      settings.solver.linear.kind = LinearSolverKind::Iterative;
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::Ground(Eigen::Vector3d::UnitZ(), 1e9, 0.5, 1.0), &e)
                  .IsValid());
      for (int i = 0; i < 9; ++i) {
        RigidActorDesc box = test::Cube(1e9, 0.5, 1.0);
        box.name = "cube" + std::to_string(i);
        box.position = {0.5 * (i % 3), 0.5 * (i / 3), 0.1};
        box.linearVelocity = {0.3, 0.1 * (i % 2), 0};
        REQUIRE(scene.AddRigidActor(box, &e).IsValid());
      }
      StepReport last;
      CHECK(AllocationsPerRun(scene, 1e-3, 10, 20, &last) == 0);
      CHECK(last.krylovIterations > 0);  // the steps did take the Krylov path
    }
  }
}
