// Degenerate surfaces and scales the mesher cannot handle: refused before meshing, meshed in
// normalized coordinates, or stopped at the time or size budget with the reason, never a hang.
#include <catch2/catch.hpp>
#include <chrono>
#include <string>

#include "geometry/tet_mesh.h"

using namespace superdex;

namespace {

// A closed cube of side 1 with every vertex transformed by f (outward faces).
template <typename F>
TriangleMesh Cube(F f) {
  TriangleMesh m = MakeBoxMesh(Eigen::Vector3d::Constant(0.5), 1);
  for (Eigen::Vector3d& v : m.vertices) v = f(v);
  return m;
}

}  // namespace

TEST_CASE("bad input: degenerate surfaces are refused before meshing", "[geometry][bad_input]") {
  // These used to hang in CGAL's search for initial points (it shoots rays forever).
  TetMesh out;
  std::string e;
  const auto toPoint = [](const Eigen::Vector3d&) { return Eigen::Vector3d(1, 2, 3); };
  CHECK_FALSE(MeshTetsFromSurface(Cube(toPoint), 0.3, &out, &e));
  CHECK(e == "MeshTetsFromSurface: the surface's vertices all coincide: it encloses no volume");
  CHECK_FALSE(MeshTetsFromSurface(
      Cube([](const Eigen::Vector3d& v) { return Eigen::Vector3d(v.x(), v.y(), 0.0); }), 0.3,
      &out, &e));
  CHECK(e.rfind("MeshTetsFromSurface: the surface encloses no volume (|volume| 0", 0) == 0);
}

TEST_CASE("bad input: the mesher works at any scale and stops at its budget",
          "[geometry][bad_input]") {
  MeshingLimits bounds;
  bounds.seconds = 60;  // a regression fails here instead of hanging (it used to run forever)
  for (double r : {1e10, 1e155, 1e-20}) {
    TetMesh ball;
    std::string e;
    INFO("radius " << r);
    REQUIRE(MeshTetSphere(r, r / 3, &ball, &e, bounds));
    CHECK(ball.Bounds().max.x() == Approx(r).epsilon(0.05));
    // Meshed, but at 1e155 m the tets' volumes overflow: not a mesh to simulate.
    CHECK(ValidateTetMesh(ball, "ball", &e) == (r < 1e100));
  }
  // A budget that cannot be met: the refinement is stopped and reported, within the budget.
  bounds.seconds = 0.05;
  TetMesh out;
  std::string e;
  const auto start = std::chrono::steady_clock::now();
  CHECK_FALSE(MeshTetSphere(1.0, 0.05, &out, &e, bounds));
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 10);
  CHECK(e.rfind("MeshTetsFromSurface: CGAL Mesh_3 stopped: the Delaunay refinement did not "
                "finish in time (the budget for about ",
                0) == 0);
  bounds.seconds = -1;
  bounds.maxTets = 100;
  CHECK_FALSE(MeshTetSphere(1.0, 0.2, &out, &e, bounds));
  CHECK(e == "MeshTetsFromSurface: edge length 0.2 m would give about 4434 tets (limit 100); use "
             "a larger edge length");
}
