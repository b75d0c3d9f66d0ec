// Tetrahedral meshes: the structured box (volume, orientation, boundary), Gmsh 2.2 / 4.1 and
// TetGen files read back (and their errors), validation messages, CGAL Mesh_3 tetrahedralization
// of closed surfaces (volume, orientation, determinism, closed boundary), shipped data files.
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>

#include "geometry/tet_mesh.h"
#include "geometry/triangle_mesh.h"

using namespace superdex;

namespace {

std::string TempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("superdex_tet_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string Str(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

double TotalVolume(const TetMesh& m) {
  double v = 0.0;
  for (int t = 0; t < m.NumTets(); ++t) v += m.TetVolume(t);
  return v;
}

double MinVolume(const TetMesh& m) {
  double v = INFINITY;
  for (int t = 0; t < m.NumTets(); ++t) v = std::min(v, m.TetVolume(t));
  return v;
}

bool SameMesh(const TetMesh& a, const TetMesh& b) {
  return a.vertices == b.vertices && a.tets == b.tets;
}

// Every directed boundary edge appears once and its reverse once: the boundary is a closed,
// consistently oriented surface.
bool ClosedAndConsistent(const std::vector<Eigen::Vector3i>& faces) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    const auto rev = directed.find({e.second, e.first});
    if (n != 1 || rev == directed.end() || rev->second != 1) return false;
  }
  return !faces.empty();
}

struct Flux {
  Eigen::Vector3d areaNormal = Eigen::Vector3d::Zero();  // Σ n A
  double volume = 0.0;                                   // Σ (centroid · n) A / 3
  double area = 0.0;
};

Flux BoundaryFlux(const TetMesh& m, const std::vector<Eigen::Vector3i>& faces) {
  Flux f;
  for (const auto& t : faces) {
    const Eigen::Vector3d &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    const Eigen::Vector3d an = 0.5 * (b - a).cross(c - a);  // n A
    f.areaNormal += an;
    f.volume += ((a + b + c) / 3.0).dot(an) / 3.0;
    f.area += an.norm();
  }
  return f;
}

// Gmsh 2.2 text of `m` with node tags i + 1, element tags from 1: a point and a triangle before
// the tets (to be ignored), and a $PhysicalNames section (to be skipped).
std::string Gmsh22Text(const TetMesh& m) {
  std::string s =
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 \"body\"\n"
      "$EndPhysicalNames\n$Nodes\n" +
      std::to_string(m.NumVertices()) + "\n";
  for (int i = 0; i < m.NumVertices(); ++i)
    s += std::to_string(i + 1) + " " + Str(m.vertices[i].x()) + " " + Str(m.vertices[i].y()) + " " +
         Str(m.vertices[i].z()) + "\n";
  s += "$EndNodes\n$Elements\n" + std::to_string(m.NumTets() + 2) + "\n";
  s += "1 15 2 0 1 1\n";     // point
  s += "2 2 2 0 1 1 2 3\n";  // triangle
  for (int t = 0; t < m.NumTets(); ++t) {
    s += std::to_string(t + 3) + " 4 2 1 1";
    for (int k = 0; k < 4; ++k) s += " " + std::to_string(m.tets[t][k] + 1);
    s += "\n";
  }
  return s + "$EndElements\n";
}

}  // namespace

TEST_CASE("tet box: volume, orientation, boundary", "[tet_mesh]") {
  const Eigen::Vector3d h(0.3, 0.2, 0.1);
  const int a = 3, b = 4, c = 5;
  const TetMesh m = MakeTetBox(h, Eigen::Vector3i(a, b, c));
  REQUIRE(m.NumVertices() == (a + 1) * (b + 1) * (c + 1));
  REQUIRE(m.NumTets() == 6 * a * b * c);
  const double boxVolume = 8 * h.prod();
  CHECK(std::abs(TotalVolume(m) - boxVolume) < 1e-12);
  // Every Kuhn tet of a cell has 1/6 of its volume.
  CHECK(MinVolume(m) == Approx(boxVolume / (6 * a * b * c)).epsilon(1e-12));
  std::string e;
  CHECK(ValidateTetMesh(m, "box", &e));
  const Aabb bounds = m.Bounds();
  CHECK(bounds.min == -h);
  CHECK(bounds.max == h);

  const auto faces = BoundaryFaces(m);
  CHECK(faces.size() == size_t(2 * (a * b + b * c + c * a) * 2));
  CHECK(ClosedAndConsistent(faces));
  const Flux f = BoundaryFlux(m, faces);
  CHECK(f.areaNormal.norm() < 1e-14);
  CHECK(f.volume == Approx(boxVolume).epsilon(1e-12));
  CHECK(f.area == Approx(8 * (h.x() * h.y() + h.y() * h.z() + h.z() * h.x())).epsilon(1e-12));
  // Outward: every boundary face's normal points away from the centre.
  for (const auto& t : faces) {
    const Eigen::Vector3d n =
        (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    CHECK(n.dot(m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]) > 0);
  }
  // Deterministic order: by tet, then by local face.
  CHECK(faces == BoundaryFaces(m));

  // One cell: 6 tets, 12 boundary triangles.
  const TetMesh one = MakeTetBox(Eigen::Vector3d::Ones(), Eigen::Vector3i(1, 1, 1));
  CHECK(one.NumTets() == 6);
  CHECK(BoundaryFaces(one).size() == 12);
  CHECK(TotalVolume(one) == Approx(8.0).epsilon(1e-15));
}

TEST_CASE("tet files: Gmsh 2.2, Gmsh 4.1 and TetGen give the same mesh", "[tet_mesh]") {
  const TetMesh m = MakeTetBox(Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3i(1, 1, 2));
  std::string e;

  SECTION("Gmsh 2.2 (written by hand and by WriteGmsh22)") {
    TetMesh r;
    REQUIRE(ReadTetMeshFile(Write("a.msh", Gmsh22Text(m)), &r, &e));
    CHECK(SameMesh(r, m));
    const std::string path = TempPath("written.msh");
    REQUIRE(WriteGmsh22(m, path, &e));
    TetMesh w;
    REQUIRE(ReadTetMeshFile(path, &w, &e));
    CHECK(SameMesh(w, m));
    CHECK_FALSE(WriteGmsh22(m, "/nonexistent/dir/x.msh", &e));
    CHECK(e == "/nonexistent/dir/x.msh: cannot write file");
  }

  SECTION("Gmsh 4.1: sparse node tags in two blocks, one parametric; triangles ignored") {
    // Node i has tag 100 + 7 i; block 1 holds the first 5 nodes (a volume block), block 2 the
    // rest (a parametric surface block: u v after x y z).
    auto tag = [](int i) { return std::to_string(100 + 7 * i); };
    const int n = m.NumVertices(), n1 = 5;
    std::string s =
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
        "$Entities\n0 0 1 1\n1 0 0 0 1 1 1 0 0\n1 0 0 0 1 1 1 0 1 1\n$EndEntities\n";
    s += "$Nodes\n2 " + std::to_string(n) + " 100 " + tag(n - 1) + "\n";
    s += "3 1 0 " + std::to_string(n1) + "\n";
    for (int i = 0; i < n1; ++i) s += tag(i) + "\n";
    for (int i = 0; i < n1; ++i)
      s += Str(m.vertices[i].x()) + " " + Str(m.vertices[i].y()) + " " + Str(m.vertices[i].z()) +
           "\n";
    s += "2 1 1 " + std::to_string(n - n1) + "\n";
    for (int i = n1; i < n; ++i) s += tag(i) + "\n";
    for (int i = n1; i < n; ++i)
      s += Str(m.vertices[i].x()) + " " + Str(m.vertices[i].y()) + " " + Str(m.vertices[i].z()) +
           " 0.5 0.25\n";
    s += "$EndNodes\n";
    const int half = m.NumTets() / 2;
    s += "$Elements\n3 " + std::to_string(m.NumTets() + 1) + " 1 " +
         std::to_string(m.NumTets() + 1) + "\n";
    s += "2 1 2 1\n1 " + tag(0) + " " + tag(1) + " " + tag(2) + "\n";  // a triangle
    for (int blk = 0; blk < 2; ++blk) {
      const int t0 = blk == 0 ? 0 : half, t1 = blk == 0 ? half : m.NumTets();
      s += "3 1 4 " + std::to_string(t1 - t0) + "\n";
      for (int t = t0; t < t1; ++t) {
        s += std::to_string(t + 2);
        for (int k = 0; k < 4; ++k) s += " " + tag(m.tets[t][k]);
        s += "\n";
      }
    }
    s += "$EndElements\n";
    TetMesh r;
    REQUIRE(ReadTetMeshFile(Write("b.msh", s), &r, &e));
    CHECK(SameMesh(r, m));
  }

  SECTION("TetGen: 0-based, attributes, markers and comments; read through .node or .ele") {
    std::string node = "# a TetGen node file\n" + std::to_string(m.NumVertices()) + " 3 1 1\n";
    for (int i = 0; i < m.NumVertices(); ++i)
      node += "  " + std::to_string(i) + "  " + Str(m.vertices[i].x()) + " " +
              Str(m.vertices[i].y()) + " " + Str(m.vertices[i].z()) + "  42.0  1  # point\n";
    std::string ele = std::to_string(m.NumTets()) + " 4 1\n";
    for (int t = 0; t < m.NumTets(); ++t) {
      ele += std::to_string(t);
      for (int k = 0; k < 4; ++k) ele += " " + std::to_string(m.tets[t][k]);
      ele += " 7\n";
    }
    ele += "# generated by hand\n";
    const std::string nodePath = Write("c.node", node);
    const std::string elePath = Write("c.ele", ele);
    TetMesh r1, r2;
    REQUIRE(ReadTetMeshFile(nodePath, &r1, &e));
    REQUIRE(ReadTetMeshFile(elePath, &r2, &e));
    CHECK(SameMesh(r1, m));
    CHECK(SameMesh(r2, m));
  }
}

TEST_CASE("tet files: errors name the file and the defect", "[tet_mesh]") {
  const TetMesh m = MakeTetBox(Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3i(1, 1, 2));
  TetMesh r;
  std::string e;

  SECTION("missing, empty, unknown extension") {
    const std::string missing = TempPath("does_not_exist.msh");
    CHECK_FALSE(ReadTetMeshFile(missing, &r, &e));
    CHECK(e == missing + ": cannot open file");
    const std::string empty = Write("empty.msh", "");
    CHECK_FALSE(ReadTetMeshFile(empty, &r, &e));
    CHECK(e == empty + ": empty file");
    const std::string emptyNode = Write("empty.node", "# nothing\n\n");
    Write("empty.ele", "1 4 0\n0 0 1 2 3\n");
    CHECK_FALSE(ReadTetMeshFile(emptyNode, &r, &e));
    CHECK(e == emptyNode + ": empty file");
    const std::string vtk = Write("x.vtk", "");
    CHECK_FALSE(ReadTetMeshFile(vtk, &r, &e));
    CHECK(e.rfind(vtk + ": unknown tet mesh format \".vtk\"", 0) == 0);
    // .ele without its .node.
    const std::string lonely = Write("lonely.ele", "1 4 0\n0 0 1 2 3\n");
    CHECK_FALSE(ReadTetMeshFile(lonely, &r, &e));
    CHECK(e == TempPath("lonely.node") + ": cannot open file (the node file of " + lonely + ")");
  }

  SECTION("a tet references a node that does not exist") {
    std::string s = Gmsh22Text(m);
    // The last tet (element 14) is on the line before $EndElements; make it reference node 99.
    const std::string lastTet = "14 4 2 1 1";
    const size_t at = s.find(lastTet);
    REQUIRE(at != std::string::npos);
    const size_t eol = s.find('\n', at);
    s.replace(at, eol - at, "14 4 2 1 1 1 2 3 99");
    const int line = static_cast<int>(std::count(s.begin(), s.begin() + at, '\n')) + 1;
    const std::string path = Write("badref.msh", s);
    CHECK_FALSE(ReadTetMeshFile(path, &r, &e));
    CHECK(e == path + ": line " + std::to_string(line) +
                   ": tet 14 references node 99 which does not exist");

    const std::string node = Write("badref.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
    const std::string ele = Write("badref.ele", "2 4 0\n1 1 2 3 4\n2 1 2 3 5\n");
    CHECK_FALSE(ReadTetMeshFile(node, &r, &e));
    CHECK(e == ele +
                   ": line 3: tet 2 references node 5 which does not exist (points are "
                   "numbered 1..4 in " +
                   node + ")");
  }

  SECTION("inverted and degenerate tets are refused by ValidateTetMesh") {
    TetMesh bad = m;
    std::swap(bad.tets[3][0], bad.tets[3][1]);
    std::swap(bad.tets[5][2], bad.tets[5][3]);
    const std::string inverted = Write("inverted.msh", Gmsh22Text(bad));
    REQUIRE(ReadTetMeshFile(inverted, &r, &e));  // reading does not judge geometry
    CHECK_FALSE(ValidateTetMesh(r, inverted, &e));
    // The box is 0.2 x 0.4 x 0.6 m in 12 tets of 0.004 m^3.
    CHECK(e.rfind(inverted + ": tet 3 is inverted (signed volume -0.004 < 0); 0 of 12 tets are "
                             "degenerate",
                  0) == 0);
    CHECK(e.find(", 2 inverted") != std::string::npos);

    // A flat tet: four coplanar points.
    const std::string flat =
        Write("degenerate.node", "5 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 0\n");
    Write("degenerate.ele", "2 4 0\n0 0 1 2 3\n1 0 1 4 2\n");
    REQUIRE(ReadTetMeshFile(flat, &r, &e));
    CHECK_FALSE(ValidateTetMesh(r, flat, &e));
    CHECK(e.rfind(flat + ": tet 1 is degenerate (volume 0); 1 of 2 tets are degenerate", 0) == 0);
  }

  SECTION("binary, unsupported versions, no tets, truncated, malformed") {
    const std::string bin =
        Write("binary.msh",
              std::string("$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\n", 25) + "$EndMeshFormat\n");
    CHECK_FALSE(ReadTetMeshFile(bin, &r, &e));
    CHECK(e.rfind(bin + ": line 2: binary Gmsh file (file-type 1 in $MeshFormat): only ASCII", 0) ==
          0);
    const std::string v40 = Write("v40.msh", "$MeshFormat\n4 0 8\n$EndMeshFormat\n");
    CHECK_FALSE(ReadTetMeshFile(v40, &r, &e));
    CHECK(e == v40 + ": line 2: unsupported Gmsh format version 4 (supported: 2.2, 4.1)");
    const std::string v1 = Write("v1.msh", "$NOD\n1\n1 0 0 0\n$ENDNOD\n");
    CHECK_FALSE(ReadTetMeshFile(v1, &r, &e));
    CHECK(e.rfind(v1 + ": line 1: expected $MeshFormat", 0) == 0);
    const std::string tris = Write("tris.msh",
                                   "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n"
                                   "2 1 0 0\n3 0 1 0\n$EndNodes\n$Elements\n1\n1 2 2 0 1 1 2 3\n"
                                   "$EndElements\n");
    CHECK_FALSE(ReadTetMeshFile(tris, &r, &e));
    CHECK(e == tris +
                   ": no tetrahedra (element type 4) in $Elements (found only elements 1 of "
                   "type 2 (3-node triangle))");
    const std::string truncated = Write("truncated.msh",
                                        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n"
                                        "1 0 0 0\n2 1 0 0\n$EndNodes\n");
    CHECK_FALSE(ReadTetMeshFile(truncated, &r, &e));
    CHECK(e == truncated + ": line 8: $Nodes declares 3 nodes but $EndNodes comes after 2");
    const std::string nan = Write("nan.msh",
                                  "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 nan 0\n"
                                  "$EndNodes\n");
    CHECK_FALSE(ReadTetMeshFile(nan, &r, &e));
    CHECK(e == nan + ": line 6: malformed coordinates of node 1: \"1 0 nan 0\"");
    const std::string twice = Write("twice.msh",
                                    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n"
                                    "1 1 0 0\n$EndNodes\n");
    CHECK_FALSE(ReadTetMeshFile(twice, &r, &e));
    CHECK(e == twice + ": line 7: node 1 is defined twice");
    const std::string short4 = Write("short.msh",
                                     "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n"
                                     "2 1 0 0\n3 0 1 0\n$EndNodes\n$Elements\n1\n5 4 2 0 1 1 2 3\n"
                                     "$EndElements\n");
    CHECK_FALSE(ReadTetMeshFile(short4, &r, &e));
    CHECK(e == short4 +
                   ": line 12: element 5 (type 4, a 4-node tetrahedron) has 3 node tags, "
                   "expected 4");
    const std::string gap = Write("gap.node", "3 3 0 0\n1 0 0 0\n2 1 0 0\n4 0 1 0\n");
    Write("gap.ele", "1 4 0\n1 1 2 3 3\n");
    CHECK_FALSE(ReadTetMeshFile(gap, &r, &e));
    CHECK(e == gap + ": line 4: points must be numbered consecutively: expected 3, got 4");
    const std::string fewTets = Write("few.ele", "2 4 0\n0 0 1 2 3\n");
    Write("few.node", "4 3\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n");
    CHECK_FALSE(ReadTetMeshFile(fewTets, &r, &e));
    // The header's count is checked against the file's size before any line is read.
    CHECK(e == fewTets + ": line 1: the header declares 2 tets, which need at least 20 bytes (10 "
                         "per line), but the file holds 16 bytes");
    const std::string fewPoints =
        Write("fewp.node", "4 3\n0 0 0 0\n1 1 0 0\n# a comment, long enough for 4 points\n");
    CHECK_FALSE(ReadTetMeshFile(fewPoints, &r, &e));
    CHECK(e == fewPoints + ": file ends after 2 of 4 points");
  }

  SECTION("ValidateTetMesh: structure") {
    TetMesh bad = m;
    CHECK(ValidateTetMesh(bad, "ok", &e));
    bad.tets[2][1] = bad.tets[2][3];
    CHECK_FALSE(ValidateTetMesh(bad, "rep", &e));
    CHECK(e == "rep: tet 2 repeats vertex " + std::to_string(bad.tets[2][3]));
    bad = m;
    bad.tets[4][0] = 12;
    CHECK_FALSE(ValidateTetMesh(bad, "range", &e));
    CHECK(e == "range: tet 4 references vertex 12 which does not exist (12 vertices)");
    bad = m;
    bad.vertices[1].y() = NAN;
    CHECK_FALSE(ValidateTetMesh(bad, "nan", &e));
    CHECK(e.rfind("nan: vertex 1 has a non-finite coordinate", 0) == 0);
    CHECK_FALSE(ValidateTetMesh(TetMesh(), "empty", &e));
    CHECK(e == "empty: no tets");
  }
}

TEST_CASE("tet mesher: CGAL Mesh_3 of an icosphere", "[tet_mesh]") {
  const double r = 0.1, h = 0.03;
  const TriangleMesh sphere = MakeIcosphere(r, 3);
  TetMesh a, b;
  std::string e;
  REQUIRE(MeshTetsFromSurface(sphere, h, &a, &e));
  REQUIRE(ValidateTetMesh(a, "sphere", &e));
  CHECK(MinVolume(a) > 0);
  const double exact = 4.0 / 3.0 * M_PI * r * r * r;
  const double volume = TotalVolume(a);
  CAPTURE(a.NumVertices(), a.NumTets(), volume / exact);
  // The boundary is made of chords of the input (icosphere) surface, within facet_distance =
  // h/20 = 1.5 mm of it: the volume falls short of the input surface's by less than 3 % at
  // r/h = 3.3 (measured 0.970 of the exact sphere).
  const double inputVolume = ComputeMassProperties(sphere, 1.0).volume;
  CHECK(volume < inputVolume);
  CHECK(std::abs(volume / inputVolume - 1) < 0.03);
  // Only used vertices.
  std::vector<int> used(a.NumVertices(), 0);
  for (const auto& t : a.tets)
    for (int k = 0; k < 4; ++k) used[t[k]] = 1;
  CHECK(std::count(used.begin(), used.end(), 0) == 0);
  // Closed, outward boundary enclosing the same volume.
  const auto faces = BoundaryFaces(a);
  CHECK(ClosedAndConsistent(faces));
  const Flux f = BoundaryFlux(a, faces);
  CHECK(f.areaNormal.norm() < 1e-12);
  CHECK(f.volume == Approx(volume).epsilon(1e-10));
  // Boundary vertices lie on (or just inside) the sphere.
  for (const auto& t : faces)
    for (int k = 0; k < 3; ++k) CHECK(a.vertices[t[k]].norm() == Approx(r).epsilon(0.02));
  // Deterministic.
  REQUIRE(MeshTetsFromSurface(sphere, h, &b, &e));
  CHECK(SameMesh(a, b));

  TetMesh fine;
  REQUIRE(MeshTetsFromSurface(sphere, h / 2, &fine, &e));
  REQUIRE(ValidateTetMesh(fine, "fine sphere", &e));
  CAPTURE(fine.NumTets(), TotalVolume(fine) / exact);
  CHECK(std::abs(TotalVolume(fine) / exact - 1) < 0.03);

  // An inward-oriented surface bounds the same solid: still positive tets.
  TriangleMesh inward = sphere;
  for (auto& t : inward.faces) std::swap(t[1], t[2]);
  TetMesh in;
  REQUIRE(MeshTetsFromSurface(inward, h, &in, &e));
  REQUIRE(ValidateTetMesh(in, "inward sphere", &e));
  CHECK(TotalVolume(in) == Approx(volume).epsilon(0.01));

  // MakeTetSphere: icosphere with edges <= h/2 (4 subdivisions here).
  const TetMesh ball = MakeTetSphere(r, h);
  REQUIRE(ValidateTetMesh(ball, "ball", &e));
  CHECK(std::abs(TotalVolume(ball) / exact - 1) < 0.03);
  CHECK(ClosedAndConsistent(BoundaryFaces(ball)));
}

TEST_CASE("tet mesher: refused inputs", "[tet_mesh]") {
  TetMesh out;
  std::string e;
  const TriangleMesh sphere = MakeIcosphere(0.1, 1);
  CHECK_FALSE(MeshTetsFromSurface(sphere, 0.0, &out, &e));
  CHECK(e == "MeshTetsFromSurface: edge length must be positive and finite (got 0 m)");
  CHECK_FALSE(MeshTetsFromSurface(sphere, -1.0, &out, &e));
  TriangleMesh open = sphere;
  open.faces.pop_back();
  CHECK_FALSE(MeshTetsFromSurface(open, 0.03, &out, &e));
  CHECK(e.rfind("MeshTetsFromSurface: the surface is not closed: edge (", 0) == 0);
  CHECK(e.find("belongs to only one face") != std::string::npos);
  CHECK_FALSE(MeshTetsFromSurface(MakePlanePatch(1.0, 2), 0.1, &out, &e));
  CHECK(e.find("not closed") != std::string::npos);
  TriangleMesh flipped = sphere;
  std::swap(flipped.faces[0][1], flipped.faces[0][2]);
  CHECK_FALSE(MeshTetsFromSurface(flipped, 0.03, &out, &e));
  CHECK(e.find("not consistently oriented") != std::string::npos);
  CHECK_FALSE(MeshTetsFromSurface(TriangleMesh(), 0.03, &out, &e));
  CHECK(e == "MeshTetsFromSurface: the surface has no faces");
  CHECK_FALSE(MeshTetsFromSurface(sphere, 1e-5, &out, &e));
  CHECK(e.find("use a larger edge length") != std::string::npos);
  CHECK(MakeTetSphere(0.1, 0.0).tets.empty());
}

TEST_CASE("tet files: shipped cube meshes read back and validate", "[tet_mesh]") {
  const std::string dir = std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/meshes/";
  TetMesh m;
  std::string e;
  REQUIRE(ReadTetMeshFile(dir + "cube_0.2.msh", &m, &e));
  CHECK(ValidateTetMesh(m, "cube_0.2.msh", &e));
  CHECK(SameMesh(m, MakeTetBox(Eigen::Vector3d::Constant(0.1), Eigen::Vector3i(4, 4, 4))));
  CHECK(TotalVolume(m) == Approx(0.008).epsilon(1e-12));
  REQUIRE(ReadTetMeshFile(dir + "cube_0.2.node", &m, &e));
  CHECK(ValidateTetMesh(m, "cube_0.2.node", &e));
  CHECK(SameMesh(m, MakeTetBox(Eigen::Vector3d::Constant(0.1), Eigen::Vector3i(2, 2, 2))));
  CHECK(BoundaryFaces(m).size() == 2 * 12 * 2);
}
