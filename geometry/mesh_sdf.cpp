#include "geometry/mesh_sdf.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <utility>

namespace superdex {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Inside = CGAL::Side_of_triangle_mesh<Mesh, Kernel>;

Eigen::Vector3d ToEigen(const Point& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

struct MeshSdf::Impl {
  Mesh mesh;
  Tree tree;
  std::unique_ptr<Inside> inside;
  TriangleMesh triangles;  // our copy, face f = CGAL face index f
};

MeshSdf::MeshSdf(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
MeshSdf::~MeshSdf() = default;

std::shared_ptr<const MeshSdf> MeshSdf::Build(const TriangleMesh& tri, std::string* error) {
  if (tri.faces.empty()) {
    *error = "mesh: has no faces";
    return nullptr;
  }
  // Closed: every directed edge has its reverse exactly once.
  std::map<std::pair<int, int>, int> directed;
  for (const Eigen::Vector3i& f : tri.faces)
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  for (const auto& [e, count] : directed) {
    if (count > 1) {
      *error = "mesh: not manifold or inconsistently oriented (edge " + std::to_string(e.first) +
               "-" + std::to_string(e.second) + " is used twice in the same direction)";
      return nullptr;
    }
    if (!directed.count({e.second, e.first})) {
      *error = "mesh: not closed (boundary edge " + std::to_string(e.first) + "-" +
               std::to_string(e.second) + ")";
      return nullptr;
    }
  }
  double volume = 0.0;
  for (const Eigen::Vector3i& f : tri.faces)
    volume += tri.vertices[f[0]].dot(tri.vertices[f[1]].cross(tri.vertices[f[2]])) / 6.0;
  if (!(volume > 0.0)) {
    *error = "mesh: inward oriented or degenerate (signed volume " + std::to_string(volume) + ")";
    return nullptr;
  }
  auto impl = std::make_unique<Impl>();
  impl->triangles = tri;
  std::vector<Mesh::Vertex_index> v;
  for (const Eigen::Vector3d& x : tri.vertices) v.push_back(impl->mesh.add_vertex(Point(x.x(), x.y(), x.z())));
  for (const Eigen::Vector3i& f : tri.faces) {
    if (impl->mesh.add_face(v[f[0]], v[f[1]], v[f[2]]) == Mesh::null_face()) {
      *error = "mesh: not manifold (a face cannot be added to the half-edge structure)";
      return nullptr;
    }
  }
  impl->tree.insert(faces(impl->mesh).first, faces(impl->mesh).second, impl->mesh);
  impl->tree.build();
  impl->tree.accelerate_distance_queries();
  impl->inside = std::make_unique<Inside>(impl->mesh);
  std::shared_ptr<MeshSdf> out(new MeshSdf(std::move(impl)));
  for (const Eigen::Vector3d& x : tri.vertices) out->radius_ = std::max(out->radius_, x.norm());
  return out;
}

double MeshSdf::Value(const Eigen::Vector3d& X) const {
  const Point p(X.x(), X.y(), X.z());
  const double d = std::sqrt(impl_->tree.squared_distance(p));
  return (*impl_->inside)(p) == CGAL::ON_BOUNDED_SIDE ? -d : d;
}

SdfSample MeshSdf::Evaluate(const Eigen::Vector3d& X) const {
  const Point p(X.x(), X.y(), X.z());
  const auto [closest, face] = impl_->tree.closest_point_and_primitive(p);
  const Eigen::Vector3d c = ToEigen(closest);
  const double sign = (*impl_->inside)(p) == CGAL::ON_BOUNDED_SIDE ? -1.0 : 1.0;
  const Eigen::Vector3i& f = impl_->triangles.faces[static_cast<int>(face.idx())];
  const Eigen::Vector3d a = impl_->triangles.vertices[f[0]], b = impl_->triangles.vertices[f[1]],
                        e = impl_->triangles.vertices[f[2]];
  SdfSample s;
  const Eigen::Vector3d diff = X - c;
  const double dist = diff.norm();
  s.value = sign * dist;
  const Eigen::Vector3d normal = (b - a).cross(e - a).normalized();
  // Barycentric coordinates of c in its face: which feature is closest.
  const Eigen::Vector3d v0 = b - a, v1 = e - a, v2 = c - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0),
               d21 = v2.dot(v1), den = d00 * d11 - d01 * d01;
  const double l1 = (d11 * d20 - d01 * d21) / den, l2 = (d00 * d21 - d01 * d20) / den;
  const double lambda[3] = {1.0 - l1 - l2, l1, l2};
  const double tol = 1e-9;
  int zeros = 0;
  for (double l : lambda) zeros += l < tol;
  const double scale = std::sqrt(std::max(d00, d11));
  if (zeros == 0 || dist < 1e-12 * std::max(1.0, scale)) {
    s.gradient = normal;  // face interior (or on the surface)
    return s;
  }
  s.gradient = sign * diff / dist;
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - s.gradient * s.gradient.transpose();
  if (zeros == 1) {  // an edge: the one opposite the zero coordinate
    const Eigen::Vector3d verts[3] = {a, b, e};
    int k = lambda[0] < tol ? 0 : lambda[1] < tol ? 1 : 2;
    const Eigen::Vector3d t = (verts[(k + 2) % 3] - verts[(k + 1) % 3]).normalized();
    s.hessian = (P - t * t.transpose()) / s.value;
  } else {
    s.hessian = P / s.value;
  }
  return s;
}

}  // namespace superdex
