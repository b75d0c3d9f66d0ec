// Triangle surface meshes (see triangle_mesh.h).
#include "geometry/triangle_mesh.h"

#include "geometry/number_text.h"
#include "geometry/mesh_limits.h"
#include "geometry/token_parsing.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>
#include <utility>

namespace superdex {

Aabb MeshVertices::Bounds() const {
  Aabb b;
  for (const auto& v : vertices) b.Extend(v);
  return b;
}

// ---------------------------------------------------------------------------------------------
// Per-face queries

double TriangleMesh::FaceArea(int f) const {
  const Eigen::Vector3i& t = faces[f];
  return 0.5 * (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).norm();
}

Eigen::Vector3d TriangleMesh::FaceNormal(int f) const {
  const Eigen::Vector3i& t = faces[f];
  const Eigen::Vector3d n =
      (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]);
  const double len = n.norm();
  return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

double TriangleMesh::SurfaceArea() const {
  double a = 0.0;
  for (int f = 0; f < NumFaces(); ++f) a += FaceArea(f);
  return a;
}

// ---------------------------------------------------------------------------------------------
// Generators

TriangleMesh MakeIcosphere(double radius, int subdivisions) {
  TriangleMesh m;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;  // golden ratio
  const double base[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                              {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                              {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (const auto& v : base) m.vertices.push_back(Eigen::Vector3d(v[0], v[1], v[2]).normalized());
  // Counter-clockwise seen from outside.
  const int f0[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                         {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                         {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                         {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (const auto& f : f0) m.faces.emplace_back(f[0], f[1], f[2]);
  for (int s = 0; s < subdivisions; ++s) {
    // One new vertex per edge, shared by the two faces of the edge.
    std::map<std::pair<int, int>, int> midpoints;
    auto midpoint = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = midpoints.find(key);
      if (it != midpoints.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      const int idx = m.NumVertices() - 1;
      midpoints.emplace(key, idx);
      return idx;
    };
    std::vector<Eigen::Vector3i> next;
    next.reserve(m.faces.size() * 4);
    for (const auto& f : m.faces) {
      const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      next.emplace_back(f[0], a, c);
      next.emplace_back(f[1], b, a);
      next.emplace_back(f[2], c, b);
      next.emplace_back(a, b, c);
    }
    m.faces.swap(next);
  }
  for (auto& v : m.vertices) v *= radius;
  return m;
}

TriangleMesh MakeBoxMesh(const Eigen::Vector3d& halfExtents, int divisions) {
  TriangleMesh m;
  const int n = std::max(1, divisions);
  // Vertices live on the integer lattice {0..n}^3 of the box; a lattice point maps to
  // X = (2 l/n − 1) ∘ halfExtents. Sharing lattice points makes the six faces one closed mesh.
  std::map<std::tuple<int, int, int>, int> index;
  auto vertex = [&](const Eigen::Vector3i& l) {
    const auto key = std::make_tuple(l.x(), l.y(), l.z());
    const auto it = index.find(key);
    if (it != index.end()) return it->second;
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) {
      // Exact ±h at the faces, so the box's faces are exactly planar and its area exact.
      const double s = l[k] == 0 ? -1.0 : (l[k] == n ? 1.0 : 2.0 * l[k] / n - 1.0);
      p[k] = s * halfExtents[k];
    }
    m.vertices.push_back(p);
    index.emplace(key, m.NumVertices() - 1);
    return m.NumVertices() - 1;
  };
  m.faces.reserve(12 * n * n);
  // Face with fixed axis k at lattice 0 (normal −e_k) or n (normal +e_k), spanned by the axes
  // u = k+1, v = k+2 (cyclic), so that e_u × e_v = e_k.
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      auto at = [&](int a, int b) {
        Eigen::Vector3i l;
        l[k] = side * n;
        l[u] = a;
        l[v] = b;
        return vertex(l);
      };
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const int v00 = at(i, j), v10 = at(i + 1, j), v11 = at(i + 1, j + 1), v01 = at(i, j + 1);
          if (side == 1) {  // +e_k: (u, v) counter-clockwise
            m.faces.emplace_back(v00, v10, v11);
            m.faces.emplace_back(v00, v11, v01);
          } else {  // −e_k: reversed
            m.faces.emplace_back(v00, v11, v10);
            m.faces.emplace_back(v00, v01, v11);
          }
        }
    }
  }
  return m;
}

TriangleMesh MakePlanePatch(double size, int divisions) {
  TriangleMesh m;
  const int n = std::max(1, divisions);
  m.vertices.reserve((n + 1) * (n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.vertices.emplace_back(size * (double(i) / n - 0.5), size * (double(j) / n - 0.5), 0.0);
  m.faces.reserve(2 * n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      m.faces.emplace_back(a, b, c);  // counter-clockwise seen from +z
      m.faces.emplace_back(a, c, d);
    }
  return m;
}

bool FaceOppositeVertices(const std::vector<Eigen::Vector3i>& faces,
                          std::vector<Eigen::Vector3i>* opposite, std::pair<int, int>* badEdge,
                          std::vector<Eigen::Vector3i>* oppositeFace) {
  // Each edge's (face, local index of the opposite vertex) uses, sorted by edge.
  struct Use {
    int a, b, face, local;
  };
  std::vector<Use> uses;
  uses.reserve(3 * faces.size());
  for (size_t f = 0; f < faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const int u = faces[f][(i + 1) % 3], v = faces[f][(i + 2) % 3];
      uses.push_back({std::min(u, v), std::max(u, v), static_cast<int>(f), i});
    }
  std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
    return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.face < y.face;
  });
  opposite->assign(faces.size(), Eigen::Vector3i::Constant(-1));
  if (oppositeFace) oppositeFace->assign(faces.size(), Eigen::Vector3i::Constant(-1));
  for (size_t k = 0; k < uses.size();) {
    size_t e = k;
    while (e < uses.size() && uses[e].a == uses[k].a && uses[e].b == uses[k].b) ++e;
    if (e - k > 2) {
      *badEdge = {uses[k].a, uses[k].b};
      return false;
    }
    if (e - k == 2) {
      const Use &x = uses[k], &y = uses[k + 1];
      (*opposite)[x.face][x.local] = faces[y.face][y.local];
      (*opposite)[y.face][y.local] = faces[x.face][x.local];
      if (oppositeFace) {
        (*oppositeFace)[x.face][x.local] = y.face;
        (*oppositeFace)[y.face][y.local] = x.face;
      }
    }
    k = e;
  }
  return true;
}

TriangleMesh MakeRectangleMesh(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                               const Eigen::Vector2i& cells) {
  TriangleMesh m;
  const int nx = std::max(1, cells.x()), ny = std::max(1, cells.y());
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      m.vertices.emplace_back(lo.x() + (hi.x() - lo.x()) * i / nx,
                              lo.y() + (hi.y() - lo.y()) * j / ny, 0.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      m.faces.emplace_back(a, b, c);
      m.faces.emplace_back(a, c, d);
    }
  return m;
}

TriangleMesh MakeAnnulusMesh(double innerRadius, double outerRadius, double angle,
                             const Eigen::Vector2i& cells) {
  TriangleMesh m = MakeRectangleMesh(Eigen::Vector2d(innerRadius, 0.0),
                                     Eigen::Vector2d(outerRadius, angle), cells);
  for (Eigen::Vector3d& v : m.vertices)  // (r, θ) → (r cos θ, r sin θ): orientation kept (r > 0)
    v = Eigen::Vector3d(v.x() * std::cos(v.y()), v.x() * std::sin(v.y()), 0.0);
  return m;
}

TriangleMesh MakeDiskMesh(double radius, int rings) {
  TriangleMesh m;
  const int n = std::max(1, rings);
  m.vertices.emplace_back(0.0, 0.0, 0.0);
  for (int k = 1; k <= n; ++k)
    for (int j = 0; j < 6 * k; ++j) {
      const double a = 2.0 * M_PI * j / (6 * k), r = radius * k / n;
      m.vertices.emplace_back(r * std::cos(a), r * std::sin(a), 0.0);
    }
  // Ring k's first vertex: 1 + 3k(k − 1).
  auto first = [](int k) { return k == 0 ? 0 : 1 + 3 * k * (k - 1); };
  for (int j = 0; j < 6; ++j) m.faces.emplace_back(0, 1 + j, 1 + (j + 1) % 6);
  for (int k = 2; k <= n; ++k) {  // zip ring k − 1 (ni vertices) with ring k (no) by angle
    const int ni = 6 * (k - 1), no = 6 * k, bi = first(k - 1), bo = first(k);
    int i = 0, j = 0;
    while (i < ni || j < no) {
      // Advance on the ring whose next vertex comes first (the outer one on a tie: a corner).
      const bool outer = i == ni || (j < no && (j + 1) * ni <= (i + 1) * no);
      if (outer) {
        m.faces.emplace_back(bi + i % ni, bo + j, bo + (j + 1) % no);
        ++j;
      } else {
        m.faces.emplace_back(bi + i, bo + j % no, bi + (i + 1) % ni);
        ++i;
      }
    }
  }
  return m;
}

TriangleMesh MakeCylinderMesh(double radius, double halfLength, int segments, int rings) {
  TriangleMesh m;
  const int n = std::max(3, segments);
  const int r = std::max(1, rings);
  // Side: (r + 1) rings of n vertices along x from −halfLength to +halfLength.
  for (int j = 0; j <= r; ++j)
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * i / n;
      m.vertices.emplace_back(-halfLength + 2.0 * halfLength * j / r, radius * std::cos(a),
                              radius * std::sin(a));
    }
  for (int j = 0; j < r; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * n + i, b = j * n + (i + 1) % n, c = a + n, d = b + n;
      m.faces.emplace_back(a, b, d);  // outward: the angle increases counter-clockwise about +x
      m.faces.emplace_back(a, d, c);
    }
  // Caps: a centre vertex each, fans to the end rings.
  const int c0 = m.NumVertices();
  m.vertices.emplace_back(-halfLength, 0.0, 0.0);
  m.vertices.emplace_back(halfLength, 0.0, 0.0);
  for (int i = 0; i < n; ++i) {
    m.faces.emplace_back(c0, (i + 1) % n, i);                  // −x cap, normal −x
    m.faces.emplace_back(c0 + 1, r * n + i, r * n + (i + 1) % n);  // +x cap, normal +x
  }
  return m;
}

TriangleMesh MakeCapsuleMesh(double radius, double halfLength, int segments, int capRings,
                             int rows) {
  TriangleMesh m;
  const int n = std::max(3, segments), k = std::max(1, capRings), r = std::max(1, rows);
  // The profile (ρ, z) from the bottom pole to the top one, poles excluded: the bottom cap's
  // latitudes up to its equator, the side rows, the top cap's latitudes.
  std::vector<std::pair<double, double>> ring;
  for (int j = 1; j <= k; ++j) {
    const double t = -0.5 * M_PI + 0.5 * M_PI * j / k;
    ring.emplace_back(radius * std::cos(t), -halfLength + radius * std::sin(t));
  }
  for (int j = 1; j <= r; ++j) ring.emplace_back(radius, -halfLength + 2.0 * halfLength * j / r);
  for (int j = 1; j < k; ++j) {
    const double t = 0.5 * M_PI * j / k;
    ring.emplace_back(radius * std::cos(t), halfLength + radius * std::sin(t));
  }
  for (const auto& [rho, z] : ring)
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * i / n;
      m.vertices.emplace_back(rho * std::cos(a), rho * std::sin(a), z);
    }
  const int rings = static_cast<int>(ring.size());
  for (int j = 0; j + 1 < rings; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * n + i, b = j * n + (i + 1) % n, c = a + n, d = b + n;
      m.faces.emplace_back(a, b, d);  // outward: the angle increases counter-clockwise about +z
      m.faces.emplace_back(a, d, c);
    }
  const int p0 = m.NumVertices();
  m.vertices.emplace_back(0.0, 0.0, -halfLength - radius);
  m.vertices.emplace_back(0.0, 0.0, halfLength + radius);
  const int top = (rings - 1) * n;
  for (int i = 0; i < n; ++i) {
    m.faces.emplace_back(p0, (i + 1) % n, i);                  // bottom pole, normal −z
    m.faces.emplace_back(p0 + 1, top + i, top + (i + 1) % n);  // top pole, normal +z
  }
  return m;
}

// ---------------------------------------------------------------------------------------------
// OBJ reading

namespace {


struct PendingIndex {
  long index;         // 1-based, resolved (negative indices made absolute)
  std::string token;  // as written, for messages
};

}  // namespace

bool ReadObj(const std::string& path, TriangleMesh* mesh, std::string* error) {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (mesh == nullptr) return fail(path + ": no output mesh given");
  std::ifstream in(path);
  if (!in) return fail(path + ": cannot open file");

  TriangleMesh m;
  struct Polygon {
    std::vector<PendingIndex> corners;
    int line;
  };
  std::vector<Polygon> polygons;
  double triangles = 0;
  std::string line;
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    const std::string where = path + ":" + std::to_string(lineNo) + ": ";
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);  // comments, also after data
    std::istringstream s(line);                       // '\r' of CRLF files is whitespace here
    std::string tag;
    if (!(s >> tag)) continue;
    if (tag == "v") {
      // "v x y z [w]": w (rational weight) is ignored; colours after xyz are tolerated.
      std::string tok[3];
      double x[3];
      for (int k = 0; k < 3; ++k)
        if (!(s >> tok[k]) || !ParseDouble(tok[k], &x[k]))
          return fail(where + "malformed vertex (expected \"v x y z\" with finite numbers)");
      if (static_cast<double>(m.vertices.size()) >= limits::kMaxMeshVertices)
        return fail(where + "more than " + std::to_string(long(limits::kMaxMeshVertices)) +
                    " vertices (the limit per mesh file)");
      m.vertices.emplace_back(x[0], x[1], x[2]);
    } else if (tag == "f") {
      // "f a b c ...", each corner "v", "v/vt", "v//vn" or "v/vt/vn"; only v is used.
      Polygon poly;
      poly.line = lineNo;
      std::string tok;
      while (s >> tok) {
        const std::string v = tok.substr(0, tok.find('/'));
        long idx = 0;
        if (!ParseLong(v, &idx)) return fail(where + "malformed face index \"" + tok + "\"");
        if (idx < 0) {
          // Relative to the vertices read so far: −1 is the last one.
          if (idx < -static_cast<long>(m.vertices.size()))
            return fail(where + "face index " + v + " out of range (" +
                        std::to_string(m.vertices.size()) + " vertices so far)");
          idx = static_cast<long>(m.vertices.size()) + idx + 1;
        }
        poly.corners.push_back({idx, v});
      }
      if (poly.corners.size() < 3)
        return fail(where + "a face needs at least 3 vertices, got " +
                    std::to_string(poly.corners.size()));
      triangles += static_cast<double>(poly.corners.size()) - 2;
      if (triangles > limits::kMaxMeshElements)
        return fail(where + "more than " + std::to_string(long(limits::kMaxMeshElements)) +
                    " triangles (the limit per mesh file)");
      polygons.push_back(std::move(poly));
    }
    // Every other statement (vt, vn, o, g, s, usemtl, mtllib, l, ...) is ignored.
  }
  if (in.bad()) return fail(path + ": read error");

  // Positive indices are checked once all vertices are known.
  const long nv = static_cast<long>(m.vertices.size());
  if (nv > INT_MAX) return fail(path + ": too many vertices");
  for (const Polygon& poly : polygons) {
    for (const PendingIndex& c : poly.corners)
      if (c.index < 1 || c.index > nv)
        return fail(path + ":" + std::to_string(poly.line) + ": face index " + c.token +
                    " out of range (" + std::to_string(nv) + " vertices)");
    // Fan triangulation around the first corner.
    for (size_t k = 1; k + 1 < poly.corners.size(); ++k)
      m.faces.emplace_back(static_cast<int>(poly.corners[0].index - 1),
                           static_cast<int>(poly.corners[k].index - 1),
                           static_cast<int>(poly.corners[k + 1].index - 1));
  }
  if (m.faces.empty()) return fail(path + ": no faces");
  *mesh = std::move(m);
  return true;
}

bool WriteObj(const TriangleMesh& mesh, const std::string& path, std::string* error) {
  std::ofstream out(path);
  for (const Eigen::Vector3d& v : mesh.vertices)
    out << "v " << RoundTrip(v.x()) << ' ' << RoundTrip(v.y()) << ' ' << RoundTrip(v.z()) << '\n';
  for (const Eigen::Vector3i& f : mesh.faces)
    out << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
  out.flush();
  if (!out) {
    if (error) *error = path + ": cannot write file";
    return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Mass properties

MassProperties ComputeMassProperties(const TriangleMesh& mesh, double density) {
  // Divergence theorem: the solid is the signed sum of the tetrahedra (o, a, b, c) over the
  // faces, o a reference point (the bounding-box centre, which keeps round-off small for meshes
  // far from the origin). For a tetrahedron with vertices p_0..p_3 and relative coordinates
  // r_i = p_i − o (r_0 = 0), exactly:
  //   V = r_1 · (r_2 × r_3) / 6,   ∫ r dV = V/4 Σ r_i,
  //   ∫ r rᵀ dV = V/20 (Σ r_i r_iᵀ + (Σ r_i)(Σ r_i)ᵀ).
  MassProperties mp;
  if (mesh.vertices.empty()) return mp;
  const Aabb box = mesh.Bounds();
  const Eigen::Vector3d o = 0.5 * (box.min + box.max);
  double vol = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   // ∫ r dV
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // ∫ r rᵀ dV
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d a = mesh.vertices[f[0]] - o;
    const Eigen::Vector3d b = mesh.vertices[f[1]] - o;
    const Eigen::Vector3d c = mesh.vertices[f[2]] - o;
    const double v = a.dot(b.cross(c)) / 6.0;
    const Eigen::Vector3d s = a + b + c;
    vol += v;
    first += (v / 4.0) * s;
    second += (v / 20.0) *
              (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  mp.volume = vol;
  mp.mass = density * vol;
  if (vol != 0.0) {
    const Eigen::Vector3d rc = first / vol;  // centre of mass relative to o
    mp.centerOfMass = o + rc;
    Eigen::Matrix3d J = density * (second - vol * rc * rc.transpose());  // parallel axis
    mp.secondMoment = 0.5 * (J + J.transpose());
  }
  return mp;
}

}  // namespace superdex
