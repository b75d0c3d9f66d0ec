#include "geometry/triangle_mesh.h"

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

namespace superdex {

double TriangleMesh::FaceArea(int f) const {
  const Eigen::Vector3i& t = faces[f];
  return 0.5 * (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).norm();
}

Eigen::Vector3d TriangleMesh::FaceNormal(int f) const {
  const Eigen::Vector3i& t = faces[f];
  const Eigen::Vector3d n = (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]);
  const double len = n.norm();
  return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

double TriangleMesh::SurfaceArea() const {
  double a = 0.0;
  for (int f = 0; f < NumFaces(); ++f) a += FaceArea(f);
  return a;
}

Aabb TriangleMesh::Bounds() const {
  Aabb b;
  for (const auto& v : vertices) b.Extend(v);
  return b;
}

TriangleMesh MakeIcosphere(double radius, int subdivisions) {
  TriangleMesh m;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double base[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                              {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                              {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (const auto& v : base) m.vertices.push_back(Eigen::Vector3d(v[0], v[1], v[2]).normalized());
  const int f0[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                         {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                         {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                         {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7}, {9, 8, 1}};
  for (const auto& f : f0) m.faces.emplace_back(f[0], f[1], f[2]);
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      const int idx = m.NumVertices() - 1;
      mid.emplace(key, idx);
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

TriangleMesh MakeBoxMesh(const Eigen::Vector3d& h, int divisions) {
  TriangleMesh m;
  const int n = std::max(1, divisions);
  std::map<std::tuple<long, long, long>, int> index;  // shared vertices on the integer lattice
  auto vertex = [&](const Eigen::Vector3i& lattice) {
    const auto key = std::make_tuple(long(lattice.x()), long(lattice.y()), long(lattice.z()));
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    const Eigen::Vector3d p = (lattice.cast<double>() / n - Eigen::Vector3d::Ones()).cwiseProduct(h);
    m.vertices.push_back(p);
    index.emplace(key, m.NumVertices() - 1);
    return m.NumVertices() - 1;
  };
  // Each face: fixed axis k at lattice 0 or 2n, spanned by axes u, v with u × v = ±e_k.
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      for (int i = 0; i < 2 * n; i += 2)
        for (int j = 0; j < 2 * n; j += 2) {
          // Lattice spacing 2 per cell keeps integer coordinates in [0, 2n].
          auto at = [&](int a, int b) {
            Eigen::Vector3i l;
            l[k] = side * 2 * n;
            l[u] = a;
            l[v] = b;
            return vertex(l);
          };
          const int v00 = at(i, j), v10 = at(i + 2, j), v11 = at(i + 2, j + 2), v01 = at(i, j + 2);
          if (side == 1) {
            m.faces.emplace_back(v00, v10, v11);
            m.faces.emplace_back(v00, v11, v01);
          } else {
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
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.vertices.emplace_back(size * (double(i) / n - 0.5), size * (double(j) / n - 0.5), 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      m.faces.emplace_back(a, b, c);
      m.faces.emplace_back(a, c, d);
    }
  return m;
}

bool ReadObj(const std::string& path, TriangleMesh* mesh, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    if (error) *error = path + ": cannot open file";
    return false;
  }
  TriangleMesh m;
  std::string line;
  int lineNo = 0;
  std::vector<std::pair<int, int>> faceLines;  // face start index in m.faces, line number
  std::vector<std::vector<long>> polys;
  std::vector<int> polyLines;
  while (std::getline(in, line)) {
    ++lineNo;
    std::istringstream s(line);
    std::string tag;
    if (!(s >> tag) || tag[0] == '#') continue;
    if (tag == "v") {
      double x, y, z;
      if (!(s >> x >> y >> z) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
        if (error) *error = path + ":" + std::to_string(lineNo) + ": malformed vertex";
        return false;
      }
      m.vertices.emplace_back(x, y, z);
    } else if (tag == "f") {
      std::vector<long> poly;
      std::string tok;
      while (s >> tok) {
        try {
          poly.push_back(std::stol(tok.substr(0, tok.find('/'))));
        } catch (...) {
          if (error) *error = path + ":" + std::to_string(lineNo) + ": malformed face index \"" + tok + "\"";
          return false;
        }
      }
      if (poly.size() < 3) {
        if (error) *error = path + ":" + std::to_string(lineNo) + ": a face needs at least 3 vertices";
        return false;
      }
      // Negative indices are relative to the vertices read so far.
      for (long& idx : poly) idx = idx < 0 ? long(m.vertices.size()) + idx + 1 : idx;
      polys.push_back(poly);
      polyLines.push_back(lineNo);
    }
  }
  const long nv = long(m.vertices.size());
  for (size_t p = 0; p < polys.size(); ++p) {
    for (long idx : polys[p])
      if (idx < 1 || idx > nv) {
        if (error)
          *error = path + ":" + std::to_string(polyLines[p]) + ": face index " + std::to_string(idx) +
                   " out of range (" + std::to_string(nv) + " vertices)";
        return false;
      }
    for (size_t k = 1; k + 1 < polys[p].size(); ++k)
      m.faces.emplace_back(int(polys[p][0] - 1), int(polys[p][k] - 1), int(polys[p][k + 1] - 1));
  }
  if (m.faces.empty()) {
    if (error) *error = path + ": no faces";
    return false;
  }
  *mesh = std::move(m);
  return true;
}

MassProperties ComputeMassProperties(const TriangleMesh& mesh, double density) {
  // Signed tetrahedra (0, a, b, c): volume det/6, first and second moments exactly.
  MassProperties mp;
  double vol = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // ∫ x xᵀ dV about the origin
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d& a = mesh.vertices[f[0]];
    const Eigen::Vector3d& b = mesh.vertices[f[1]];
    const Eigen::Vector3d& c = mesh.vertices[f[2]];
    const double v = a.dot(b.cross(c)) / 6.0;
    vol += v;
    first += v * (a + b + c) / 4.0;
    // ∫_tet x xᵀ dV = V/20 (Σ_i v_i v_iᵀ + (Σ v_i)(Σ v_i)ᵀ) with the origin as fourth vertex.
    const Eigen::Vector3d s = a + b + c;
    second += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  mp.volume = vol;
  mp.mass = density * vol;
  if (vol != 0.0) {
    mp.centerOfMass = first / vol;
    mp.secondMoment = density * (second - vol * mp.centerOfMass * mp.centerOfMass.transpose());
  }
  return mp;
}

}  // namespace superdex
