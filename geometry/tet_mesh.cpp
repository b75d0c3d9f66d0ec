// Tetrahedral meshes (see tet_mesh.h): queries, validation, boundary, box generator, Gmsh and
// TetGen files. Meshing of surfaces (CGAL Mesh_3) lives in tet_mesher.cpp.
#include "geometry/tet_mesh.h"
#include "geometry/mesh_limits.h"
#include "geometry/number_text.h"
#include "geometry/token_parsing.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <unordered_map>
#include <utility>

namespace superdex {

// ---------------------------------------------------------------------------------------------
// Queries

double TetMesh::TetVolume(int t) const {
  const Eigen::Vector4i& q = tets[t];
  const Eigen::Vector3d& x0 = vertices[q[0]];
  return (vertices[q[1]] - x0).dot((vertices[q[2]] - x0).cross(vertices[q[3]] - x0)) / 6.0;
}

namespace {

std::vector<std::string> Split(const std::string& line) {
  std::vector<std::string> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

// Reads a text file line by line, counting lines, skipping blank lines (and, if `hashComments`,
// everything from '#' to the end of a line).
class LineReader {
 public:
  LineReader(std::istream& in, bool hashComments) : in_(in), hashComments_(hashComments) {}
  // Tokens of the next non-blank line; false at the end of the file.
  bool Next(std::vector<std::string>* tokens) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_;
      if (hashComments_) {
        const size_t hash = line.find('#');
        if (hash != std::string::npos) line.erase(hash);
      }
      *tokens = Split(line);
      if (!tokens->empty()) return true;
    }
    return false;
  }
  int Line() const { return line_; }
  bool Bad() const { return in_.bad(); }

 private:
  std::istream& in_;
  bool hashComments_;
  int line_ = 0;
};

// Error reporting for one file: "<path>: <message>" or "<path>: line <n>: <message>".
struct Failer {
  std::string path;
  std::string* error;
  bool operator()(const std::string& message) const {
    if (error) *error = path + ": " + message;
    return false;
  }
  bool operator()(int line, const std::string& message) const {
    if (error) *error = path + ": line " + std::to_string(line) + ": " + message;
    return false;
  }
};

std::string Quote(const std::vector<std::string>& tokens) {
  std::string s;
  for (size_t k = 0; k < tokens.size() && k < 8; ++k) s += (k ? " " : "") + tokens[k];
  if (tokens.size() > 8) s += " ...";
  return "\"" + s + "\"";
}

std::string Extension(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// ---------------------------------------------------------------------------------------------
// Gmsh

const char* GmshTypeName(long type) {
  switch (type) {
    case 1:
      return "2-node line";
    case 2:
      return "3-node triangle";
    case 3:
      return "4-node quadrangle";
    case 4:
      return "4-node tetrahedron";
    case 5:
      return "8-node hexahedron";
    case 6:
      return "6-node prism";
    case 7:
      return "5-node pyramid";
    case 8:
      return "3-node line";
    case 9:
      return "6-node triangle";
    case 11:
      return "10-node tetrahedron";
    case 15:
      return "point";
    default:
      return "other";
  }
}

struct PendingTet {
  int line;
  long tag;
  std::array<long, 4> nodes;
};

struct GmshState {
  double fileBytes = -1;  // the file's size (-1: unknown), which bounds every declared count
  TetMesh mesh;
  std::unordered_map<long, int> nodeIndex;  // Gmsh node tag -> 0-based vertex index
  std::vector<PendingTet> tets;
  std::map<long, long> ignored;  // element type -> count
};

bool AddNode(const Failer& fail, int line, long tag, const std::vector<std::string>& t,
             size_t first, GmshState* s) {
  double x[3];
  for (int k = 0; k < 3; ++k)
    if (first + k >= t.size() || !ParseDouble(t[first + k], &x[k]))
      return fail(line, "malformed coordinates of node " + std::to_string(tag) + ": " + Quote(t));
  if (!s->nodeIndex.emplace(tag, s->mesh.NumVertices()).second)
    return fail(line, "node " + std::to_string(tag) + " is defined twice");
  if (s->mesh.vertices.size() >= static_cast<size_t>(INT_MAX)) return fail(line, "too many nodes");
  s->mesh.vertices.emplace_back(x[0], x[1], x[2]);
  return true;
}

// Reads one element given its type, tag and node tokens (t[first..]).
bool AddElement(const Failer& fail, int line, long tag, long type,
                const std::vector<std::string>& t, size_t first, GmshState* s) {
  if (type != 4) {
    ++s->ignored[type];
    return true;
  }
  if (t.size() - first != 4)
    return fail(line, "element " + std::to_string(tag) + " (type 4, a 4-node tetrahedron) has " +
                          std::to_string(t.size() - first) + " node tags, expected 4");
  PendingTet p{line, tag, {}};
  for (int k = 0; k < 4; ++k)
    if (!ParseLong(t[first + k], &p.nodes[k]))
      return fail(line,
                  "malformed node tag \"" + t[first + k] + "\" in element " + std::to_string(tag));
  s->tets.push_back(p);
  return true;
}

// The size of the stream's file in bytes (-1 if unknown); the stream is left at its start.
double FileBytes(std::istream& in) {
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.clear();
  in.seekg(0, std::ios::beg);
  return size >= 0 ? static_cast<double>(size) : -1.0;
}

// A declared count within the limit and the file's size (limits::CheckDeclaredCount), else the
// message at `line`. Checked before anything is allocated for the items.
bool CheckCount(const Failer& fail, int line, const std::string& section, long count, double limit,
                double bytesPerItem, double fileBytes, const std::string& what) {
  const std::string m = limits::CheckDeclaredCount(double(count), limit, bytesPerItem, fileBytes,
                                                   what);
  return m.empty() || fail(line, section + " " + m);
}

// Reads the declared count(s) of a section header line.
bool ParseCounts(const Failer& fail, LineReader& r, const char* section, size_t n,
                 std::vector<long>* out) {
  std::vector<std::string> t;
  if (!r.Next(&t)) return fail(std::string("file ends inside ") + section);
  out->assign(n, 0);
  if (t.size() < n)
    return fail(r.Line(), std::string("malformed ") + section + " header " + Quote(t));
  for (size_t k = 0; k < n; ++k)
    if (!ParseLong(t[k], &(*out)[k]) || (*out)[k] < 0)
      return fail(r.Line(), std::string("malformed ") + section + " header " + Quote(t));
  return true;
}

// Next data line of a section that declared `expected` entries of which `got` were read.
bool NextData(const Failer& fail, LineReader& r, const std::string& section, const char* what,
              long expected, long got, std::vector<std::string>* t) {
  if (!r.Next(t))
    return fail("file ends inside " + section + " after " + std::to_string(got) + " of " +
                std::to_string(expected) + " " + what);
  if ((*t)[0][0] == '$')
    return fail(r.Line(), section + " declares " + std::to_string(expected) + " " + what + " but " +
                              (*t)[0] + " comes after " + std::to_string(got));
  return true;
}

bool ExpectEnd(const Failer& fail, LineReader& r, const std::string& end) {
  std::vector<std::string> t;
  if (!r.Next(&t)) return fail("file ends before " + end);
  if (t[0] != end) return fail(r.Line(), "expected " + end + ", got " + Quote(t));
  return true;
}

// A Gmsh section of items ($Nodes, $Elements): its names and the limits on its declared counts.
struct ItemSection {
  const char* name;     ///< "$Nodes"
  const char* item;     ///< "node"
  const char* items;    ///< "nodes"
  double limit;         ///< the most items (and entity blocks) a file may declare
  double bytesPerItem;  ///< the fewest bytes an item takes in a format 4.1 file
  const char* end;      ///< "$EndNodes"
};
const ItemSection kNodeSection{"$Nodes", "node", "nodes", limits::kMaxMeshVertices, 8,
                               "$EndNodes"};
const ItemSection kElementSection{"$Elements", "element", "elements", limits::kMaxMeshElements,
                                  4, "$EndElements"};

// A format 2 section: the count, then one item a line, each read by readItem(tokens), then the
// section's end. An item line takes at least 8 bytes.
template <typename ReadItem>
bool ReadItemLines(const Failer& fail, LineReader& r, const ItemSection& x, double fileBytes,
                   ReadItem readItem) {
  std::vector<long> c;
  if (!ParseCounts(fail, r, x.name, 1, &c) ||
      !CheckCount(fail, r.Line(), x.name, c[0], x.limit, 8, fileBytes, x.items))
    return false;
  std::vector<std::string> t;
  for (long i = 0; i < c[0]; ++i)
    if (!NextData(fail, r, x.name, x.items, c[0], i, &t) || !readItem(t)) return false;
  return ExpectEnd(fail, r, x.end);
}

bool ReadGmshNodes2(const Failer& fail, LineReader& r, GmshState* s) {
  auto readNode = [&](const std::vector<std::string>& t) {
    long tag;
    if (!ParseLong(t[0], &tag)) return fail(r.Line(), "malformed node line " + Quote(t));
    return AddNode(fail, r.Line(), tag, t, 1, s);
  };
  return ReadItemLines(fail, r, kNodeSection, s->fileBytes, readNode);
}

bool ReadGmshElements2(const Failer& fail, LineReader& r, GmshState* s) {
  auto readElement = [&](const std::vector<std::string>& t) {
    // elm-number elm-type number-of-tags <tags> node-number-list
    long tag, type, ntags;
    if (t.size() < 3 || !ParseLong(t[0], &tag) || !ParseLong(t[1], &type) ||
        !ParseLong(t[2], &ntags) || ntags < 0 || 3 + static_cast<size_t>(ntags) > t.size())
      return fail(r.Line(), "malformed element line " + Quote(t));
    return AddElement(fail, r.Line(), tag, type, t, 3 + static_cast<size_t>(ntags), s);
  };
  return ReadItemLines(fail, r, kElementSection, s->fileBytes, readElement);
}

// A format 4.1 section of entity blocks: the header "numEntityBlocks numItems minTag maxTag",
// then per block a line "entityDim entityTag <x> numItemsInBlock" (x: parametric for $Nodes, the
// element type for $Elements) and the block's lines, then the section's end. readBlock(header,
// total, read) reads one block's lines (`total`: the items the section declares, `read`: those
// of the blocks before it) and returns false on a problem.
template <typename ReadBlock>
bool ReadEntityBlocks(const Failer& fail, LineReader& r, const ItemSection& x, double fileBytes,
                      ReadBlock readBlock) {
  std::vector<long> c;
  if (!ParseCounts(fail, r, x.name, 4, &c) ||
      !CheckCount(fail, r.Line(), x.name, c[1], x.limit, x.bytesPerItem, fileBytes, x.items) ||
      !CheckCount(fail, r.Line(), x.name, c[0], x.limit, 8, fileBytes, "entity blocks"))
    return false;
  const std::string name = x.name, item = x.item, items = x.items;
  long read = 0;
  std::vector<std::string> t;
  for (long b = 0; b < c[0]; ++b) {
    if (!NextData(fail, r, name, "entity blocks", c[0], b, &t)) return false;
    long h[4];
    if (t.size() != 4 || !ParseLong(t[0], &h[0]) || !ParseLong(t[1], &h[1]) ||
        !ParseLong(t[2], &h[2]) || !ParseLong(t[3], &h[3]) || h[3] < 0)
      return fail(r.Line(), "malformed " + item + " block header " + Quote(t));
    if (h[3] > c[1] - read)
      return fail(r.Line(), item + " block of " + std::to_string(h[3]) + " " + items + ", but " +
                                name + " declares " + std::to_string(c[1]) + " " + items +
                                " of which " + std::to_string(read) + " came before");
    if (!readBlock(h, c[1], read)) return false;
    read += h[3];
  }
  if (read != c[1])
    return fail(r.Line(), name + " declares " + std::to_string(c[1]) + " " + items +
                              ", its blocks hold " + std::to_string(read));
  return ExpectEnd(fail, r, x.end);
}

bool ReadGmshNodes41(const Failer& fail, LineReader& r, GmshState* s) {
  // Per block: the node tags, one a line, then the coordinates, one node a line.
  std::vector<std::string> t;
  auto readBlock = [&](const long* h, long total, long read) {
    std::vector<long> tags;  // grows with the lines read, not with the declared count
    for (long i = 0; i < h[3]; ++i) {
      if (!NextData(fail, r, "$Nodes", "nodes", total, read + i, &t)) return false;
      long tag;
      if (t.size() != 1 || !ParseLong(t[0], &tag))
        return fail(r.Line(), "malformed node tag line " + Quote(t));
      tags.push_back(tag);
    }
    for (long i = 0; i < h[3]; ++i) {
      if (!NextData(fail, r, "$Nodes", "node coordinates", total, read + i, &t)) return false;
      if (!AddNode(fail, r.Line(), tags[i], t, 0, s)) return false;
    }
    return true;
  };
  return ReadEntityBlocks(fail, r, kNodeSection, s->fileBytes, readBlock);
}

bool ReadGmshElements41(const Failer& fail, LineReader& r, GmshState* s) {
  // Per block (its header's third number is the element type): "tag node ..." per element.
  std::vector<std::string> t;
  auto readBlock = [&](const long* h, long total, long read) {
    for (long i = 0; i < h[3]; ++i) {
      if (!NextData(fail, r, "$Elements", "elements", total, read + i, &t)) return false;
      long tag;
      if (!ParseLong(t[0], &tag)) return fail(r.Line(), "malformed element line " + Quote(t));
      if (!AddElement(fail, r.Line(), tag, h[2], t, 1, s)) return false;
    }
    return true;
  };
  return ReadEntityBlocks(fail, r, kElementSection, s->fileBytes, readBlock);
}

bool ReadGmsh(const std::string& path, TetMesh* mesh, std::string* error) {
  const Failer fail{path, error};
  std::ifstream in(path, std::ios::binary);
  if (!in) return fail("cannot open file");
  const double fileBytes = FileBytes(in);
  LineReader r(in, false);
  std::vector<std::string> t;
  if (!r.Next(&t)) return fail("empty file");
  if (t[0] != "$MeshFormat")
    return fail(r.Line(), "expected $MeshFormat, got " + Quote(t) +
                              " (not a Gmsh file, or Gmsh format 1, which is not supported)");
  if (!r.Next(&t)) return fail("file ends inside $MeshFormat");
  const int formatLine = r.Line();
  long fileType = -1;
  if (t.size() < 3 || !ParseLong(t[1], &fileType))
    return fail(formatLine, "malformed $MeshFormat line " + Quote(t) +
                                " (expected \"version file-type data-size\")");
  if (fileType != 0)
    return fail(formatLine, "binary Gmsh file (file-type " + t[1] +
                                " in $MeshFormat): only ASCII .msh files are supported (save "
                                "with Mesh.Binary = 0, e.g. gmsh -save -format msh22)");
  const std::string& version = t[0];
  const bool v2 = version == "2" || version.rfind("2.", 0) == 0;
  const bool v41 = version == "4.1";
  if (!v2 && !v41)
    return fail(formatLine,
                "unsupported Gmsh format version " + version + " (supported: 2.2, 4.1)");
  if (!ExpectEnd(fail, r, "$EndMeshFormat")) return false;

  GmshState s;
  s.fileBytes = fileBytes;
  bool haveNodes = false, haveElements = false;
  while (r.Next(&t)) {
    const std::string section = t[0];  // a copy: skipping a section reads into t
    if (section == "$Nodes") {
      if (haveNodes) return fail(r.Line(), "second $Nodes section");
      haveNodes = true;
      if (!(v2 ? ReadGmshNodes2(fail, r, &s) : ReadGmshNodes41(fail, r, &s))) return false;
    } else if (section == "$Elements") {
      if (haveElements) return fail(r.Line(), "second $Elements section");
      haveElements = true;
      if (!(v2 ? ReadGmshElements2(fail, r, &s) : ReadGmshElements41(fail, r, &s))) return false;
    } else if (section.size() > 1 && section[0] == '$' && section.rfind("$End", 0) != 0) {
      // Any other section ($PhysicalNames, $Entities, $NodeData, ...) is skipped.
      const int start = r.Line();
      const std::string end = "$End" + section.substr(1);
      bool closed = false;
      while (r.Next(&t))
        if (t[0] == end) {
          closed = true;
          break;
        }
      if (!closed) return fail(start, section + " is not closed by " + end);
    } else {
      return fail(r.Line(), "unexpected line outside a section: " + Quote(t));
    }
  }
  if (r.Bad()) return fail("read error");
  if (!haveNodes) return fail("no $Nodes section");
  if (!haveElements) return fail("no $Elements section");
  if (s.tets.empty()) {
    std::string found;
    for (const auto& [type, n] : s.ignored)
      found += (found.empty() ? "" : ", ") + std::to_string(n) + " of type " +
               std::to_string(type) + " (" + GmshTypeName(type) + ")";
    return fail("no tetrahedra (element type 4) in $Elements" +
                (found.empty() ? std::string(" (no elements at all)")
                               : " (found only elements " + found + ")"));
  }
  s.mesh.tets.reserve(s.tets.size());
  for (const PendingTet& p : s.tets) {
    Eigen::Vector4i q;
    for (int k = 0; k < 4; ++k) {
      const auto it = s.nodeIndex.find(p.nodes[k]);
      if (it == s.nodeIndex.end())
        return fail(p.line, "tet " + std::to_string(p.tag) + " references node " +
                                std::to_string(p.nodes[k]) + " which does not exist");
      q[k] = it->second;
    }
    s.mesh.tets.push_back(q);
  }
  *mesh = std::move(s.mesh);
  return true;
}

// ---------------------------------------------------------------------------------------------
// TetGen

// Reads one of TetGen's two files (`role`: "node" or "element", for the message when it is the
// sibling of the file asked for): its header line's counts into h[0..n) (absent ones keep their
// values; `layout` names them in the message), then the rest by readBody(fail, r, fileBytes).
template <typename ReadBody>
bool ReadTetGenFile(const std::string& path, const std::string& asked, const char* role,
                    const char* layout, size_t n, long* h, std::string* error, ReadBody readBody) {
  const Failer fail{path, error};
  std::ifstream in(path, std::ios::binary);
  const double fileBytes = in ? FileBytes(in) : -1.0;
  if (!in)
    return fail(path == asked ? std::string("cannot open file")
                              : "cannot open file (the " + std::string(role) + " file of " +
                                    asked + ")");
  LineReader r(in, true);
  std::vector<std::string> t;
  if (!r.Next(&t)) return fail("empty file");
  for (size_t k = 0; k < t.size() && k < n; ++k)
    if (!ParseLong(t[k], &h[k]) || h[k] < 0)
      return fail(r.Line(),
                  "malformed header " + Quote(t) + " (expected \"" + std::string(layout) + "\")");
  if (!readBody(fail, r, fileBytes)) return false;
  return !r.Bad() || fail("read error");
}

bool ReadTetGen(const std::string& nodePath, const std::string& elePath, const std::string& asked,
                TetMesh* mesh, std::string* error) {
  TetMesh m;
  int base = 0;
  std::vector<std::string> t;
  // <# of points> <dimension (3)> <# of attributes> <boundary markers (0 or 1)>
  long h[4] = {0, 3, 0, 0};
  auto readPoints = [&](const Failer& fail, LineReader& r, double fileBytes) {
    if (h[0] == 0)
      return fail(r.Line(),
                  "no points (a count of 0 means the points are in a .poly file, "
                  "which is not supported)");
    if (h[1] != 3) return fail(r.Line(), "dimension " + std::to_string(h[1]) + ", expected 3");
    if (!CheckCount(fail, r.Line(), "the header", h[0], limits::kMaxMeshVertices, 8, fileBytes,
                    "points"))
      return false;
    const size_t need = 4 + static_cast<size_t>(h[2]) + (h[3] > 0 ? 1 : 0);
    m.vertices.reserve(h[0]);
    for (long i = 0; i < h[0]; ++i) {
      if (!r.Next(&t))
        return fail("file ends after " + std::to_string(i) + " of " + std::to_string(h[0]) +
                    " points");
      long idx;
      double x[3];
      if (t.size() < need || !ParseLong(t[0], &idx) || !ParseDouble(t[1], &x[0]) ||
          !ParseDouble(t[2], &x[1]) || !ParseDouble(t[3], &x[2]))
        return fail(r.Line(), "malformed point line " + Quote(t) + " (expected index, x, y, z, " +
                                  std::to_string(h[2]) + " attributes and " +
                                  (h[3] > 0 ? "1 marker" : "no marker") + ")");
      if (i == 0) {
        if (idx != 0 && idx != 1)
          return fail(r.Line(),
                      "the first point is numbered " + std::to_string(idx) + " (expected 0 or 1)");
        base = static_cast<int>(idx);
      } else if (idx != base + i) {
        return fail(r.Line(), "points must be numbered consecutively: expected " +
                                  std::to_string(base + i) + ", got " + std::to_string(idx));
      }
      m.vertices.emplace_back(x[0], x[1], x[2]);
    }
    return true;
  };
  if (!ReadTetGenFile(nodePath, asked, "node", "points dimension attributes markers", 4, h, error,
                      readPoints))
    return false;
  // <# of tetrahedra> <nodes per tet (4 or 10)> <# of attributes>
  long e[3] = {0, 4, 0};
  auto readTets = [&](const Failer& fail, LineReader& r, double fileBytes) {
    if (e[0] == 0) return fail(r.Line(), "no tets");
    if (e[1] != 4 && e[1] != 10)
      return fail(r.Line(), std::to_string(e[1]) + " nodes per tet (expected 4 or 10)");
    if (!CheckCount(fail, r.Line(), "the header", e[0], limits::kMaxMeshElements, 10, fileBytes,
                    "tets"))
      return false;
    const size_t need = 1 + static_cast<size_t>(e[1]) + static_cast<size_t>(e[2]);
    m.tets.reserve(e[0]);
    for (long i = 0; i < e[0]; ++i) {
      if (!r.Next(&t))
        return fail("file ends after " + std::to_string(i) + " of " + std::to_string(e[0]) +
                    " tets");
      long idx, n[4];
      if (t.size() < need || !ParseLong(t[0], &idx))
        return fail(r.Line(), "malformed tet line " + Quote(t) + " (expected index, " +
                                  std::to_string(e[1]) + " nodes and " + std::to_string(e[2]) +
                                  " attributes)");
      Eigen::Vector4i q;
      for (int k = 0; k < 4; ++k) {
        if (!ParseLong(t[1 + k], &n[k]))
          return fail(r.Line(), "malformed node number \"" + t[1 + k] + "\" in tet " + t[0]);
        if (n[k] < base || n[k] >= base + m.NumVertices())
          return fail(r.Line(), "tet " + t[0] + " references node " + std::to_string(n[k]) +
                                    " which does not exist (points are numbered " +
                                    std::to_string(base) + ".." +
                                    std::to_string(base + m.NumVertices() - 1) + " in " + nodePath +
                                    ")");
        q[k] = static_cast<int>(n[k] - base);
      }
      m.tets.push_back(q);
    }
    return true;
  };
  if (!ReadTetGenFile(elePath, asked, "element", "tetrahedra nodes-per-tet attributes", 3, e,
                      error, readTets))
    return false;
  *mesh = std::move(m);
  return true;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Files

bool ReadTetMeshFile(const std::string& path, TetMesh* mesh, std::string* error) {
  if (mesh == nullptr) {
    if (error) *error = path + ": no output mesh given";
    return false;
  }
  const std::string ext = Extension(path);
  if (ext == "msh") return ReadGmsh(path, mesh, error);
  if (ext == "node" || ext == "ele") {
    const std::string stem = path.substr(0, path.size() - ext.size());  // keeps the dot
    // The sibling keeps the case style of the given extension.
    const bool upper = std::isupper(static_cast<unsigned char>(path.back()));
    const std::string node = ext == "node" ? path : stem + (upper ? "NODE" : "node");
    const std::string ele = ext == "ele" ? path : stem + (upper ? "ELE" : "ele");
    return ReadTetGen(node, ele, path, mesh, error);
  }
  if (error)
    *error = path + ": unknown tet mesh format \"." + ext +
             "\" (supported: .msh (Gmsh 2.2 / 4.1 ASCII), .node / .ele (TetGen))";
  return false;
}

bool WriteGmsh22(const TetMesh& mesh, const std::string& path, std::string* error) {
  std::ofstream out(path);
  if (!out) {
    if (error) *error = path + ": cannot write file";
    return false;
  }
  out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << mesh.NumVertices() << "\n";
  for (int i = 0; i < mesh.NumVertices(); ++i) {
    const Eigen::Vector3d& v = mesh.vertices[i];
    out << i + 1 << ' ' << RoundTrip(v.x()) << ' ' << RoundTrip(v.y()) << ' ' << RoundTrip(v.z())
        << '\n';
  }
  out << "$EndNodes\n$Elements\n" << mesh.NumTets() << "\n";
  for (int t = 0; t < mesh.NumTets(); ++t) {
    const Eigen::Vector4i& q = mesh.tets[t];
    out << t + 1 << " 4 2 1 1 " << q[0] + 1 << ' ' << q[1] + 1 << ' ' << q[2] + 1 << ' ' << q[3] + 1
        << '\n';
  }
  out << "$EndElements\n";
  out.flush();
  if (!out) {
    if (error) *error = path + ": cannot write file";
    return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Validation

bool ValidateTetMesh(const TetMesh& mesh, const std::string& name, std::string* error) {
  auto fail = [&](const std::string& message) {
    if (error) *error = name + ": " + message;
    return false;
  };
  if (mesh.tets.empty()) return fail("no tets");
  const int nv = mesh.NumVertices();
  for (int i = 0; i < nv; ++i)
    if (!mesh.vertices[i].allFinite())
      return fail("vertex " + std::to_string(i) + " has a non-finite coordinate (" +
                  NumberText(mesh.vertices[i].x()) + ", " + NumberText(mesh.vertices[i].y()) +
                  ", " + NumberText(mesh.vertices[i].z()) + ")");
  for (int t = 0; t < mesh.NumTets(); ++t) {
    const Eigen::Vector4i& q = mesh.tets[t];
    for (int k = 0; k < 4; ++k) {
      if (q[k] < 0 || q[k] >= nv)
        return fail("tet " + std::to_string(t) + " references vertex " + std::to_string(q[k]) +
                    " which does not exist (" + std::to_string(nv) + " vertices)");
      for (int l = 0; l < k; ++l)
        if (q[l] == q[k])
          return fail("tet " + std::to_string(t) + " repeats vertex " + std::to_string(q[k]));
    }
  }
  const Aabb box = mesh.Bounds();
  const double diag = (box.max - box.min).stableNorm();  // no overflow for huge extents
  const double cube = diag * diag * diag;
  if (!(cube >= 1e-290 && cube <= 1e290))  // tet volumes (products of three lengths) must fit
    return fail("the mesh's extent " + NumberText(diag) +
                " m is out of double precision's range for tet volumes (its cube must be within "
                "1e-290 to 1e290 m^3)");
  const double tol = 1e-12 * cube;
  int degenerate = 0, inverted = 0, first = -1;
  for (int t = 0; t < mesh.NumTets(); ++t) {
    const double v = mesh.TetVolume(t);
    if (v > tol) continue;
    if (std::abs(v) <= tol)
      ++degenerate;
    else
      ++inverted;
    if (first < 0) first = t;
  }
  if (first < 0) return true;
  const double v = mesh.TetVolume(first);
  const std::string counts = std::to_string(degenerate) + " of " + std::to_string(mesh.NumTets()) +
                             " tets are degenerate (|volume| <= " + NumberText(tol) + " m^3), " +
                             std::to_string(inverted) + " inverted";
  if (std::abs(v) <= tol)
    return fail("tet " + std::to_string(first) + " is degenerate (volume " + NumberText(v) +
                "); " + counts);
  return fail("tet " + std::to_string(first) + " is inverted (signed volume " + NumberText(v) +
              " < 0); " + counts + " (swapping two vertices of a tet reverses its orientation)");
}

// ---------------------------------------------------------------------------------------------
// Boundary

std::vector<Eigen::Vector3i> BoundaryFaces(const TetMesh& mesh) {
  // Face k is opposite vertex k, ordered so that its normal points away from vertex k when the
  // tet is positively oriented.
  static const int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  struct Entry {
    std::array<int, 3> key;  // sorted vertex indices
    int id;                  // 4 t + k
  };
  std::vector<Entry> entries;
  entries.reserve(4 * mesh.tets.size());
  for (int t = 0; t < mesh.NumTets(); ++t)
    for (int k = 0; k < 4; ++k) {
      std::array<int, 3> key = {mesh.tets[t][kFace[k][0]], mesh.tets[t][kFace[k][1]],
                                mesh.tets[t][kFace[k][2]]};
      std::sort(key.begin(), key.end());
      entries.push_back({key, 4 * t + k});
    }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.key != b.key ? a.key < b.key : a.id < b.id;
  });
  std::vector<int> single;
  for (size_t i = 0; i < entries.size();) {
    size_t j = i + 1;
    while (j < entries.size() && entries[j].key == entries[i].key) ++j;
    if (j == i + 1) single.push_back(entries[i].id);
    i = j;
  }
  std::sort(single.begin(), single.end());
  std::vector<Eigen::Vector3i> faces;
  faces.reserve(single.size());
  for (int id : single) {
    const Eigen::Vector4i& q = mesh.tets[id / 4];
    const int* f = kFace[id % 4];
    faces.emplace_back(q[f[0]], q[f[1]], q[f[2]]);
  }
  return faces;
}

// ---------------------------------------------------------------------------------------------
// Generators

TetMesh MakeTetBox(const Eigen::Vector3d& halfExtents, const Eigen::Vector3i& cells) {
  const Eigen::Vector3i n = cells.cwiseMax(1);
  TetMesh m;
  m.vertices.reserve(static_cast<size_t>(n.x() + 1) * (n.y() + 1) * (n.z() + 1));
  auto coord = [&](int l, int k) {
    // Exactly ±h on the faces, as MakeBoxMesh.
    const double s = l == 0 ? -1.0 : (l == n[k] ? 1.0 : 2.0 * l / n[k] - 1.0);
    return s * halfExtents[k];
  };
  for (int k = 0; k <= n.z(); ++k)
    for (int j = 0; j <= n.y(); ++j)
      for (int i = 0; i <= n.x(); ++i)
        m.vertices.emplace_back(coord(i, 0), coord(j, 1), coord(k, 2));
  auto index = [&](const Eigen::Vector3i& l) {
    return l.x() + (n.x() + 1) * (l.y() + (n.y() + 1) * l.z());
  };
  // Kuhn split: one tet per permutation (a, b, c) of the axes, the path 0 → e_a → e_a + e_b →
  // (1, 1, 1) through the cell. Its orientation is the permutation's sign; odd ones get two
  // vertices swapped.
  static const int kPerm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},   // even
                                  {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};  // odd
  m.tets.reserve(6 * static_cast<size_t>(n.x()) * n.y() * n.z());
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const Eigen::Vector3i o(i, j, k);
        for (int p = 0; p < 6; ++p) {
          const Eigen::Vector3i a = Eigen::Vector3i::Unit(kPerm[p][0]);
          const Eigen::Vector3i ab = a + Eigen::Vector3i::Unit(kPerm[p][1]);
          int v1 = index(o + a), v2 = index(o + ab);
          if (p >= 3) std::swap(v1, v2);
          m.tets.emplace_back(index(o), v1, v2, index(o + Eigen::Vector3i::Ones()));
        }
      }
  return m;
}

}  // namespace superdex
