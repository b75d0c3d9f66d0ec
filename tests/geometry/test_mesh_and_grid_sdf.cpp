// Mesh distance (CGAL) and grid SDFs: exactness against analytic fields, derivative consistency,
// second-order interpolation error, and the errors for bad meshes.
#include <catch2/catch.hpp>
#include <random>

#include "geometry/grid_sdf.h"
#include "geometry/mesh_sdf.h"
#include "optim/finite_difference.h"

using namespace superdex;

TEST_CASE("mesh SDF of a box mesh equals the analytic box SDF", "[geometry][sdf][mesh]") {
  const Eigen::Vector3d h(0.3, 0.2, 0.1);
  std::string error;
  auto mesh = MeshSdf::Build(MakeBoxMesh(h, 2), &error);
  REQUIRE(mesh);
  const BoxSdf box{h};
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Vector3d X(u(rng), u(rng), u(rng));
    const SdfSample a = mesh->Evaluate(X), b = box.Evaluate(X);
    INFO("X = " << X.transpose());
    CHECK(a.value == Approx(b.value).margin(1e-12));
    if (b.value > 1e-6) {  // outside: unique closest point, same gradient and Hessian
      CHECK((a.gradient - b.gradient).norm() < 1e-9);
      CHECK((a.hessian - b.hessian).norm() < 1e-6 * (1.0 + b.hessian.norm()));
    }
  }
}

TEST_CASE("mesh SDF derivatives near an icosphere", "[geometry][sdf][mesh][gradient]") {
  std::string error;
  auto mesh = MeshSdf::Build(MakeIcosphere(0.5, 2), &error);
  REQUIRE(mesh);
  std::mt19937 rng(4);
  std::normal_distribution<double> n01;
  int checked = 0;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d dir = Eigen::Vector3d(n01(rng), n01(rng), n01(rng)).normalized();
    const Eigen::Vector3d X = dir * (0.5 + 0.05 * std::abs(n01(rng)) + 0.005);
    const SdfSample s = mesh->Evaluate(X);
    const double h = 1e-6;
    const Eigen::VectorXd g = FiniteDifferenceGradient(
        [&](const Eigen::VectorXd& x) { return mesh->Value(x); }, X, h);
    const Eigen::MatrixXd H = FiniteDifferenceJacobian(
        [&](const Eigen::VectorXd& x) { return Eigen::VectorXd(mesh->Evaluate(x).gradient); }, X, h);
    // Skip points within 1e-5 of a Voronoi boundary between features, where FD straddles a kink.
    if ((H - H.transpose()).norm() > 1e-3 * (1 + H.norm())) continue;
    ++checked;
    CHECK((s.gradient - g).norm() < 1e-6);
    CHECK((s.hessian - H).norm() < 1e-3 * (1 + H.norm()));
  }
  CHECK(checked > 150);
  CHECK(mesh->Evaluate(Eigen::Vector3d::Zero()).value < -0.45);
}

TEST_CASE("bad meshes give clear errors", "[geometry][sdf][mesh]") {
  std::string error;
  TriangleMesh m = MakeBoxMesh(Eigen::Vector3d::Constant(0.1), 1);
  TriangleMesh open = m;
  open.faces.pop_back();
  CHECK_FALSE(MeshSdf::Build(open, &error));
  CHECK(error.rfind("mesh: not closed (boundary edge", 0) == 0);
  TriangleMesh inverted = m;
  for (auto& f : inverted.faces) std::swap(f[1], f[2]);
  CHECK_FALSE(MeshSdf::Build(inverted, &error));
  CHECK(error.rfind("mesh: inward oriented", 0) == 0);
  TriangleMesh doubled = m;
  doubled.faces.push_back(m.faces[0]);
  CHECK_FALSE(MeshSdf::Build(doubled, &error));
  CHECK(error.rfind("mesh: not manifold or inconsistently oriented", 0) == 0);
  CHECK_FALSE(MeshSdf::Build(TriangleMesh(), &error));
  CHECK(error == "mesh: has no faces");
}

TEST_CASE("grid SDF: consistent derivatives, continuous extension, second-order error",
          "[geometry][sdf][grid]") {
  const SphereSdf sphere{0.3};
  auto phi = [&](const Eigen::Vector3d& X) { return sphere.Evaluate(X).value; };
  std::mt19937 rng(6);
  std::normal_distribution<double> n01;
  SECTION("derivatives of the interpolant and of its extension") {
    const GridSdf g = GridSdf::Build(phi, Eigen::Vector3d::Constant(-0.4), 0.05,
                                     Eigen::Vector3i::Constant(17));
    for (int i = 0; i < 100; ++i) {
      const Eigen::Vector3d X(0.6 * n01(rng), 0.6 * n01(rng), 0.6 * n01(rng));
      const SdfSample s = g.Evaluate(X);
      const Eigen::VectorXd gfd = FiniteDifferenceGradient(
          [&](const Eigen::VectorXd& x) { return g.Evaluate(x).value; }, X, 1e-7);
      const Eigen::MatrixXd Hfd = FiniteDifferenceJacobian(
          [&](const Eigen::VectorXd& x) { return Eigen::VectorXd(g.Evaluate(x).gradient); }, X, 1e-7);
      INFO("X = " << X.transpose());
      CHECK((s.gradient - gfd).norm() < 1e-6);
      CHECK((s.hessian - Hfd).norm() < 1e-4 * (1 + Hfd.norm()));
    }
    // Nodes are exact.
    CHECK(g.Evaluate(Eigen::Vector3d(0.1, -0.2, 0.05)).value ==
          Approx(phi(Eigen::Vector3d(0.1, -0.2, 0.05))).margin(1e-12));
  }
  SECTION("interpolation error falls at second order in the contact band") {
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 2000; ++i) {
      const Eigen::Vector3d dir = Eigen::Vector3d(n01(rng), n01(rng), n01(rng)).normalized();
      points.push_back(dir * (0.3 + 0.01 * n01(rng)));  // |φ| within a few cm of the surface
    }
    double previous = 0.0, order = 0.0;
    int levels = 0;
    for (double h : {0.04, 0.02, 0.01}) {
      const int n = static_cast<int>(std::lround(0.8 / h)) + 1;
      const GridSdf g = GridSdf::Build(phi, Eigen::Vector3d::Constant(-0.4), h,
                                       Eigen::Vector3i::Constant(n));
      double err = 0.0;
      for (const auto& X : points) err = std::max(err, std::abs(g.Evaluate(X).value - phi(X)));
      if (levels > 0) order += std::log2(previous / err);
      previous = err;
      ++levels;
      INFO("h = " << h << ": max error " << err << " m, grid " << g.MemoryBytes() << " bytes");
      CHECK(err < 0.2 * h);
    }
    order /= levels - 1;
    INFO("measured order " << order);
    CHECK(order >= 1.8);
    CHECK(order <= 2.2);
  }
}
