// Bad mesh files: each is refused with a message that names the file, the place (line or item)
// and the rule, before memory is allocated for a declared count.
#include <catch2/catch.hpp>
#include <fstream>
#include <string>

#include "geometry/mesh_io.h"
#include "geometry/mesh_limits.h"
#include "geometry/tet_mesh.h"

using namespace superdex;

namespace {

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = std::string(SUPERDEX_BINARY_DIR) + "/bad_input_" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The error of reading `text` as file `name` (a surface mesh, or a tet mesh for .msh/.node/.ele).
std::string Error(const std::string& name, const std::string& text) {
  const std::string path = Write(name, text);
  std::string e;
  const std::string ext = name.substr(name.find_last_of('.') + 1);
  bool ok;
  if (ext == "msh" || ext == "node" || ext == "ele") {
    TetMesh m;
    ok = ReadTetMeshFile(path, &m, &e);
  } else {
    TriangleMesh m;
    ok = ReadMeshFile(path, &m, &e);
  }
  if (ok) return "<read>";
  REQUIRE(e.rfind(path + ": ", 0) == 0);  // every message starts with the file
  return e.substr(path.size() + 2);
}

const char* kPlyHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n";

std::string Replace(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("bad input: Gmsh files", "[geometry][bad_input]") {
  // An unclosed extra section used to read freed memory and end in basic_string::_M_create.
  CHECK(Error("open_section.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Foo\nbar baz\n") ==
        "line 4: $Foo is not closed by $EndFoo");
  // A 4.1 node block of 1e9 nodes used to allocate 7.8 GB before failing.
  CHECK(Error("huge_block.msh",
              "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1000000000 1 1000000000\n"
              "3 1 0 1000000000\n1\n0 0 0\n$EndNodes\n") ==
        "line 5: $Nodes declares 1000000000 nodes (limit 10000000 per file)");
  CHECK(Error("block_beyond_total.msh",
              "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n3 1 0 999999\n1\n2\n"
              "0 0 0\n1 0 0\n$EndNodes\n") ==
        "line 6: node block of 999999 nodes, but $Nodes declares 2 nodes of which 0 came before");
  CHECK(Error("many_nodes.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5000\n1 0 0 0\n") ==
        "line 5: $Nodes declares 5000 nodes, which need at least 40000 bytes (8 per line), but "
        "the file holds 55 bytes");
  CHECK(Error("many_elements.msh",
              "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n0 0 0 0\n$EndNodes\n$Elements\n"
              "1 99999999999 1 2\n$EndElements\n") ==
        "line 8: $Elements declares 99999999999 elements (limit 50000000 per file)");
}

TEST_CASE("bad input: TetGen files", "[geometry][bad_input]") {
  // Headers of 2147483646 points or tets used to end in std::bad_alloc.
  Write("huge.ele", "1 4 0\n1 1 2 3 4\n");
  CHECK(Error("huge.node", "2147483646 3 0 0\n1 0 0 0\n") ==
        "line 1: the header declares 2147483646 points (limit 10000000 per file)");
  Write("huge_tets.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
  const std::string ele = Write("huge_tets.ele", "2147483646 4 0\n1 1 2 3 4\n");
  TetMesh m;
  std::string e;
  CHECK_FALSE(ReadTetMeshFile(ele, &m, &e));
  CHECK(e == ele + ": line 1: the header declares 2147483646 tets (limit 50000000 per file)");
}

TEST_CASE("bad input: OFF files", "[geometry][bad_input]") {
  CHECK(Error("empty.off", "") == "the file is empty (expected the OFF keyword)");
  CHECK(Error("keyword.off", "PLY\n3 1 0\n") == "line 1: expected the OFF keyword, got \"PLY\"");
  CHECK(Error("four.off", "4OFF\n1 0 0\n") ==
        "line 1: 4OFF: only 3-dimensional OFF files are supported");
  CHECK(Error("counts.off", "OFF\n3 x 0\n") ==
        "line 2: malformed counts (expected \"vertices faces edges\")");
  CHECK(Error("declared.off", "OFF\n999999 1 0\n0 0 0\n") ==
        "line 2: the header declares 999999 vertices, which need at least 5999994 bytes (6 per "
        "line), but the file holds 21 bytes");
  CHECK(Error("vertex.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n") ==
        "line 4: malformed vertex (expected \"x y z\" with finite numbers)");
  CHECK(Error("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n") ==
        "line 6: face 0: vertex index 7 out of range (3 vertices, numbered from 0)");
  CHECK(Error("short_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n9 0 1 2\n") ==
        "line 6: malformed face (expected \"n i_1 ... i_n\")");
  CHECK(Error("truncated.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n# the end\n") ==
        "the file ends after 1 of 2 faces");
}

TEST_CASE("bad input: STL files", "[geometry][bad_input]") {
  CHECK(Error("noend.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                           "vertex 0 1 0\nendloop\nendfacet\n") ==
        "the file ends without \"endsolid\"");
  CHECK(Error("badvertex.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n") ==
        "line 4: malformed vertex (expected \"vertex x y z\" with finite numbers)");
  CHECK(Error("loop.stl", "solid s\nfacet normal 0 0 1\nvertex 0 0 0\n") ==
        "line 3: expected \"outer loop\", got \"vertex\"");
  // Binary: 84 bytes of header and count, then 50 per triangle.
  std::string binary(84, '\0');
  binary[80] = 2;  // two triangles declared, none present
  CHECK(Error("truncated_binary.stl", binary + std::string(50, '\0')) ==
        "binary header: declares 2 triangles, which need 184 bytes (84 + 50 per triangle), but "
        "the file holds 134 (truncated, or not an STL file)");
  std::string nan = binary;
  nan[80] = 1;
  std::string triangle(50, '\0');
  const float bad = NAN;
  std::memcpy(&triangle[12], &bad, 4);
  CHECK(Error("nan_binary.stl", nan + triangle) ==
        "triangle 0: vertex coordinates must be finite numbers");
}

TEST_CASE("bad input: PLY files", "[geometry][bad_input]") {
  // A negative index used to be reported as 18446744073709551615.
  CHECK(Error("negative.ply", std::string(kPlyHeader) + "3 0 1 -1\n") ==
        "line 13: face 0: vertex index -1 out of range (3 vertices, numbered from 0)");
  CHECK(Error("format.ply", Replace(kPlyHeader, "ascii", "utf8")) ==
        "line 2: unknown format \"utf8\"");
  CHECK(Error("noindices.ply", Replace(kPlyHeader, "vertex_indices", "corners") + "3 0 1 2\n") ==
        "line 7: element face has no list property vertex_indices");
  CHECK(Error("count.ply", std::string(kPlyHeader) + "200 0 1 2\n") ==
        "line 13: a list of 200 values does not fit in the rest of the data");
  CHECK(Error("items.ply", Replace(kPlyHeader, "element vertex 3", "element vertex 3000000")) ==
        "line 3: declares 3000000 items of element vertex, which need at least 18000000 bytes "
        "(6 per line), but the file holds 178 bytes");
  CHECK(Error("noheader.ply", "ply\nformat ascii 1.0\nelement vertex 3\n") ==
        "the file ends inside the header (no end_header)");
  const std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n";
  CHECK(Error("binary.ply", binary + std::string(20, '\0')) ==
        "vertex 1: the file ends inside it (binary data truncated)");
}

TEST_CASE("bad input: tet meshes beyond double precision's range", "[geometry][bad_input]") {
  TetMesh m = MakeTetBox(Eigen::Vector3d::Constant(1e155), Eigen::Vector3i(1, 1, 1));
  std::string e;
  CHECK_FALSE(ValidateTetMesh(m, "huge", &e));
  CHECK(e == "huge: the mesh's extent 3.4641e+155 m is out of double precision's range for tet "
             "volumes (its cube must be within 1e-290 to 1e290 m^3)");
}
