// Shell actors (core/model/shell_kind.h): membrane and hinge bending on triangles, lumped mass,
// pinned nodes, a colliding role without normals.
//
// Expectations:
//   - a square plate clamped on one edge (its nodes pinned and its edges' mid-edge normals held)
//     under its weight (mid-edge bending): the tip deflection equals Kirchhoff's q L⁴ / (8 D)
//     within 2 % on a 16 × 16 mesh (measured 0.39 %), the error falling at second order under
//     refinement (6.2 %, 1.6 %, 0.39 % at 4, 8, 16 cells a side; asserted: by more than 3× per
//     halving); ν = 0, where Kirchhoff's solution is cylindrical bending (the free edges' moment
//     and shear vanish with κ_y = 0); a static solve (Backward Euler steps of 100 s). The hinge
//     model, without the plate's Poisson term, deflects 28 % more at 16 cells (its free edges
//     relax anticlastically);
//   - the stage of a shell resting on the ground in contact: gradient and exact Hessian equal
//     central differences (relative 1e-6 / 1e-5), the projected Hessian PSD, in the explicit-
//     normals mode; its residual Jacobian in the reconstructed-load mode (5e-9);
//   - bad input: a missing mesh, an edge of three triangles, an inconsistently oriented pair, an
//     unused vertex, a degenerate triangle, a clamped node that does not exist and two bad
//     material fields, each refused naming the field and the rule.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/model/shell_kind.h"
#include "core/scene.h"
#include "stage_derivative_recorder.h"

namespace superdex {
namespace {

ShellActorDesc Plate(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Eigen::Vector2i& cells) {
  ShellActorDesc d;
  d.name = "plate";
  d.mesh = std::make_shared<TriangleMesh>(MakeRectangleMesh(lo, hi, cells));
  d.meshSource = "rectangle";
  return d;
}

}  // namespace

TEST_CASE("shell: a cantilever plate under its weight deflects as Kirchhoff's plate",
          "[core][shell]") {
  const double L = 1.0, h = 0.01, E = 2e11, rho = 7800.0, g = 9.81;
  const double D = E * h * h * h / 12.0, q = rho * h * g;
  const double expected = q * std::pow(L, 4) / (8.0 * D);
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BackwardEuler;
  std::vector<double> error;
  for (int n : {4, 8, 16}) {
    ShellActorDesc d = Plate(Eigen::Vector2d(0, -0.5), Eigen::Vector2d(L, 0.5), Eigen::Vector2i(n, n));
    d.material.youngsModulus = E;
    d.material.poissonRatio = 0.0;
    d.material.density = rho;
    d.material.thickness = h;
    for (int i = 0; i < d.mesh->NumVertices(); ++i)
      if (d.mesh->vertices[i].x() < 1e-12) d.clampedNodes.push_back(i);
    Scene scene(settings);
    Error e;
    std::unique_ptr<ShellKind> kind = ShellKind::Build(d, &e);
    INFO(e.message);
    REQUIRE(kind);
    const ActorHandle a = scene.AddActor(std::move(kind), &e);
    REQUIRE(a.IsValid());
    for (int s = 0; s < 3; ++s) {
      StepReport r;
      REQUIRE(scene.Step(100.0, &r, &e));
      REQUIRE(r.status == StageStatus::Converged);
    }
    const Eigen::VectorXd& x = scene.KindStateOf(a).x;
    double tip = 0.0;
    int count = 0;
    for (int i = 0; i < d.mesh->NumVertices(); ++i)
      if (d.mesh->vertices[i].x() > L - 1e-12) {
        tip += -x[3 * i + 2];
        ++count;
      }
    tip /= count;
    error.push_back(std::abs(tip / expected - 1.0));
    INFO(n << " cells: tip " << tip << " m, Kirchhoff " << expected << " m");
    CHECK(tip > 0.0);
  }
  INFO("relative errors " << error[0] << ", " << error[1] << ", " << error[2]);
  CHECK(error[2] < 0.02);
  CHECK(error[2] < error[1] / 3.0);
  CHECK(error[1] < error[0] / 3.0);
}

TEST_CASE("shell: the stage's derivatives with the shell on the ground", "[core][shell][gradient]") {
  const bool explicitNormals = GENERATE(true, false);
  SceneSettings settings;
  settings.eval.explicitNormals = explicitNormals;
  Scene scene(settings);
  RigidActorDesc ground;
  ground.name = "ground";
  ground.dynamic = false;
  ground.shape.kind = RigidShapeKind::Plane;
  ground.contact.penaltyCoefficient = 1e6;
  ground.contact.viscousFrictionCoefficient = 1e3;
  Error e;
  REQUIRE(scene.AddRigidActor(ground, &e).IsValid());
  // A 10 cm cloth-like sheet tilted so that one edge is 1 mm into the ground, moving.
  ShellActorDesc d = Plate(Eigen::Vector2d(-0.05, -0.05), Eigen::Vector2d(0.05, 0.05), Eigen::Vector2i(3, 3));
  d.material.youngsModulus = 1e6;
  d.material.thickness = 1e-3;
  d.position = Eigen::Vector3d(0, 0, 0.004);
  d.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()));
  d.linearVelocity = Eigen::Vector3d(0.2, 0.1, -0.1);
  d.contact.penaltyCoefficient = 1e6;
  d.contact.viscousFrictionCoefficient = 1e3;
  d.contact.normalViscousDampingCoefficient = 0.3;
  std::unique_ptr<ShellKind> kind = ShellKind::Build(d, &e);
  REQUIRE(kind);
  REQUIRE(scene.AddActor(std::move(kind), &e).IsValid());
  test::StageDerivativeRecorder rec;
  rec.residualStep = 1e-8;
  StepReport r;
  REQUIRE(scene.Step(1e-3, &r, &e, &rec));
  REQUIRE(rec.checked);
  CHECK(rec.dofs == 3 * 16);
  rec.CheckAccuracy(explicitNormals);
}

TEST_CASE("shell: bad meshes and fields are refused with the field and the rule", "[core][shell]") {
  auto refused = [](const ShellActorDesc& d, const std::string& part) {
    Error e;
    CHECK_FALSE(ShellKind::Build(d, &e));
    INFO(e.message);
    CHECK(e.message.find(part) != std::string::npos);
  };
  ShellActorDesc d;
  refused(d, "mesh: a triangle mesh of at least one triangle is required");
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  mesh->faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};  // edge (0, 1) in three triangles
  d.mesh = mesh;
  refused(d, "mesh: mesh: edge (0, 1) is shared by more than two triangles");
  mesh->faces = {{0, 1, 2}, {0, 1, 3}, {0, 2, 4}};  // (0, 1) run the same way twice
  refused(d, "mesh: mesh: edge (0, 1) is traversed the same way by triangles 0 and 1");
  mesh->faces = {{0, 1, 2}};
  refused(d, "mesh: mesh: vertex 3 belongs to no triangle");
  mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  refused(d, "mesh: mesh: triangle 0 is degenerate");
  mesh->vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  d.clampedNodes = {3};
  refused(d, "clamped_nodes: node 3 does not exist");
  d.clampedNodes.clear();
  d.material.thickness = -1.0;
  refused(d, "material.thickness");
  d.material.thickness = 1e-3;
  d.material.poissonRatio = 0.5;
  refused(d, "material.poisson_ratio");
}

}  // namespace superdex
