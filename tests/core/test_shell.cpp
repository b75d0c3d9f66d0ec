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
//   - a clamped disk under its weight: the centre within 2.5 % of q R⁴/(64 D) at 8 and 12 rings
//     (measured −2.4 %, −2.0 %: no convergence on that mesh, the mid-edge average's limit);
//   - stiffness damping: a clamped strip's swing keeps its amplitude without it (SymplecticDIRK22,
//     log decrement below 0.005) and loses it at ζ = β ω / 2 with it (within 5 %);
//   - the stage of a shell (with stiffness damping) resting on the ground in contact: gradient
//     and exact Hessian equal
//     central differences (relative 1e-6 / 1e-5), the projected Hessian PSD, in the explicit-
//     normals mode; its residual Jacobian in the reconstructed-load mode (5e-9);
//   - bad input: a missing mesh, an edge of three triangles, an inconsistently oriented pair, an
//     unused vertex, a degenerate triangle, a clamped node that does not exist and two bad
//     material fields, each refused naming the field and the rule.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
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
  d.material.stiffnessDamping = 5e-3;  // its frozen-K term in the stage too
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

TEST_CASE("shell: stiffness damping takes a mode's energy at the rate ζ = β ω / 2",
          "[core][shell]") {
  // A 1 m × 0.25 m steel strip (h = 1 cm, ν = 0, 8 × 2 cells) clamped at x = 0, released flat
  // under gravity: its tip swings about the static deflection. With β = 0 and the symplectic
  // DIRK22 the swing keeps its amplitude (log decrement below 0.005 per period); with β the
  // logarithmic decrement between successive peaks is 2π ζ / √(1 − ζ²), ζ = β ω / 2 with ω the
  // measured angular frequency, within 5 % (from the second to the third swing, peak to trough).
  auto swing = [](double beta, double* omega) {
    ShellActorDesc d = Plate(Eigen::Vector2d(0, -0.125), Eigen::Vector2d(1.0, 0.125), Eigen::Vector2i(8, 2));
    d.material = {2e11, 0.0, 7800.0, 0.01, beta};
    for (int i = 0; i < d.mesh->NumVertices(); ++i)
      if (d.mesh->vertices[i].x() < 1e-12) d.clampedNodes.push_back(i);
    d.colliderType = ColliderType::None;
    SceneSettings settings;
    settings.integrator = IntegrationMethod::SymplecticDIRK22;
    Scene scene(settings);
    Error e;
    const ActorHandle a = scene.AddActor(ShellKind::Build(d, &e), &e);
    REQUIRE(a.IsValid());
    const int tip = 8;  // (x = 1, y = −0.125)
    std::vector<double> w, t;
    for (int s = 0; s < 800; ++s) {
      StepReport r;
      REQUIRE(scene.Step(1e-3, &r, &e));
      REQUIRE(r.status == StageStatus::Converged);
      w.push_back(scene.KindStateOf(a).x[3 * tip + 2]);
      t.push_back(1e-3 * (s + 1));
    }
    // Extremes of the swing (local maxima and minima of w), parabola-refined; the swing's
    // height H_k from the k-th peak to the trough after it needs no rest level.
    std::vector<double> peak, trough, when;
    for (size_t s = 1; s + 1 < w.size(); ++s) {
      const double up = w[s] - w[s - 1], down = w[s + 1] - w[s];
      if ((up > 0) == (down > 0)) continue;
      const double c = 0.5 * (w[s - 1] - w[s + 1]) / (w[s - 1] - 2 * w[s] + w[s + 1]);
      const double extreme = w[s] - 0.25 * (w[s - 1] - w[s + 1]) * c;
      if (up > 0) {
        peak.push_back(extreme);
        when.push_back(t[s] + 1e-3 * c);
      } else if (!peak.empty()) {
        trough.push_back(extreme);
      }
    }
    REQUIRE(trough.size() >= 4);
    *omega = 2 * M_PI * (peak.size() - 1) / (when.back() - when.front());
    // From the second swing on (the release excites higher modes, which β damps faster).
    return std::log((peak[1] - trough[1]) / (peak[2] - trough[2]));
  };
  double omega0 = 0.0, omega = 0.0;
  const double undamped = swing(0.0, &omega0);
  INFO("undamped: log decrement " << undamped << ", ω " << omega0 << " rad/s");
  CHECK(std::abs(undamped) < 0.005);
  const double beta = 0.002;
  const double damped = swing(beta, &omega);
  const double zeta = 0.5 * beta * omega;
  const double expected = 2 * M_PI * zeta / std::sqrt(1 - zeta * zeta);
  INFO("β " << beta << " s: log decrement " << damped << ", expected " << expected << " (ω "
            << omega << " rad/s, ζ " << zeta << ")");
  CHECK(std::abs(damped / expected - 1.0) < 0.05);
}

TEST_CASE("shell: a clamped circular plate under its weight sags near Kirchhoff's plate",
          "[core][shell]") {
  // A steel disk (R = 1 m, h = 1 cm, ν = 0.3) clamped along its rim (MakeDiskMesh: a centre and
  // rings of 6k nodes, no grid direction): the centre deflection against q R⁴/(64 D) (Kirchhoff).
  // Measured +2.1 %, −2.4 %, −2.0 % at 4, 8, 12 rings: the mid-edge average does not converge on
  // this mesh (its triangles are not a lattice: known of the average formulation, whose
  // stiffness carries a mesh-dependent error off regular grids; the rectangle cantilever
  // converges). Asserted: within 2.5 % at 8 and 12 rings, so that a change of the error shows.
  const double R = 1.0, h = 0.01, E = 2e11, nu = 0.3, rho = 7800.0, g = 9.81;
  const double D = E * h * h * h / (12.0 * (1.0 - nu * nu));
  const double expected = rho * h * g * std::pow(R, 4) / (64.0 * D);
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BackwardEuler;
  std::vector<double> error;
  for (int rings : {4, 8, 12}) {
    ShellActorDesc d;
    d.name = "disk";
    d.mesh = std::make_shared<TriangleMesh>(MakeDiskMesh(R, rings));
    d.material = {E, nu, rho, h, 0.0};
    d.colliderType = ColliderType::None;
    for (int i = 0; i < d.mesh->NumVertices(); ++i)
      if (d.mesh->vertices[i].norm() > R - 1e-9) d.clampedNodes.push_back(i);
    Scene scene(settings);
    Error e;
    const ActorHandle a = scene.AddActor(ShellKind::Build(d, &e), &e);
    INFO(e.message);
    REQUIRE(a.IsValid());
    for (int s = 0; s < 3; ++s) {
      StepReport r;
      REQUIRE(scene.Step(100.0, &r, &e));
      REQUIRE(r.status == StageStatus::Converged);
    }
    const double w = -scene.KindStateOf(a).x[2];  // node 0: the centre
    error.push_back(std::abs(w / expected - 1.0));
    std::printf("clamped disk, %d rings: centre %.6g m, Kirchhoff %.6g m (%.2f %%)\n", rings, w,
                expected, 100 * (w / expected - 1.0));
  }
  INFO("relative errors " << error[0] << ", " << error[1] << ", " << error[2]);
  CHECK(error[1] < 0.025);
  CHECK(error[2] < 0.025);
}

}  // namespace superdex
