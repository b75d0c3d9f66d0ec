// Triangle meshes: generators (topology, orientation, measures), OBJ reading and its errors, mass
// properties against closed forms.
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include "geometry/mesh_sdf.h"
#include <set>
#include <string>

#include "geometry/triangle_mesh.h"

using namespace superdex;

namespace {

struct Topology {
  bool closed = false;  ///< every edge in exactly two faces, used in opposite directions
  int edges = 0;        ///< undirected edges
  int boundaryEdges = 0;
};

Topology Analyse(const TriangleMesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& f : m.faces)
    for (int k = 0; k < 3; ++k) directed[{f[k], f[(k + 1) % 3]}]++;
  Topology t;
  t.closed = true;
  std::set<std::pair<int, int>> undirected;
  for (const auto& [e, n] : directed) {
    undirected.insert({std::min(e.first, e.second), std::max(e.first, e.second)});
    const auto rev = directed.find({e.second, e.first});
    if (n != 1 || rev == directed.end() || rev->second != 1) t.closed = false;
    if (rev == directed.end()) ++t.boundaryEdges;
  }
  t.edges = static_cast<int>(undirected.size());
  return t;
}

bool AllVerticesUsed(const TriangleMesh& m) {
  std::vector<bool> used(m.vertices.size(), false);
  for (const auto& f : m.faces)
    for (int k = 0; k < 3; ++k) used[f[k]] = true;
  return std::all_of(used.begin(), used.end(), [](bool b) { return b; });
}

// Rigidly moved copy: x -> R x + t.
TriangleMesh Transformed(TriangleMesh m, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  for (auto& v : m.vertices) v = R * v + t;
  return m;
}

// A scratch directory unique to this process, removed at scope exit.
struct ScratchDir {
  std::filesystem::path dir;
  ScratchDir() {
    dir = std::filesystem::temp_directory_path() /
          ("superdex_test_geometry_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  std::string Write(const std::string& name, const std::string& text) const {
    const std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
};

}  // namespace

TEST_CASE("mesh: face area, normal, surface area and bounds", "[geometry][mesh]") {
  TriangleMesh m;
  m.vertices = {{1, 0, 0}, {3, 0, 0}, {1, 4, 0}, {5, 5, 5}};
  m.faces = {{0, 1, 2}, {0, 2, 1}, {0, 1, 1}};
  CHECK(m.FaceArea(0) == Approx(4.0));
  CHECK(m.FaceNormal(0).isApprox(Eigen::Vector3d::UnitZ(), 1e-15));
  CHECK(m.FaceNormal(1).isApprox(-Eigen::Vector3d::UnitZ(), 1e-15));
  CHECK(m.FaceArea(2) == 0.0);
  CHECK(m.FaceNormal(2) == Eigen::Vector3d::Zero());  // degenerate face
  CHECK(m.SurfaceArea() == Approx(8.0));
  const Aabb b = m.Bounds();
  CHECK(b.min == Eigen::Vector3d(1, 0, 0));
  CHECK(b.max == Eigen::Vector3d(5, 5, 5));
  CHECK(TriangleMesh().Bounds().IsEmpty());
}

TEST_CASE("mesh: icosphere is a closed outward sphere converging in volume", "[geometry][mesh]") {
  const double r = 0.3;
  const double exactVolume = 4.0 / 3.0 * M_PI * r * r * r;
  double previousError = 0.0;
  for (int n = 0; n <= 5; ++n) {
    INFO("subdivisions " << n);
    const TriangleMesh s = MakeIcosphere(r, n);
    const int faces = 20 * (1 << (2 * n));
    CHECK(s.NumFaces() == faces);
    CHECK(s.NumVertices() == faces / 2 + 2);  // shared midpoints, Euler V − E + F = 2
    const Topology t = Analyse(s);
    CHECK(t.closed);
    CHECK(s.NumVertices() - t.edges + s.NumFaces() == 2);
    CHECK(AllVerticesUsed(s));
    double worstRadius = 0.0;
    for (const auto& v : s.vertices) worstRadius = std::max(worstRadius, std::abs(v.norm() - r));
    CHECK(worstRadius <= 1e-15);
    bool outward = true;
    for (int f = 0; f < s.NumFaces(); ++f) {
      const Eigen::Vector3i& tri = s.faces[f];
      const Eigen::Vector3d c = (s.vertices[tri[0]] + s.vertices[tri[1]] + s.vertices[tri[2]]) / 3;
      outward &= s.FaceNormal(f).dot(c) > 0.0;
    }
    CHECK(outward);
    // Inscribed polyhedron: volume below the sphere's, error O(h²) so ~1/4 per subdivision.
    const MassProperties mp = ComputeMassProperties(s, 1.0);
    const double error = exactVolume - mp.volume;
    CHECK(error > 0.0);
    if (n == 1) CHECK(error < previousError / 3.0);
    if (n >= 2) {  // asymptotic ratio 4 (observed 3.74, 3.93, 3.98, 4.00)
      CHECK(error < previousError / 3.5);
      CHECK(error > previousError / 4.5);
    }
    previousError = error;
    CHECK(mp.centerOfMass.norm() <= 1e-15);
    if (n == 5) {
      CHECK(error < 1e-3 * exactVolume);
      // Solid sphere: J = m r²/5 I (to the discretization error).
      const Eigen::Matrix3d J = mp.mass * r * r / 5.0 * Eigen::Matrix3d::Identity();
      CHECK((mp.secondMoment - J).norm() < 1e-3 * J.norm());  // observed 3.6e-4
    }
  }
}

TEST_CASE("mesh: box mesh is closed, exact in area, volume and mass properties",
          "[geometry][mesh]") {
  const Eigen::Vector3d h(0.1, 0.25, 0.4);
  const double density = 1700.0;
  for (int d : {1, 2, 5}) {
    INFO("divisions " << d);
    const TriangleMesh b = MakeBoxMesh(h, d);
    CHECK(b.NumFaces() == 12 * d * d);
    CHECK(b.NumVertices() == 6 * d * d + 2);  // shared along edges and corners
    const Topology t = Analyse(b);
    CHECK(t.closed);
    CHECK(b.NumVertices() - t.edges + b.NumFaces() == 2);
    CHECK(AllVerticesUsed(b));
    CHECK(b.Bounds().min == -h);
    CHECK(b.Bounds().max == h);
    // Outward, axis-aligned normals; every vertex of a face on that face's plane.
    for (int f = 0; f < b.NumFaces(); ++f) {
      const Eigen::Vector3d n = b.FaceNormal(f);
      int axis;
      CHECK(n.cwiseAbs().maxCoeff(&axis) == 1.0);
      CHECK(n.cwiseAbs().sum() == 1.0);
      for (int k = 0; k < 3; ++k) CHECK(b.vertices[b.faces[f][k]][axis] == n[axis] * h[axis]);
    }
    CHECK(b.SurfaceArea() ==
          Approx(8.0 * (h.x() * h.y() + h.y() * h.z() + h.z() * h.x())).epsilon(1e-14));
    const MassProperties mp = ComputeMassProperties(b, density);
    const double V = 8.0 * h.prod(), m = density * V;
    CHECK(mp.volume == Approx(V).epsilon(1e-14));
    CHECK(mp.mass == Approx(m).epsilon(1e-14));
    CHECK(mp.centerOfMass.norm() <= 1e-15);
    // J = ∫ x xᵀ dm = diag(m a²/3, m b²/3, m c²/3) for half extents (a, b, c).
    const Eigen::Matrix3d J = (m / 3.0) * Eigen::Vector3d(h.cwiseProduct(h)).asDiagonal();
    CHECK((mp.secondMoment - J).norm() <= 1e-12 * J.norm());
    // Moved rigidly far from the origin: c = t, J = R J₀ Rᵀ.
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
    const Eigen::Vector3d shift(12.0, -7.5, 30.0);
    const MassProperties moved = ComputeMassProperties(Transformed(b, R, shift), density);
    CHECK(moved.volume == Approx(V).epsilon(1e-12));
    CHECK((moved.centerOfMass - shift).norm() <= 1e-12 * shift.norm());
    CHECK((moved.secondMoment - R * J * R.transpose()).norm() <= 1e-12 * J.norm());
  }
}

TEST_CASE("mesh: mass properties of a tetrahedron match the closed form", "[geometry][mesh]") {
  // Corner tetrahedron (0, e_x, e_y, e_z): V = 1/6, c = (1/4, 1/4, 1/4),
  // ∫ x² dV = 1/60, ∫ x y dV = 1/120, so J_xx = 1/60 − V/16 = 1/160, J_xy = 1/120 − V/16 = −1/480.
  TriangleMesh t;
  t.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  t.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  CHECK(Analyse(t).closed);
  const double rho = 3.0;
  const MassProperties mp = ComputeMassProperties(t, rho);
  CHECK(mp.volume == Approx(1.0 / 6.0).epsilon(1e-15));
  CHECK(mp.mass == Approx(0.5).epsilon(1e-15));
  CHECK((mp.centerOfMass - Eigen::Vector3d::Constant(0.25)).norm() <= 1e-15);
  Eigen::Matrix3d J = Eigen::Matrix3d::Constant(-rho / 480.0);
  J.diagonal().setConstant(rho / 160.0);
  CHECK((mp.secondMoment - J).norm() <= 1e-14);
  CHECK((mp.secondMoment - mp.secondMoment.transpose()).norm() == 0.0);
  // Reversed orientation (inward faces) gives the negated volume.
  for (auto& f : t.faces) std::swap(f[1], f[2]);
  CHECK(ComputeMassProperties(t, rho).volume == Approx(-1.0 / 6.0).epsilon(1e-15));
}

TEST_CASE("mesh: plane patch is an open +z grid", "[geometry][mesh]") {
  const int n = 4;
  const TriangleMesh p = MakePlanePatch(2.0, n);
  CHECK(p.NumVertices() == (n + 1) * (n + 1));
  CHECK(p.NumFaces() == 2 * n * n);
  CHECK(p.SurfaceArea() == Approx(4.0).epsilon(1e-14));
  for (int f = 0; f < p.NumFaces(); ++f) CHECK(p.FaceNormal(f) == Eigen::Vector3d::UnitZ());
  const Topology t = Analyse(p);
  CHECK_FALSE(t.closed);
  CHECK(t.boundaryEdges == 4 * n);
  CHECK(p.Bounds().min == Eigen::Vector3d(-1, -1, 0));
  CHECK(p.Bounds().max == Eigen::Vector3d(1, 1, 0));
}

TEST_CASE("mesh: OBJ reading of quads, slash forms, negative indices and comments",
          "[geometry][mesh][obj]") {
  const ScratchDir scratch;
  // Cube [0, 2]^3 written with everything a real exporter emits.
  const std::string path = scratch.Write("cube.obj",
                                         "# exported cube\n"
                                         "mtllib cube.mtl\n"
                                         "o Cube\n"
                                         "v 0 0 0\n"
                                         "v 2 0 0 1.0\n"  // optional w
                                         "v 2 2 0\n"
                                         "v 0 2 0   # inline comment\n"
                                         "v 0 0 2\r\n"  // CRLF line
                                         "v 2.0e0 0 2\n"
                                         "v 2 2 2\n"
                                         "v 0 2 2\n"
                                         "vt 0 0\n"
                                         "vn 0 0 -1\n"
                                         "\n"
                                         "g sides\n"
                                         "s off\n"
                                         "usemtl grey\n"
                                         "f 1/1/1 4/1/1 3/1/1 2/1/1\n"  // bottom, v/vt/vn
                                         "f 5//1 6//1 7//1 8//1\n"      // top, v//vn
                                         "f 1/1 2/1 6/1 5/1\n"          // front, v/vt
                                         "f -6 -5 -1 -2\n"              // back: 3 4 8 7
                                         "f -7 -6 -2 -3\n"              // right: 2 3 7 6
                                         "f 1 5 8\tf\n"                 // left, split in two
                                         "f 1 8 4\n");
  // "f 1 5 8\tf" has a bad token: checked below; use a clean copy for the geometry.
  std::string err;
  TriangleMesh m;
  CHECK_FALSE(ReadObj(path, &m, &err));
  CHECK(err == path + ":23: malformed face index \"f\"");

  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("\tf\n"), 3, "\n");
  const std::string good = scratch.Write("cube_good.obj", text);
  REQUIRE(ReadObj(good, &m, &err));
  CHECK(m.NumVertices() == 8);
  CHECK(m.NumFaces() == 12);  // four quads → 8 triangles, plus 2 + 2
  CHECK(Analyse(m).closed);
  CHECK(m.SurfaceArea() == Approx(24.0).epsilon(1e-15));
  const MassProperties mp = ComputeMassProperties(m, 1.0);
  CHECK(mp.volume == Approx(8.0).epsilon(1e-15));
  CHECK((mp.centerOfMass - Eigen::Vector3d::Ones()).norm() <= 1e-15);

  // A pentagon is fan-triangulated from its first corner.
  const std::string pent = scratch.Write("pentagon.obj",
                                         "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\n"
                                         "f 1 2 3 4 5\n");
  REQUIRE(ReadObj(pent, &m, &err));
  REQUIRE(m.NumFaces() == 3);
  CHECK(m.faces[0] == Eigen::Vector3i(0, 1, 2));
  CHECK(m.faces[1] == Eigen::Vector3i(0, 2, 3));
  CHECK(m.faces[2] == Eigen::Vector3i(0, 3, 4));
  CHECK(m.SurfaceArea() == Approx(3.0));
}

TEST_CASE("mesh: OBJ errors name the file and the line", "[geometry][mesh][obj]") {
  const ScratchDir scratch;
  TriangleMesh m;
  m.vertices = {{7, 7, 7}};
  m.faces = {{0, 0, 0}};
  std::string err;
  auto unchanged = [&] { return m.NumVertices() == 1 && m.NumFaces() == 1; };

  const std::string missing = (scratch.dir / "does_not_exist.obj").string();
  CHECK_FALSE(ReadObj(missing, &m, &err));
  CHECK(err == missing + ": cannot open file");

  std::string eight;
  for (int i = 0; i < 8; ++i) eight += "v " + std::to_string(i) + " 0 0\n";
  const std::string range = scratch.Write("mesh.obj", eight + "\n\nf 1 2 3\nf 1 2 9\n");
  CHECK_FALSE(ReadObj(range, &m, &err));
  CHECK(err == range + ":12: face index 9 out of range (8 vertices)");

  const std::string zero = scratch.Write("zero.obj", eight + "f 0 1 2\n");
  CHECK_FALSE(ReadObj(zero, &m, &err));
  CHECK(err == zero + ":9: face index 0 out of range (8 vertices)");

  const std::string negative = scratch.Write("negative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\n");
  CHECK_FALSE(ReadObj(negative, &m, &err));
  CHECK(err == negative + ":3: face index -3 out of range (2 vertices so far)");

  const std::string badVertex = scratch.Write("bad_vertex.obj", "v 0 0 0\nv 1 zero 0\n");
  CHECK_FALSE(ReadObj(badVertex, &m, &err));
  CHECK(err.rfind(badVertex + ":2: malformed vertex", 0) == 0);

  const std::string shortVertex = scratch.Write("short_vertex.obj", "v 1 2\n");
  CHECK_FALSE(ReadObj(shortVertex, &m, &err));
  CHECK(err.rfind(shortVertex + ":1: malformed vertex", 0) == 0);

  const std::string twoCorners = scratch.Write("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  CHECK_FALSE(ReadObj(twoCorners, &m, &err));
  CHECK(err == twoCorners + ":3: a face needs at least 3 vertices, got 2");

  const std::string badIndex = scratch.Write("bad_index.obj", eight + "f 1 2x 3\n");
  CHECK_FALSE(ReadObj(badIndex, &m, &err));
  CHECK(err == badIndex + ":9: malformed face index \"2x\"");

  const std::string noFaces = scratch.Write("no_faces.obj", eight);
  CHECK_FALSE(ReadObj(noFaces, &m, &err));
  CHECK(err == noFaces + ": no faces");

  const std::string empty = scratch.Write("empty.obj", "");
  CHECK_FALSE(ReadObj(empty, &m, &err));
  CHECK(err == empty + ": no faces");

  CHECK(unchanged());                          // the output is untouched on failure
  CHECK_FALSE(ReadObj(missing, &m, nullptr));  // a null error pointer is allowed
  CHECK_FALSE(ReadObj(range, nullptr, &err));  // a null mesh is an error, not a crash
}

TEST_CASE("cylinder mesh: closed, outward, volume of the inscribed prism", "[geometry]") {
  const double r = 0.05, half = 0.1;
  const int n = 24;
  const TriangleMesh m = MakeCylinderMesh(r, half, n, 3);
  // The inscribed regular n-gon prism: V = ½ n r² sin(2π/n) · 2 half.
  const double prism = 0.5 * n * r * r * std::sin(2 * M_PI / n) * 2 * half;
  CHECK(ComputeMassProperties(m, 1.0).volume == Approx(prism).epsilon(1e-12));
  std::string why;
  CHECK(MeshSdf::Build(m, &why) != nullptr);  // closed and outward
  for (int f = 0; f < m.NumFaces(); ++f) CHECK(m.FaceArea(f) > 0);
}

TEST_CASE("disk and annulus meshes: open +z discs of the right area and topology",
          "[geometry][mesh]") {
  for (int rings : {1, 3, 7}) {
    const TriangleMesh d = MakeDiskMesh(0.5, rings);
    CHECK(d.NumVertices() == 1 + 3 * rings * (rings + 1));
    CHECK(d.NumFaces() == 6 * rings * rings);
    CHECK(AllVerticesUsed(d));
    for (int f = 0; f < d.NumFaces(); ++f) CHECK(d.FaceNormal(f).z() > 1.0 - 1e-12);
    const Topology t = Analyse(d);
    CHECK(t.boundaryEdges == 6 * rings);  // the rim
    CHECK(d.NumVertices() - t.edges + d.NumFaces() == 1);  // a disk
    // The area of the rim's regular 6n-gon.
    const int n = 6 * rings;
    CHECK(d.SurfaceArea() == Approx(0.5 * n * 0.25 * std::sin(2 * M_PI / n)).epsilon(1e-12));
  }
  const TriangleMesh a = MakeAnnulusMesh(6.0, 10.0, 2 * M_PI, Eigen::Vector2i(4, 32));
  CHECK(a.NumVertices() == 5 * 33);
  CHECK(a.NumFaces() == 2 * 4 * 32);
  for (int f = 0; f < a.NumFaces(); ++f) CHECK(a.FaceNormal(f).z() > 1.0 - 1e-12);
  const Topology t = Analyse(a);
  CHECK(t.boundaryEdges == 2 * 32 + 2 * 4);  // both rims and the slit's two sides
  CHECK(a.NumVertices() - t.edges + a.NumFaces() == 1);  // cut open: a disk's topology
  const double polygon = 0.5 * 32 * std::sin(2 * M_PI / 32) * (100.0 - 36.0);
  CHECK(a.SurfaceArea() == Approx(polygon).epsilon(1e-12));
}
