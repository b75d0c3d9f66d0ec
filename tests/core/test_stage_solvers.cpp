// Independent checks of the stage solver: the same stages of real scenes solved by superdex's
// Newton, by Ipopt (potential stages) and by Ceres (any stage) must end at the same positions.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/scene.h"

using namespace superdex;

namespace {

enum class Setup { SlidingBox, BouncingBox };

std::unique_ptr<Scene> Build(Setup setup, const ExperimentalEvalParams& eval) {
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BDF2;
  settings.eval = eval;
  auto scene = std::make_unique<Scene>(settings);
  Error e;
  RigidActorDesc ground;
  ground.name = "ground";
  ground.dynamic = false;
  ground.shape.kind = RigidShapeKind::Plane;
  ground.contact.penaltyCoefficient = 1e6;
  ground.contact.normalViscousDampingCoefficient = 0.5;
  REQUIRE(scene->AddRigidActor(ground, &e).IsValid());
  RigidActorDesc box;
  box.name = "box";
  box.shape.kind = RigidShapeKind::Box;
  box.shape.halfExtents = Eigen::Vector3d(0.1, 0.08, 0.06);
  box.shape.surfaceResolution = 2;
  box.mass = 1.3;
  box.contact.penaltyCoefficient = 1e6;
  box.contact.normalViscousDampingCoefficient = 0.5;
  box.contact.viscousFrictionCoefficient = 0.2;
  if (setup == Setup::SlidingBox) {
    box.position = Eigen::Vector3d(0, 0, 0.06 - 0.004);
    box.linearVelocity = Eigen::Vector3d(1.5, 0.4, 0);
    box.angularVelocity = Eigen::Vector3d(0, 0, 2.0);
  } else {
    box.position = Eigen::Vector3d(0, 0, 0.2);
    box.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 1, 0).normalized()));
    box.linearVelocity = Eigen::Vector3d(0.3, 0, -2.0);
  }
  REQUIRE(scene->AddRigidActor(box, &e).IsValid());
  return scene;
}

Eigen::Vector3d Run(Setup setup, const ExperimentalEvalParams& eval, StageSolverKind solver,
                    int steps) {
  auto scene = Build(setup, eval);
  Error e;
  REQUIRE(scene->SetStageSolver(solver, &e));
  for (int i = 0; i < steps; ++i) {
    StepReport r;
    REQUIRE(scene->Step(2e-3, &r, &e));
    INFO(ToString(solver) << " step " << i << ": " << r.message);
    REQUIRE(r.status == StageStatus::Converged);
  }
  return scene->State(ActorHandle{1}).p;
}

}  // namespace

TEST_CASE("Newton, Ipopt and Ceres solve the same stages to the same end positions",
          "[core][solvers][dissipation]") {
  for (Setup setup : {Setup::SlidingBox, Setup::BouncingBox}) {
    const char* name = setup == Setup::SlidingBox ? "sliding box" : "bouncing box";
    const int steps = setup == Setup::SlidingBox ? 100 : 150;  // the bounce: impact and rebound
    SECTION(std::string(name) + ", explicit normals (a potential): Newton, Ipopt, Ceres") {
      ExperimentalEvalParams eval;
      eval.explicitNormals = true;
      const Eigen::Vector3d newton = Run(setup, eval, StageSolverKind::Newton, steps);
      const Eigen::Vector3d ipopt = Run(setup, eval, StageSolverKind::Ipopt, steps);
      const Eigen::Vector3d ceres = Run(setup, eval, StageSolverKind::Ceres, steps);
      INFO("newton " << newton.transpose() << "\nipopt  " << ipopt.transpose() << "\nceres  "
                     << ceres.transpose());
      WARN("relative differences: ipopt " << (ipopt - newton).norm() / newton.norm() << ", ceres " << (ceres - newton).norm() / newton.norm());
      CHECK((ipopt - newton).norm() <= 1e-8 * newton.norm());
      CHECK((ceres - newton).norm() <= 1e-8 * newton.norm());
    }
    SECTION(std::string(name) + ", reconstructed load (residual): Newton, Ceres") {
      const ExperimentalEvalParams eval;
      const Eigen::Vector3d newton = Run(setup, eval, StageSolverKind::Newton, steps);
      const Eigen::Vector3d ceres = Run(setup, eval, StageSolverKind::Ceres, steps);
      INFO("newton " << newton.transpose() << "\nceres  " << ceres.transpose());
      WARN("relative difference: ceres " << (ceres - newton).norm() / newton.norm());
      CHECK((ceres - newton).norm() <= 1e-8 * newton.norm());
      auto scene = Build(setup, eval);
      Error e;
      CHECK_FALSE(scene->SetStageSolver(StageSolverKind::Ipopt, &e));
      CHECK(e.message.find("ipopt minimizes potential stages only") != std::string::npos);
    }
  }
}

TEST_CASE("Scene::SetSolverParams validates and replaces the stage solver's settings",
          "[core][solver]") {
  Scene scene;
  Error e;
  NonlinearSolverParams p = scene.Settings().solver;
  CHECK(p.partLineSearch);
  p.partLineSearch = false;
  p.maxIterations = 7;
  REQUIRE(scene.SetSolverParams(p, &e));
  CHECK_FALSE(scene.Settings().solver.partLineSearch);
  CHECK(scene.Settings().solver.maxIterations == 7);
  p.maxLineSearchSteps = 0;
  CHECK_FALSE(scene.SetSolverParams(p, &e));
  CHECK(e.message.find("solver.max_line_search_steps: must be >= 1") != std::string::npos);
  CHECK(scene.Settings().solver.maxLineSearchSteps == NonlinearSolverParams().maxLineSearchSteps);
}
