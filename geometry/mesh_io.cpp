#include "geometry/mesh_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <vector>

namespace superdex {

bool ReadMeshFile(const std::string& path, TriangleMesh* mesh, std::string* error) {
  std::string ext = path.substr(path.find_last_of('.') == std::string::npos ? path.size()
                                                                             : path.find_last_of('.') + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == "obj") return ReadObj(path, mesh, error);
  if (ext != "off" && ext != "stl" && ext != "ply") {
    *error = path + ": unknown mesh format \"." + ext + "\" (supported: .obj, .off, .stl, .ply)";
    return false;
  }
  if (!std::ifstream(path)) {
    *error = path + ": cannot open file";
    return false;
  }
  std::vector<CGAL::Exact_predicates_inexact_constructions_kernel::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  try {
    ok = CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false));
  } catch (const std::exception& e) {
    ok = false;
  }
  if (!ok) {
    *error = path + ": not a readable ." + ext + " file";
    return false;
  }
  *mesh = TriangleMesh();
  for (const auto& p : points) mesh->vertices.emplace_back(p.x(), p.y(), p.z());
  for (size_t f = 0; f < polygons.size(); ++f) {
    const auto& poly = polygons[f];
    if (poly.size() < 3) {
      *error = path + ": face " + std::to_string(f) + " has fewer than 3 corners";
      return false;
    }
    for (std::size_t v : poly)
      if (v >= points.size()) {
        *error = path + ": face " + std::to_string(f) + " index " + std::to_string(v) +
                 " out of range (" + std::to_string(points.size()) + " vertices)";
        return false;
      }
    for (size_t k = 1; k + 1 < poly.size(); ++k)
      mesh->faces.emplace_back(int(poly[0]), int(poly[k]), int(poly[k + 1]));
  }
  if (mesh->faces.empty()) {
    *error = path + ": no faces";
    return false;
  }
  return true;
}

}  // namespace superdex
