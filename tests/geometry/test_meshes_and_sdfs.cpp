#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>

#include "geometry/analytic_sdf.h"
#include "geometry/triangle_mesh.h"

using namespace superdex;

namespace {

// Every directed edge appears once and its reverse once: closed, consistently oriented.
bool ClosedAndOriented(const TriangleMesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& f : m.faces)
    for (int k = 0; k < 3; ++k) directed[{f[k], f[(k + 1) % 3]}]++;
  for (const auto& [e, n] : directed)
    if (n != 1 || directed.count({e.second, e.first}) != 1) return false;
  return true;
}

}  // namespace

TEST_CASE("icosphere and box meshes are closed, oriented and measure right", "[geometry]") {
  for (int n = 0; n <= 3; ++n) {
    const TriangleMesh s = MakeIcosphere(0.3, n);
    CHECK(s.NumFaces() == 20 * (1 << (2 * n)));
    CHECK(ClosedAndOriented(s));
    for (const auto& v : s.vertices) CHECK(v.norm() == Approx(0.3).epsilon(1e-14));
    CHECK(ComputeMassProperties(s, 1.0).volume > 0.0);
  }
  const double exact = 4.0 / 3.0 * M_PI * 0.027;
  CHECK(std::abs(ComputeMassProperties(MakeIcosphere(0.3, 4), 1.0).volume - exact) < 0.01 * exact);
  const Eigen::Vector3d h(0.1, 0.2, 0.3);
  for (int d : {1, 3}) {
    const TriangleMesh b = MakeBoxMesh(h, d);
    CHECK(ClosedAndOriented(b));
    CHECK(b.NumFaces() == 12 * d * d);
    CHECK(b.SurfaceArea() == Approx(8 * (h.x() * h.y() + h.y() * h.z() + h.x() * h.z())).epsilon(1e-13));
    const MassProperties mp = ComputeMassProperties(b, 2.0);
    const double m = 2.0 * 8 * h.prod();
    CHECK(mp.mass == Approx(m).epsilon(1e-13));
    CHECK(mp.centerOfMass.norm() < 1e-14);
    const Eigen::Matrix3d J = (m / 3.0) * h.cwiseProduct(h).asDiagonal();
    CHECK((mp.secondMoment - J).norm() < 1e-12 * J.norm());
  }
}

TEST_CASE("OBJ reading: quads, negative indices and clear errors", "[geometry]") {
  const std::string path = std::string(SUPERDEX_BINARY_DIR) + "/test_quad.obj";
  std::ofstream(path) << "# square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1 2/2 3/3 4/4\nf -4 -2 -1\n";
  TriangleMesh m;
  std::string err;
  REQUIRE(ReadObj(path, &m, &err));
  CHECK(m.NumFaces() == 3);
  CHECK(m.SurfaceArea() == Approx(1.5));
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 9\n";
  CHECK_FALSE(ReadObj(path, &m, &err));
  CHECK(err == path + ":4: face index 9 out of range (3 vertices)");
  CHECK_FALSE(ReadObj(path + ".missing", &m, &err));
  CHECK(err == path + ".missing: cannot open file");
  std::remove(path.c_str());
}

TEST_CASE("analytic SDFs: values, unit gradients, and derivatives by differences", "[geometry]") {
  const SphereSdf sphere{0.2};
  const BoxSdf box{Eigen::Vector3d(0.1, 0.2, 0.3)};
  const PlaneSdf plane{Eigen::Vector3d(0, 0.6, 0.8), 0.1};
  CHECK(sphere.Evaluate({0.5, 0, 0}).value == Approx(0.3));
  CHECK(box.Evaluate({0.0, 0.0, 0.25}).value == Approx(-0.05));                 // inside
  CHECK(box.Evaluate({0.4, 0.0, 0.0}).value == Approx(0.3));                    // face region
  CHECK(box.Evaluate({0.4, 0.6, 0.0}).value == Approx(0.5));                    // edge region
  CHECK(box.Evaluate({0.4, 0.6, 0.3 + 1.2}).value == Approx(std::sqrt(0.09 + 0.16 + 1.44)));
  CHECK(plane.Evaluate({0, 1, 1}).value == Approx(1.3));
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-0.8, 0.8);
  const double h = 1e-6;
  auto check = [&](auto sdf, const Eigen::Vector3d& X) {
    const SdfSample s = sdf.Evaluate(X);
    CHECK(s.gradient.norm() == Approx(1.0).epsilon(1e-12));
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(k) * h;
      const SdfSample p = sdf.Evaluate(X + e), m = sdf.Evaluate(X - e);
      CHECK(s.gradient[k] == Approx((p.value - m.value) / (2 * h)).margin(1e-7));
      CHECK((s.hessian.col(k) - (p.gradient - m.gradient) / (2 * h)).norm() < 1e-5);
    }
  };
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d X(u(rng), u(rng), u(rng));
    check(sphere, X);
    check(plane, X);
    // Away from the box's kinks: the inside medial planes and the region boundaries outside.
    const Eigen::Vector3d d = X.cwiseAbs() - box.halfExtents;
    bool nearKink = (d.array().abs() < 1e-3).any();
    if ((d.array() < 0).all()) {
      Eigen::Vector3d sorted = d;
      std::sort(sorted.data(), sorted.data() + 3);
      nearKink |= sorted[2] - sorted[1] < 1e-3;
    }
    if (!nearKink) check(box, X);
  }
}
