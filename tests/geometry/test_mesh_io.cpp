// Mesh files: OBJ, OFF, STL and PLY read to the same triangles; bad files give clear errors.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <fstream>

#include "geometry/mesh_io.h"

using namespace superdex;

namespace {

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = std::string(SUPERDEX_BINARY_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// A unit tetrahedron, outward oriented.
const char* kObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
const char* kOff = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
const char* kPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

}  // namespace

TEST_CASE("mesh files: OBJ, OFF, PLY and STL give the same tetrahedron", "[geometry][mesh][io]") {
  TriangleMesh obj, off, ply, stl;
  std::string e;
  REQUIRE(ReadMeshFile(Write("tet.obj", kObj), &obj, &e));
  REQUIRE(ReadMeshFile(Write("tet.off", kOff), &off, &e));
  REQUIRE(ReadMeshFile(Write("tet.ply", kPly), &ply, &e));
  // STL is a soup of triangles; the reader merges identical points.
  std::string stlText = "solid tet\n";
  for (const auto& f : obj.faces) {
    stlText += "facet normal 0 0 0\nouter loop\n";
    for (int k = 0; k < 3; ++k) {
      const auto& v = obj.vertices[f[k]];
      stlText += "vertex " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " +
                 std::to_string(v.z()) + "\n";
    }
    stlText += "endloop\nendfacet\n";
  }
  stlText += "endsolid tet\n";
  REQUIRE(ReadMeshFile(Write("tet.stl", stlText), &stl, &e));
  for (const TriangleMesh* m : {&off, &ply}) {
    REQUIRE(m->faces.size() == obj.faces.size());
    REQUIRE(m->vertices.size() == obj.vertices.size());
    for (size_t f = 0; f < obj.faces.size(); ++f) CHECK(m->faces[f] == obj.faces[f]);
  }
  CHECK(stl.faces.size() == 4);
  auto volume = [](const TriangleMesh& m) {
    double v = 0;
    for (const auto& f : m.faces)
      v += m.vertices[f[0]].dot(m.vertices[f[1]].cross(m.vertices[f[2]])) / 6;
    return v;
  };
  CHECK(volume(stl) == Approx(1.0 / 6));
  CHECK(volume(off) == Approx(1.0 / 6));
}

TEST_CASE("mesh files: missing, empty, unknown and malformed files", "[geometry][mesh][io]") {
  TriangleMesh m;
  std::string e;
  CHECK_FALSE(ReadMeshFile("/nonexistent/x.off", &m, &e));
  CHECK(e == "/nonexistent/x.off: cannot open file");
  const std::string empty = Write("empty.off", "");
  CHECK_FALSE(ReadMeshFile(empty, &m, &e));
  CHECK(e == empty + ": the file is empty (expected the OFF keyword)");
  const std::string unknown = Write("tet.xyz", "1 2 3\n");
  CHECK_FALSE(ReadMeshFile(unknown, &m, &e));
  CHECK(e == unknown + ": unknown mesh format \".xyz\" (supported: .obj, .off, .stl, .ply)");
  const std::string noFaces = Write("nofaces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
  CHECK_FALSE(ReadMeshFile(noFaces, &m, &e));
  CHECK(e == noFaces + ": no faces");
}
