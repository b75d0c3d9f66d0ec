#include "core/model/soft_body.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geometry/mesh_sdf.h"

namespace superdex {

Eigen::Vector3d NodeConstraint::Displacement(double t) const { return PiecewiseLinear(path, t); }

bool ValidatePlacement(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                       const Eigen::Vector3d& velocity, const std::string& prefix, Error* error) {
  if (position.allFinite() && velocity.allFinite() && orientation.coeffs().allFinite() &&
      orientation.norm() >= 1e-12)
    return true;
  return Fail(error, prefix + "position, orientation, linear_velocity: must be finite (and the "
                              "orientation nonzero)");
}

bool ValidateNodeConstraints(const std::vector<NodeConstraint>& constraints, int n,
                             const std::string& prefix, Error* error) {
  for (size_t c = 0; c < constraints.size(); ++c) {
    const NodeConstraint& k = constraints[c];
    const std::string field = prefix + "constraints[" + std::to_string(c) + "]";
    if (k.nodes.empty()) return Fail(error, field + ".nodes: must not be empty");
    for (int i : k.nodes)
      if (i < 0 || i >= n)
        return Fail(error, field + ".nodes: node " + std::to_string(i) +
                               " does not exist (the mesh has " + std::to_string(n) + " nodes)");
    if (std::string msg = CheckKeyframes(k.path, field + ".path"); !msg.empty())
      return Fail(error, msg);
  }
  return true;
}

bool BuildSoftBody(const SoftActorDesc& d, const std::string& prefix, SoftBodyModel* m,
                   SoftBodyState* st, Error* error) {
  if (!d.mesh) return Fail(error, prefix + "mesh: a tet mesh is required");
  const std::string source = d.meshSource.empty() ? "mesh" : d.meshSource;
  std::string message;
  if (!ValidateTetMesh(*d.mesh, source, &message)) return Fail(error, prefix + "mesh: " + message);
  if (std::string e = Validate(d.material, prefix + "material."); !e.empty()) return Fail(error, e);
  if (std::string e = Validate(d.contact, prefix + "contact."); !e.empty()) return Fail(error, e);
  if (!ValidatePlacement(d.position, d.orientation, d.linearVelocity, prefix, error)) return false;
  if (d.colliderType != ColliderType::None && d.colliderType != ColliderType::Sdf &&
      d.colliderType != ColliderType::Auto)
    return Fail(error, prefix + "collider_type: " + ToString(d.colliderType) +
                           " is not available for soft actors (expected None, Sdf or Auto)");
  const int n = d.mesh->NumVertices();
  if (!ValidateNodeConstraints(d.constraints, n, prefix, error)) return false;

  *m = SoftBodyModel();
  m->name = d.name;
  m->material = d.material;
  m->lame = LameFromYoungPoisson(d.material.youngsModulus, d.material.poissonRatio);
  m->contact = d.contact;
  m->boundaryElementType = d.boundaryElementType;
  m->contactLayer = d.contactLayer;
  m->constraints = d.constraints;
  // The rest shape is placed in the world: reference coordinates are world coordinates at t = 0.
  const Eigen::Matrix3d R = d.orientation.normalized().toRotationMatrix();
  m->rest = *d.mesh;
  for (Eigen::Vector3d& v : m->rest.vertices) v = d.position + R * v;

  m->elements.resize(m->rest.NumTets());
  m->nodeMass.setZero(n);
  for (int t = 0; t < m->rest.NumTets(); ++t) {
    const Eigen::Vector4i& T = m->rest.tets[t];
    const Eigen::Vector3d X[4] = {m->rest.vertices[T[0]], m->rest.vertices[T[1]],
                                  m->rest.vertices[T[2]], m->rest.vertices[T[3]]};
    if (!MakeTetElement(X, &m->elements[t]))
      return Fail(error, prefix + "mesh: " + source + ": tet " + std::to_string(t) +
                             " is degenerate or inverted");
    const double mt = d.material.density * m->elements[t].restVolume;
    for (int a = 0; a < 4; ++a) m->nodeMass[T[a]] += 0.25 * mt;
    m->mass += mt;
  }
  if (!std::isfinite(m->mass))
    return Fail(error, prefix + "mesh: " + source + ": the mass (density x volume) is not " +
                           "representable in double precision");
  for (int i = 0; i < n; ++i)
    if (!(m->nodeMass[i] > 0))
      return Fail(error, prefix + "mesh: " + source + ": node " + std::to_string(i) +
                             " belongs to no tet");

  // Colliding role: quadrature samples on the boundary faces.
  m->faces = BoundaryFaces(m->rest);
  const TriangleQuadratureRule& rule = GetTriangleQuadratureRule(d.boundaryElementType);
  m->faceArea.resize(m->faces.size());
  m->faceSampleBegin.assign(m->faces.size() + 1, 0);
  for (size_t f = 0; f < m->faces.size(); ++f) {
    const Eigen::Vector3i& F = m->faces[f];
    const Eigen::Vector3d& a = m->rest.vertices[F[0]];
    const double area =
        0.5 * (m->rest.vertices[F[1]] - a).cross(m->rest.vertices[F[2]] - a).norm();
    m->faceArea[f] = area;
    m->faceSampleBegin[f] = static_cast<int>(m->samples.size());
    for (size_t q = 0; q < rule.weights.size(); ++q)
      m->samples.push_back({static_cast<int>(f), rule.barycentric[q], area * rule.weights[q]});
  }
  m->faceSampleBegin[m->faces.size()] = static_cast<int>(m->samples.size());

  // Collider role (experimental): the grid SDF of the reference boundary surface.
  if (d.colliderType == ColliderType::Sdf || d.colliderType == ColliderType::Auto) {
    TriangleMesh surface;  // the boundary faces on their own vertices
    std::vector<int> map(n, -1);
    for (const Eigen::Vector3i& F : m->faces) {
      Eigen::Vector3i g;
      for (int k = 0; k < 3; ++k) {
        if (map[F[k]] < 0) {
          map[F[k]] = surface.NumVertices();
          surface.vertices.push_back(m->rest.vertices[F[k]]);
        }
        g[k] = map[F[k]];
      }
      surface.faces.push_back(g);
    }
    std::string why;
    auto exact = MeshSdf::Build(surface, &why);
    if (!exact)
      return Fail(error, prefix + "mesh: " + source + ": the boundary surface " + why +
                             "; collider_type Sdf needs a closed surface");
    m->colliderGrid = BuildGridSdf(
        surface, [exact](const Eigen::Vector3d& X) { return exact->Value(X); }, d.gridSdf, &why);
    if (!m->colliderGrid) return Fail(error, prefix + "grid_sdf: " + why);
    m->collider = ColliderType::Sdf;
    const Eigen::Vector3i nodes = m->colliderGrid->Nodes();
    std::ostringstream note;
    note << "actor '" << d.name << "': soft collider grid SDF " << nodes.x() << " x " << nodes.y()
         << " x " << nodes.z() << " nodes, voxel " << m->colliderGrid->Spacing() << " m, "
         << m->colliderGrid->MemoryBytes() / 1048576.0 << " MiB (experimental)";
    m->notice = note.str();
  }

  // Free and prescribed nodes.
  std::vector<char> prescribed(n, 0);
  for (const NodeConstraint& k : d.constraints)
    for (int i : k.nodes) prescribed[i] = 1;
  m->freeIndex.assign(n, -1);
  for (int i = 0; i < n; ++i)
    if (!prescribed[i]) m->freeIndex[i] = m->numFree++;

  st->x.resize(3 * n);
  st->v.resize(3 * n);
  for (int i = 0; i < n; ++i) {
    st->x.segment<3>(3 * i) = m->rest.vertices[i];
    st->v.segment<3>(3 * i) = prescribed[i] ? Eigen::Vector3d::Zero() : d.linearVelocity;
  }
  return true;
}

void ApplyNodeConstraints(const SoftBodyModel& m, const Eigen::VectorXd& initial, double t,
                          Eigen::VectorXd* x) {
  ApplyNodeConstraints(m.constraints, initial, t, x);
}

void ApplyNodeConstraints(const std::vector<NodeConstraint>& constraints,
                          const Eigen::VectorXd& initial, double t, Eigen::VectorXd* x) {
  for (const NodeConstraint& k : constraints) {
    const Eigen::Vector3d u = k.Displacement(t);
    for (int i : k.nodes) x->segment<3>(3 * i) = initial.segment<3>(3 * i) + u;
  }
}

double KineticEnergy(const SoftBodyModel& m, const SoftBodyState& s) {
  double e = 0.0;
  for (int i = 0; i < m.NumNodes(); ++i) e += 0.5 * m.nodeMass[i] * s.v.segment<3>(3 * i).squaredNorm();
  return e;
}

double ElasticEnergy(const SoftBodyModel& m, const Eigen::VectorXd& x, double* minDetF) {
  double e = 0.0;
  double minDet = INFINITY;
  TetElasticTerm term;
  for (int t = 0; t < m.rest.NumTets(); ++t) {
    const Eigen::Vector4i& T = m.rest.tets[t];
    const Eigen::Vector3d xs[4] = {x.segment<3>(3 * T[0]), x.segment<3>(3 * T[1]),
                                   x.segment<3>(3 * T[2]), x.segment<3>(3 * T[3])};
    EvaluateStableNeoHookean(m.elements[t], m.lame, xs, 0, false, &term);
    e += term.value;
    minDet = std::min(minDet, term.detF);
  }
  if (minDetF) *minDetF = minDet;
  return e;
}

Aabb SoftBounds(const Eigen::VectorXd& x) {
  Aabb b;
  for (Eigen::Index i = 0; i < x.size() / 3; ++i) b.Extend(x.segment<3>(3 * i));
  return b;
}

double TriangleBall(const Eigen::VectorXd& x, const Eigen::Vector3i& F, Eigen::Vector3d* c) {
  const Eigen::Vector3d a = x.segment<3>(3 * F[0]), b = x.segment<3>(3 * F[1]),
                        d = x.segment<3>(3 * F[2]);
  *c = (a + b + d) / 3.0;
  return std::max({(a - *c).norm(), (b - *c).norm(), (d - *c).norm()});
}

Eigen::Vector3d SoftFaceNormal(const SoftBodyModel& m, const Eigen::VectorXd& x, int f) {
  const Eigen::Vector3i& F = m.faces[f];
  const Eigen::Vector3d a = x.segment<3>(3 * F[0]);
  const Eigen::Vector3d n = (x.segment<3>(3 * F[1]) - a).cross(x.segment<3>(3 * F[2]) - a);
  const double len = n.norm();
  return len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

}  // namespace superdex
