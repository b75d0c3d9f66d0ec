#include "geometry/mesher_input.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

#include "geometry/mesh_limits.h"

namespace superdex {

std::string MesherNum(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

namespace {

// A regular tet of edge h has volume h³ / (6 √2) = h³ / 8.485; an equilateral triangle of edge h
// has area 0.433 h², and a closed triangulated surface has half as many vertices as faces.
constexpr double kRegularTetFactor = 8.485;
constexpr double kSurfaceVertexArea = 2 * 0.433;

// Checks that the surface is a closed, consistently oriented 2-manifold (at its edges: every
// undirected edge in exactly two faces, traversed once in each direction).
bool CheckClosed(const TriangleMesh& s, std::string* message) {
  std::map<std::pair<int, int>, std::array<int, 2>> edges;  // (min, max) -> uses (a→b, b→a)
  for (int f = 0; f < s.NumFaces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = s.faces[f][k], b = s.faces[f][(k + 1) % 3];
      if (a == b) {
        *message = "face " + std::to_string(f) + " repeats vertex " + std::to_string(a);
        return false;
      }
      auto& e = edges[{std::min(a, b), std::max(a, b)}];
      ++e[a < b ? 0 : 1];
    }
  for (const auto& [e, uses] : edges) {
    const int n = uses[0] + uses[1];
    const std::string edge =
        "edge (" + std::to_string(e.first) + ", " + std::to_string(e.second) + ")";
    if (n == 1) {
      *message = "the surface is not closed: " + edge + " belongs to only one face";
      return false;
    }
    if (n > 2) {
      *message = "the surface is not closed: " + edge + " belongs to " + std::to_string(n) +
                 " faces (non-manifold)";
      return false;
    }
    if (uses[0] != 1) {
      *message = "the surface is not consistently oriented: the two faces of " + edge +
                 " traverse it in the same direction";
      return false;
    }
  }
  return true;
}

bool CheckIndicesAndCoordinates(const TriangleMesh& surface, std::string* message) {
  const int nv = surface.NumVertices();
  for (int i = 0; i < nv; ++i)
    if (!surface.vertices[i].allFinite()) {
      *message = "surface vertex " + std::to_string(i) + " has a non-finite coordinate";
      return false;
    }
  for (int f = 0; f < surface.NumFaces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (surface.faces[f][k] < 0 || surface.faces[f][k] >= nv) {
        *message = "surface face " + std::to_string(f) + " references vertex " +
                   std::to_string(surface.faces[f][k]) + " which does not exist (" +
                   std::to_string(nv) + " vertices)";
        return false;
      }
  return true;
}

// Moves the surface to normalized coordinates when it is far from unit scale (see MesherInput).
bool Normalize(const TriangleMesh& surface, MesherInput* in, std::string* message) {
  const Aabb box = surface.Bounds();
  const double side = (box.max - box.min).maxCoeff();
  if (!(side > 0)) {
    *message = "the surface's vertices all coincide: it encloses no volume";
    return false;
  }
  const Eigen::Vector3d center = 0.5 * (box.min + box.max);
  in->surface = surface;
  if (side >= std::ldexp(1.0, -16) && side <= std::ldexp(1.0, 16) &&
      center.cwiseAbs().maxCoeff() <= 64 * side)
    return true;
  in->center = center;
  in->scale = std::ldexp(1.0, -static_cast<int>(std::lround(std::log2(side))));
  for (Eigen::Vector3d& v : in->surface.vertices) v = (v - center) * in->scale;
  return true;
}

double Volume(const TriangleMesh& s) {
  double volume = 0.0;
  for (const auto& f : s.faces)
    volume += s.vertices[f[0]].dot(s.vertices[f[1]].cross(s.vertices[f[2]])) / 6;
  return std::abs(volume);
}

// The size function's estimate: 24³ cells of the bounding box, each cell's count scaled by the
// solid's share of the box; the smallest size (also at the vertices) must be positive and finite.
bool EstimateSized(MesherInput* in, double volume, std::string* message) {
  const TriangleMesh& s = in->surface;
  const Aabb box = s.Bounds();
  const Eigen::Vector3d ext = box.max - box.min;
  const int n = 24;
  const double cell = ext.prod() / (n * n * n);
  const double share = ext.prod() > 0 ? volume / ext.prod() : 1.0;
  double smallest = INFINITY;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Eigen::Vector3d c =
            box.min + ext.cwiseProduct(Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5) / n);
        const double h = in->field(c);
        smallest = std::min(smallest, h);
        if (h > 0.0) in->estimatedTets += share * cell / (h * h * h / kRegularTetFactor);
      }
  for (const auto& v : s.vertices) smallest = std::min(smallest, in->field(v));
  if (!(smallest > 0.0) || !std::isfinite(smallest)) {
    *message = "the mesh size function must be positive and finite (got " +
               MesherNum(smallest / in->scale) + " m)";
    return false;
  }
  for (int f = 0; f < s.NumFaces(); ++f) {
    const Eigen::Vector3i& q = s.faces[f];
    const double h = in->field((s.vertices[q[0]] + s.vertices[q[1]] + s.vertices[q[2]]) / 3);
    in->estimatedVertices += s.FaceArea(f) / (kSurfaceVertexArea * h * h);
  }
  return true;
}

}  // namespace

bool PrepareMesherInput(const TriangleMesh& surface, double edgeLength, const MeshSizeField* field,
                        const MeshingLimits& bounds, MesherInput* in, std::string* message) {
  if (!field && (!(edgeLength > 0.0) || !std::isfinite(edgeLength))) {
    *message = "edge length must be positive and finite (got " + MesherNum(edgeLength) + " m)";
    return false;
  }
  if (field && !*field) {
    *message = "no mesh size function given";
    return false;
  }
  if (surface.faces.empty()) {
    *message = "the surface has no faces";
    return false;
  }
  if (!CheckIndicesAndCoordinates(surface, message) || !CheckClosed(surface, message) ||
      !Normalize(surface, in, message))
    return false;
  const double volume = Volume(in->surface);
  const double side = (in->surface.Bounds().max - in->surface.Bounds().min).maxCoeff();
  if (!(volume > 1e-12 * side * side * side)) {
    *message = "the surface encloses no volume (|volume| " + MesherNum(volume) +
               " of a bounding box of side " + MesherNum(side) +
               ", normalized): it is flat or folded onto itself";
    return false;
  }
  if (field) {
    const MeshSizeField original = *field;
    const Eigen::Vector3d c = in->center;
    const double s = in->scale;
    in->field = [original, c, s](const Eigen::Vector3d& x) { return s * original(x / s + c); };
    if (!EstimateSized(in, volume, message)) return false;
  } else {
    const double h = edgeLength * in->scale;
    in->edgeLength = h;
    in->estimatedTets = volume / (h * h * h / kRegularTetFactor);
    in->estimatedVertices = in->surface.SurfaceArea() / (kSurfaceVertexArea * h * h);
  }
  in->estimatedVertices += in->estimatedTets / 5;
  if (!(in->estimatedTets <= bounds.maxTets)) {
    *message = (field ? std::string("the mesh size function")
                      : "edge length " + MesherNum(edgeLength) + " m") +
               " would give about " + MesherNum(std::ceil(in->estimatedTets)) + " tets (limit " +
               MesherNum(bounds.maxTets) + "); use a larger edge length";
    return false;
  }
  const double work = std::max(in->estimatedTets, 5 * in->estimatedVertices);
  in->seconds = bounds.seconds >= 0
                    ? bounds.seconds
                    : limits::kMesherMinSeconds + limits::kMesherSecondsPerTet * work;
  in->maxVertices =
      static_cast<size_t>(1000 + limits::kMesherVertexBudgetFactor * in->estimatedVertices);
  return true;
}

}  // namespace superdex
