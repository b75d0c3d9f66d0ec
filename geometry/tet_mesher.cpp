// Tetrahedralization of closed surfaces with CGAL Mesh_3 (see tet_mesh.h). The only translation
// unit that includes Mesh_3 (slow to compile); one instantiation: Epick, Surface_mesh,
// Polyhedral_mesh_domain_3, sequential triangulation.
//
// CGAL::make_mesh_3 (make_mesh_3.h, refine_mesh_3.h, optimize_mesh_3.h) declares its options with
// Boost.Parameter, which alone costs GCC about 2 GB and 25 s. MeshC3t3 below runs the same steps
// as make_mesh_3 with a domain without features in CGAL 5.5 (initial points, Mesher_3
// refinement, sliver perturbation, sliver exudation) through the Mesh_3 classes directly, each
// stage bounded (MeshingLimits): a stage that makes no progress is stopped and reported.
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
#include <CGAL/point_generators_3.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <unordered_map>
#include <utility>

#include "geometry/mesh_limits.h"
#include "geometry/mesher_input.h"
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
using Clock = std::chrono::steady_clock;

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

// Sets *stop once the deadline has passed, unless Finish() comes first: the refinement checks
// the flag between its steps.
class Watchdog {
 public:
  Watchdog(Clock::time_point deadline, std::atomic<bool>* stop)
      : thread_([this, deadline, stop] {
          std::unique_lock<std::mutex> lock(mutex_);
          if (!done_.wait_until(lock, deadline, [this] { return finished_; })) *stop = true;
        }) {}
  ~Watchdog() { Finish(); }
  void Finish() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      finished_ = true;
    }
    done_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

 private:
  std::mutex mutex_;
  std::condition_variable done_;
  bool finished_ = false;
  std::thread thread_;
};

// CGAL 5.5's Polyhedral_mesh_domain_3::Construct_initial_points (8 points, the same rays from the
// same generator, so the same points) with a bound on the rays: CGAL's own loop never ends when
// no ray from the bounding-box centre hits the surface.
bool InitialPoints(const Domain& domain, CGAL::Random& rng,
                   std::vector<std::pair<Domain::Point_3, Domain::Index>>* out) {
  const auto ray = Domain::R().construct_ray_3_object();
  const auto vector = Domain::R().construct_vector_3_object();
  const CGAL::Bbox_3 box = domain.bbox();
  const Domain::Point_3 center(Domain::FT((box.xmin() + box.xmax()) / 2),
                               Domain::FT((box.ymin() + box.ymax()) / 2),
                               Domain::FT((box.zmin() + box.zmax()) / 2));
  CGAL::Random_points_on_sphere_3<Domain::Point_3> randomPoint(1., rng);
  int needed = 8;
  for (int shot = 0; needed > 0 && shot < limits::kMesherInitialPointRays; ++shot) {
    const Domain::Ray_3 r = ray(center, vector(CGAL::ORIGIN, *randomPoint));
    const Domain::Intersection hit = domain.construct_intersection_object()(r);
    if (std::get<2>(hit) != 0) {
      out->emplace_back(std::get<0>(hit), std::get<1>(hit));
      --needed;
    }
    ++randomPoint;
  }
  return needed == 0;
}

double SecondsLeft(Clock::time_point deadline) {
  return std::chrono::duration<double>(deadline - Clock::now()).count();
}

// CGAL 5.5 make_mesh_3(domain, criteria, perturb(time_limit = 0), exude(time_limit = 0)) for a
// domain without features, within the budget of `in`: the refinement stops at in.maxVertices or
// at the deadline, perturbation and exudation at the deadline (they otherwise run to completion,
// so the result does not depend on timing unless a budget runs out, which fails). "" on success.
std::string MeshC3t3(const Domain& domain, CGAL::Random& rng, const FacetCriteria& facets,
                     const CellCriteria& cells, const MesherInput& in, C3t3* c3t3) {
  const Clock::time_point deadline =
      Clock::now() + std::chrono::microseconds(static_cast<long long>(in.seconds * 1e6));
  const std::string budget = " (the budget for about " + MesherNum(std::ceil(in.estimatedTets)) +
                             " tets: " +
                             MesherNum(in.seconds) + " s, " + std::to_string(in.maxVertices) +
                             " vertices)";
  std::vector<std::pair<Domain::Point_3, Domain::Index>> initial;
  if (!InitialPoints(domain, rng, &initial))
    return "no initial points: " + std::to_string(limits::kMesherInitialPointRays) +
           " rays from the bounding-box centre found fewer than 8 surface points (is the "
           "surface degenerate?)";
  Tr& tr = c3t3->triangulation();
  const auto weighted = tr.geom_traits().construct_weighted_point_3_object();
  for (const auto& [point, index] : initial) {
    const Tr::Vertex_handle v = tr.insert(weighted(point));
    if (v != Tr::Vertex_handle()) {
      c3t3->set_dimension(v, 2);
      c3t3->set_index(v, index);
    }
  }
  // Delaunay refinement (refine_mesh_3_impl, non-manifold topology).
  {
    std::atomic<bool> stop(false);
    CGAL::Mesh_error_code code = CGAL::CGAL_MESH_3_NO_ERROR;
    Watchdog watchdog(deadline, &stop);
    const Criteria criteria{facets, cells};
    CGAL::Mesh_3::Mesher_3<C3t3, Criteria, Domain> mesher(*c3t3, domain, criteria, 0,
                                                          in.maxVertices, &code, &stop);
    mesher.refine_mesh();
    watchdog.Finish();
    if (code == CGAL::CGAL_MESH_3_STOPPED)
      return "the Delaunay refinement did not finish in time" + budget;
    if (code == CGAL::CGAL_MESH_3_MAXIMAL_NUMBER_OF_VERTICES_REACHED)
      return "the Delaunay refinement does not converge: it reached the vertex budget" + budget;
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
    const double left = SecondsLeft(deadline);
    if (!(left > 0)) return "no time left for the sliver perturbation" + budget;
    perturber.set_time_limit(left);
    if (perturber() == CGAL::TIME_LIMIT_REACHED)
      return "the sliver perturbation did not finish in time" + budget;
  }
  // Sliver exudation (exude_mesh_3 with its default criterion).
  {
    CGAL::Mesh_3::Slivers_exuder<C3t3, SliverCriterion> exuder(*c3t3, SliverCriterion(0.0, tr));
    const double left = SecondsLeft(deadline);
    if (!(left > 0)) return "no time left for the sliver exudation" + budget;
    exuder.set_time_limit(left);
    if (exuder() == CGAL::TIME_LIMIT_REACHED)
      return "the sliver exudation did not finish in time" + budget;
  }
  return "";
}

// The mesh size of MeshTetsFromSurfaceSized as a Mesh_3 sizing field (facet size, cell size and,
// scaled by `scale`, facet distance).
struct SizeField {
  const MeshSizeField* size = nullptr;
  double scale = 1.0;
  Kernel::FT operator()(const Point& p, int, const Domain::Index&) const {
    return scale * (*size)(Eigen::Vector3d(p.x(), p.y(), p.z()));
  }
};

// The tets of the complex, on the vertices they use (numbered in order of first use), moved
// back from normalized coordinates.
TetMesh ExtractTets(const C3t3& c3t3, const MesherInput& in) {
  TetMesh m;
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
  if (in.scale != 1.0 || !in.center.isZero())
    for (Eigen::Vector3d& v : m.vertices) v = v / in.scale + in.center;
  return m;
}

// Shared by both entry points: `field` null means the uniform size edgeLength.
bool Tetrahedralize(const TriangleMesh& surface, double edgeLength, const MeshSizeField* field,
                    const MeshingLimits& bounds, TetMesh* out, std::string* error) {
  auto fail = [&](const std::string& message) {
    if (error) *error = "MeshTetsFromSurface: " + message;
    return false;
  };
  if (out == nullptr) return fail("no output mesh given");
  MesherInput in;
  std::string message;
  if (!PrepareMesherInput(surface, edgeLength, field, bounds, &in, &message)) return fail(message);

  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> vi;
  vi.reserve(in.surface.vertices.size());
  for (const auto& v : in.surface.vertices) vi.push_back(sm.add_vertex(Point(v.x(), v.y(), v.z())));
  for (int f = 0; f < in.surface.NumFaces(); ++f) {
    const auto& q = in.surface.faces[f];
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
      const SizeField size{&in.field, 1.0}, distance{&in.field, 1.0 / 20.0};
      message = MeshC3t3(domain, rng, FacetCriteria(25.0, size, distance),
                         CellCriteria(3.0, size), in, &c3t3);
    } else {
      const double h = in.edgeLength;
      message = MeshC3t3(domain, rng, FacetCriteria(25.0, h, h / 20.0), CellCriteria(3.0, h), in,
                         &c3t3);
    }
    if (!message.empty()) return fail("CGAL Mesh_3 stopped: " + message);
    m = ExtractTets(c3t3, in);
  } catch (const std::exception& e) {
    return fail(std::string("CGAL Mesh_3 failed: ") + e.what());
  }
  if (m.tets.empty())
    return fail(field ? std::string("CGAL Mesh_3 produced no tets (is the mesh size much larger "
                                    "than the surface?)")
                      : "CGAL Mesh_3 produced no tets (is the edge length " +
                            MesherNum(edgeLength) + " m much larger than the surface?)");
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
                         std::string* error, const MeshingLimits& bounds) {
  return Tetrahedralize(surface, edgeLength, nullptr, bounds, out, error);
}

bool MeshTetsFromSurfaceSized(const TriangleMesh& surface, const MeshSizeField& edgeLength,
                              TetMesh* out, std::string* error, const MeshingLimits& bounds) {
  return Tetrahedralize(surface, 0.0, &edgeLength, bounds, out, error);
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

bool MeshTetSphere(double radius, double edgeLength, TetMesh* out, std::string* error,
                   const MeshingLimits& bounds) {
  if (!(radius > 0.0 && std::isfinite(radius) && edgeLength > 0.0 && std::isfinite(edgeLength))) {
    if (error)
      *error = "MeshTetSphere: radius and edge length must be positive and finite (got " +
               MesherNum(radius) + " m, " + MesherNum(edgeLength) + " m)";
    return false;
  }
  return MeshTetsFromSurface(SphereSurface(radius, 0.5 * edgeLength), edgeLength, out, error,
                             bounds);
}

TetMesh MakeTetSphere(double radius, double edgeLength) {
  TetMesh out;
  std::string error;
  if (!MeshTetSphere(radius, edgeLength, &out, &error)) return TetMesh();
  return out;
}

}  // namespace superdex
