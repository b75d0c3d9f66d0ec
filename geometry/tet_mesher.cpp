// Tetrahedralization of closed surfaces with CGAL Mesh_3 (see tet_mesh.h). The only translation
// unit that includes Mesh_3 (slow to compile); one instantiation: Epick, Surface_mesh,
// Polyhedral_mesh_domain_3, sequential triangulation.
//
// CGAL::make_mesh_3 (make_mesh_3.h, refine_mesh_3.h, optimize_mesh_3.h) declares its options with
// Boost.Parameter, which alone costs GCC about 2 GB and 25 s. MeshC3t3 below runs the same steps
// as make_mesh_3 with a domain without features in CGAL 5.5 (initial points, Mesher_3
// refinement, sliver perturbation, sliver exudation) through the Mesh_3 classes directly.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_3/Mesher_3.h>
#include <CGAL/Mesh_3/Sliver_perturber.h>
#include <CGAL/Mesh_3/Slivers_exuder.h>
#include <CGAL/Mesh_3/sliver_criteria.h>
#include <CGAL/Mesh_3/vertex_perturbation.h>
#include <CGAL/Mesh_cell_criteria_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_edge_criteria_3.h>
#include <CGAL/Mesh_facet_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <map>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "geometry/tet_mesh.h"

namespace superdex {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Domain = CGAL::Polyhedral_mesh_domain_3<SurfaceMesh, Kernel>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using FacetCriteria = CGAL::Mesh_facet_criteria_3<Tr>;
using CellCriteria = CGAL::Mesh_cell_criteria_3<Tr>;
using SliverCriterion = CGAL::Mesh_3::Min_dihedral_angle_criterion<Tr>;

std::string Num(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// Criteria (facets and cells; a domain without features has no edge criteria) as the
// Mesh_criteria_3 of make_mesh_3.
struct Criteria {
  using Edge_criteria = CGAL::Mesh_edge_criteria_3<Tr>;
  using Facet_criteria = FacetCriteria;
  using Cell_criteria = CellCriteria;
  const Facet_criteria& facet_criteria_object() const { return facets; }
  const Cell_criteria& cell_criteria_object() const { return cells; }
  Facet_criteria facets;
  Cell_criteria cells;
};

// CGAL 5.5 make_mesh_3(domain, criteria, perturb(time_limit = 0), exude(time_limit = 0)) for a
// domain without features. The default time limits of perturbation and exudation (the wall-clock
// time of the refinement) would make the result timing dependent; 0 runs them to completion.
void MeshC3t3(const Domain& domain, const FacetCriteria& facets, const CellCriteria& cells,
              C3t3* c3t3) {
  // Initial points on the surface (Mesh_3::internal::init_c3t3, default number of points).
  std::vector<std::pair<Domain::Point_3, Domain::Index>> initial;
  domain.construct_initial_points_object()(std::back_inserter(initial));
  Tr& tr = c3t3->triangulation();
  const auto weighted = tr.geom_traits().construct_weighted_point_3_object();
  for (const auto& [point, index] : initial) {
    const Tr::Vertex_handle v = tr.insert(weighted(point));
    if (v != Tr::Vertex_handle()) {
      c3t3->set_dimension(v, 2);
      c3t3->set_index(v, index);
    }
  }
  // Delaunay refinement (refine_mesh_3_impl, non-manifold topology, no vertex limit).
  {
    const Criteria criteria{facets, cells};
    CGAL::Mesh_3::Mesher_3<C3t3, Criteria, Domain> mesher(*c3t3, domain, criteria);
    mesher.refine_mesh();
  }
  c3t3->clear_manifold_info();
  // Sliver perturbation (perturb_mesh_3 with its default criterion and perturbations).
  {
    using Perturber = CGAL::Mesh_3::Sliver_perturber<C3t3, Domain, SliverCriterion>;
    Perturber perturber(*c3t3, domain, SliverCriterion(0.0, tr));
    perturber.add_perturbation(
        new CGAL::Mesh_3::Sq_radius_perturbation<C3t3, Domain, SliverCriterion>(40, 0.05));
    perturber.add_perturbation(
        new CGAL::Mesh_3::Volume_perturbation<C3t3, Domain, SliverCriterion>(40, 0.05));
    perturber.add_perturbation(
        new CGAL::Mesh_3::Dihedral_angle_perturbation<C3t3, Domain, SliverCriterion>(40, 0.05));
    perturber.add_perturbation(
        new CGAL::Mesh_3::Li_random_perturbation<C3t3, Domain, SliverCriterion>(100, 0.15));
    perturber.set_time_limit(0.0);
    perturber();
  }
  // Sliver exudation (exude_mesh_3 with its default criterion).
  {
    CGAL::Mesh_3::Slivers_exuder<C3t3, SliverCriterion> exuder(*c3t3, SliverCriterion(0.0, tr));
    exuder.set_time_limit(0.0);
    exuder();
  }
}

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

}  // namespace

namespace {

// The mesh size of MeshTetsFromSurfaceSized as a Mesh_3 sizing field (facet size, cell size and,
// scaled by `scale`, facet distance).
struct SizeField {
  const MeshSizeField* size = nullptr;
  double scale = 1.0;
  Kernel::FT operator()(const Point& p, int, const Domain::Index&) const {
    return scale * (*size)(Eigen::Vector3d(p.x(), p.y(), p.z()));
  }
};

// Shared by both entry points: `field` null means the uniform size edgeLength.
bool Tetrahedralize(const TriangleMesh& surface, double edgeLength, const MeshSizeField* field,
                    TetMesh* out, std::string* error) {
  auto fail = [&](const std::string& message) {
    if (error) *error = "MeshTetsFromSurface: " + message;
    return false;
  };
  if (out == nullptr) return fail("no output mesh given");
  if (!field && (!(edgeLength > 0.0) || !std::isfinite(edgeLength)))
    return fail("edge length must be positive and finite (got " + Num(edgeLength) + " m)");
  if (field && !*field) return fail("no mesh size function given");
  if (surface.faces.empty()) return fail("the surface has no faces");
  const int nv = surface.NumVertices();
  for (int i = 0; i < nv; ++i)
    if (!surface.vertices[i].allFinite())
      return fail("surface vertex " + std::to_string(i) + " has a non-finite coordinate");
  for (int f = 0; f < surface.NumFaces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (surface.faces[f][k] < 0 || surface.faces[f][k] >= nv)
        return fail("surface face " + std::to_string(f) + " references vertex " +
                    std::to_string(surface.faces[f][k]) + " which does not exist (" +
                    std::to_string(nv) + " vertices)");
  std::string message;
  if (!CheckClosed(surface, &message)) return fail(message);

  // Size guard: a regular tet of edge h has volume h^3 / (6 sqrt 2).
  double volume = 0.0;
  for (const auto& f : surface.faces)
    volume += surface.vertices[f[0]].dot(surface.vertices[f[1]].cross(surface.vertices[f[2]])) / 6;
  double estimate = 0.0;
  if (!field) {
    estimate = std::abs(volume) / (edgeLength * edgeLength * edgeLength / 8.485);
  } else {
    // The size function at the centres of 24^3 cells of the bounding box, each cell's count
    // scaled by the solid's share of the box volume; the smallest size must be positive.
    Aabb box;
    for (const auto& v : surface.vertices) box.Extend(v);
    const Eigen::Vector3d ext = box.max - box.min;
    const int n = 24;
    const double cell = ext.x() * ext.y() * ext.z() / (n * n * n);
    const double share = ext.prod() > 0 ? std::abs(volume) / ext.prod() : 1.0;
    double smallest = INFINITY;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k) {
          const Eigen::Vector3d c =
              box.min + ext.cwiseProduct(Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5) / n);
          const double h = (*field)(c);
          smallest = std::min(smallest, h);
          if (h > 0.0) estimate += share * cell / (h * h * h / 8.485);
        }
    for (const auto& v : surface.vertices) smallest = std::min(smallest, (*field)(v));
    if (!(smallest > 0.0) || !std::isfinite(smallest))
      return fail("the mesh size function must be positive and finite (got " + Num(smallest) +
                  " m)");
  }
  if (estimate > 1e7)
    return fail((field ? std::string("the mesh size function") : "edge length " + Num(edgeLength) +
                                                                      " m") +
                " would give about " + Num(estimate) +
                " tets (limit 1e7); use a larger edge length");

  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> vi;
  vi.reserve(nv);
  for (const auto& v : surface.vertices) vi.push_back(sm.add_vertex(Point(v.x(), v.y(), v.z())));
  for (int f = 0; f < surface.NumFaces(); ++f) {
    const auto& q = surface.faces[f];
    if (sm.add_face(vi[q[0]], vi[q[1]], vi[q[2]]) == SurfaceMesh::null_face())
      return fail("the surface is non-manifold at a vertex of face " + std::to_string(f));
  }
  if (!CGAL::is_closed(sm)) return fail("the surface is not closed");

  TetMesh m;
  try {
    // A fresh generator with a fixed seed per call: the same input gives the same mesh, also
    // when meshing several times in one process.
    CGAL::Random rng(0);
    const Domain domain(sm, &rng);
    C3t3 c3t3;
    if (field) {
      const SizeField size{field, 1.0}, distance{field, 1.0 / 20.0};
      MeshC3t3(domain, FacetCriteria(25.0, size, distance), CellCriteria(3.0, size), &c3t3);
    } else {
      MeshC3t3(domain, FacetCriteria(25.0, edgeLength, edgeLength / 20.0),
               CellCriteria(3.0, edgeLength), &c3t3);
    }

    // Only the vertices of cells in the complex, numbered in order of first use.
    const Tr& tr = c3t3.triangulation();
    std::unordered_map<Tr::Vertex_handle, int> index;
    auto vertexIndex = [&](Tr::Vertex_handle v) {
      const auto it = index.find(v);
      if (it != index.end()) return it->second;
      const Point& x = tr.geom_traits().construct_point_3_object()(v->point());
      m.vertices.emplace_back(x.x(), x.y(), x.z());
      index.emplace(v, m.NumVertices() - 1);
      return m.NumVertices() - 1;
    };
    for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
      Eigen::Vector4i q;
      for (int k = 0; k < 4; ++k) q[k] = vertexIndex(c->vertex(k));
      m.tets.push_back(q);
      // CGAL's cells are positively oriented already; this only guards the convention.
      if (m.TetVolume(m.NumTets() - 1) < 0.0) std::swap(m.tets.back()[2], m.tets.back()[3]);
    }
  } catch (const std::exception& e) {
    return fail(std::string("CGAL Mesh_3 failed: ") + e.what());
  }
  if (m.tets.empty())
    return fail(field ? std::string("CGAL Mesh_3 produced no tets (is the mesh size much larger "
                                    "than the surface?)")
                      : "CGAL Mesh_3 produced no tets (is the edge length " + Num(edgeLength) +
                            " m much larger than the surface?)");
  *out = std::move(m);
  return true;
}

// Icosphere of the given radius subdivided until its edges are at most `longestEdge` (at most 7
// subdivisions).
TriangleMesh SphereSurface(double radius, double longestEdge) {
  TriangleMesh sphere;
  for (int s = 0; s <= 7; ++s) {
    sphere = MakeIcosphere(radius, s);
    double longest = 0.0;
    for (const auto& f : sphere.faces)
      for (int k = 0; k < 3; ++k)
        longest =
            std::max(longest, (sphere.vertices[f[k]] - sphere.vertices[f[(k + 1) % 3]]).norm());
    if (longest <= longestEdge) break;
  }
  return sphere;
}

}  // namespace

bool MeshTetsFromSurface(const TriangleMesh& surface, double edgeLength, TetMesh* out,
                         std::string* error) {
  return Tetrahedralize(surface, edgeLength, nullptr, out, error);
}

bool MeshTetsFromSurfaceSized(const TriangleMesh& surface, const MeshSizeField& edgeLength,
                              TetMesh* out, std::string* error) {
  return Tetrahedralize(surface, 0.0, &edgeLength, out, error);
}

TetMesh MakeGradedTetSphere(double radius, const Eigen::Vector3d& pole, double fineEdgeLength,
                            double fineRadius, double grading, double coarseEdgeLength) {
  if (!(radius > 0.0) || !(fineEdgeLength > 0.0) || !(coarseEdgeLength >= fineEdgeLength) ||
      !(fineRadius >= 0.0) || !(grading > 0.0) || !(pole.norm() > 0.0) || !pole.allFinite())
    return TetMesh();
  const Eigen::Vector3d p = radius * pole.normalized();
  const MeshSizeField size = [=](const Eigen::Vector3d& x) {
    return std::min(coarseEdgeLength,
                    fineEdgeLength + grading * std::max(0.0, (x - p).norm() - fineRadius));
  };
  TetMesh out;
  std::string error;
  if (!MeshTetsFromSurfaceSized(SphereSurface(radius, 0.5 * fineEdgeLength), size, &out, &error))
    return TetMesh();
  return out;
}

TetMesh MakeTetSphere(double radius, double edgeLength) {
  if (!(radius > 0.0) || !(edgeLength > 0.0)) return TetMesh();
  TetMesh out;
  std::string error;
  if (!MeshTetsFromSurface(SphereSurface(radius, 0.5 * edgeLength), edgeLength, &out, &error))
    return TetMesh();
  return out;
}

}  // namespace superdex
