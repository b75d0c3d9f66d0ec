#include "core/model/shell_body.h"

#include <cmath>
#include <array>
#include <utility>

namespace superdex {
namespace {

// Empty when every interior edge's two faces traverse it in opposite directions; else the first
// edge that they do not.
std::string Orientation(const std::vector<Eigen::Vector3i>& faces,
                        const std::vector<Eigen::Vector3i>& oppositeFace) {
  for (size_t f = 0; f < faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const int g = oppositeFace[f][i];
      if (g < 0) continue;
      const int u = faces[f][(i + 1) % 3], v = faces[f][(i + 2) % 3];
      for (int k = 0; k < 3; ++k)
        if (faces[g][k] == u && faces[g][(k + 1) % 3] == v)
          return "edge (" + std::to_string(u) + ", " + std::to_string(v) +
                 ") is traversed the same way by triangles " + std::to_string(f) + " and " +
                 std::to_string(g) + " (the mesh must be consistently oriented)";
    }
  return {};
}

Eigen::Matrix<double, 12, 1> HingeNodes(const std::vector<Eigen::Vector3d>& X, const ShellHinge& h) {
  Eigen::Matrix<double, 12, 1> x;
  for (int k = 0; k < 4; ++k) x.segment<3>(3 * k) = X[h.node[k]];
  return x;
}

}  // namespace

MidedgeStencil MidedgeNodes(const std::vector<Eigen::Vector3d>& X, const Eigen::Vector3i& face,
                            const Eigen::Vector3i& opposite) {
  MidedgeStencil x = MidedgeStencil::Zero();
  for (int k = 0; k < 3; ++k) {
    x.segment<3>(3 * k) = X[face[k]];
    if (opposite[k] >= 0) x.segment<3>(9 + 3 * k) = X[opposite[k]];
  }
  return x;
}

std::array<bool, 3> Has(const Eigen::Vector3i& opposite) {
  return {opposite[0] >= 0, opposite[1] >= 0, opposite[2] >= 0};
}

constexpr EnumName<ShellBendingModel> kBendingModels[] = {{ShellBendingModel::Midedge, "Midedge"},
                                                         {ShellBendingModel::Hinge, "Hinge"}};

EnumNames<ShellBendingModel> NamesOf(ShellBendingModel) { return kBendingModels; }

namespace {

// The collider points: the nodes with their lumped areas m_a/(ρ h), or the triangles' quadrature
// points of the chosen rule with A w_q.
void AddCloudPoints(const PointCloudColliderParams& p, const ShellMaterial& mat, ShellModel* m) {
  if (!p.colliderTriangleElementType) {
    for (int a = 0; a < m->NumNodes(); ++a)
      m->cloudPoints.push_back({a, -1, Eigen::Vector3d::Zero(),
                                m->nodeMass[a] / (mat.density * mat.thickness)});
    return;
  }
  const TriangleQuadratureRule& rule = GetTriangleQuadratureRule(*p.colliderTriangleElementType);
  for (size_t f = 0; f < m->faces.size(); ++f)
    for (size_t q = 0; q < rule.weights.size(); ++q)
      m->cloudPoints.push_back({-1, static_cast<int>(f), rule.barycentric[q],
                                m->triangles[f].restArea * rule.weights[q]});
}

}  // namespace

bool BuildShell(const ShellActorDesc& d, const std::string& prefix, ShellModel* m,
                VectorState* state, Error* error) {
  if (!d.mesh || d.mesh->NumFaces() == 0)
    return Fail(error, prefix + "mesh: a triangle mesh of at least one triangle is required");
  const std::string source = d.meshSource.empty() ? "mesh" : d.meshSource;
  if (std::string e = Validate(d.material, prefix + "material."); !e.empty()) return Fail(error, e);
  if (std::string e = Validate(d.contact, prefix + "contact."); !e.empty()) return Fail(error, e);
  if (!ValidatePlacement(d.position, d.orientation, d.linearVelocity, prefix, error)) return false;
  if (d.colliderType != ColliderType::Auto && d.colliderType != ColliderType::None &&
      d.colliderType != ColliderType::PointCloud)
    return Fail(error, prefix + "collider_type: " + ToString(d.colliderType) +
                           " is not available for shell actors (expected Auto, None or PointCloud: "
                           "a shell has no distance field of its own)");
  if (std::string e = Validate(d.pointCloud, prefix + "point_cloud."); !e.empty())
    return Fail(error, e);
  const int n = d.mesh->NumVertices();
  for (int f = 0; f < d.mesh->NumFaces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (d.mesh->faces[f][k] < 0 || d.mesh->faces[f][k] >= n)
        return Fail(error, prefix + "mesh: " + source + ": triangle " + std::to_string(f) +
                               " names a vertex that does not exist");
  if (!ValidateNodeConstraints(d.constraints, n, prefix, error)) return false;
  for (size_t k = 0; k < d.loads.size(); ++k) {
    const std::string field = prefix + "loads[" + std::to_string(k) + "]";
    for (int i : d.loads[k].nodes)
      if (i < 0 || i >= n)
        return Fail(error, field + ".nodes: node " + std::to_string(i) +
                               " does not exist (the mesh has " + std::to_string(n) + " nodes)");
    if (d.loads[k].force.empty()) return Fail(error, field + ".force: at least one keyframe");
    if (std::string e = CheckKeyframes(d.loads[k].force, field + ".force"); !e.empty())
      return Fail(error, e);
  }
  std::vector<char> clamped(n, 0);
  for (int i : d.clampedNodes) {
    if (i < 0 || i >= n)
      return Fail(error, prefix + "clamped_nodes: node " + std::to_string(i) +
                             " does not exist (the mesh has " + std::to_string(n) + " nodes)");
    clamped[i] = 1;
  }

  *m = ShellModel();
  m->name = d.name;
  m->material = d.material;
  m->faces = d.mesh->faces;
  m->constraints = d.constraints;
  m->loads = d.loads;
  if (!d.clampedNodes.empty()) m->constraints.push_back(NodeConstraint{d.clampedNodes, {}});
  const ShellMaterial& mat = d.material;
  m->lame = PlaneStressLame(mat.youngsModulus, mat.poissonRatio);
  m->plateStiffness = mat.youngsModulus * std::pow(mat.thickness, 3) /
                      (12.0 * (1.0 - mat.poissonRatio * mat.poissonRatio));
  // The rest shape placed in the world: reference coordinates are world coordinates at t = 0.
  const Eigen::Matrix3d R = d.orientation.normalized().toRotationMatrix();
  std::vector<Eigen::Vector3d> X(n);
  for (int i = 0; i < n; ++i) X[i] = d.position + R * d.mesh->vertices[i];
  const Aabb box = d.mesh->Bounds();
  const double scale = (box.max - box.min).norm();
  m->nodeMass.setZero(n);
  const TriangleQuadratureRule& rule = GetTriangleQuadratureRule(d.contactElementType);
  m->faceSampleBegin.assign(m->faces.size() + 1, 0);
  for (size_t f = 0; f < m->faces.size(); ++f) {
    const Eigen::Vector3i& F = m->faces[f];
    const ShellTriangle t = MakeShellTriangle(X[F[0]], X[F[1]], X[F[2]]);
    if (!(t.restArea > 1e-12 * scale * scale))
      return Fail(error, prefix + "mesh: " + source + ": triangle " + std::to_string(f) +
                             " is degenerate (zero area)");
    m->triangles.push_back(t);
    const double mass = mat.density * mat.thickness * t.restArea;
    for (int k = 0; k < 3; ++k) m->nodeMass[F[k]] += mass / 3.0;
    m->mass += mass;
    m->faceSampleBegin[f] = static_cast<int>(m->samples.size());
    for (size_t q = 0; q < rule.weights.size(); ++q)
      m->samples.push_back({static_cast<int>(f), rule.barycentric[q], t.restArea * rule.weights[q]});
  }
  m->faceSampleBegin.back() = static_cast<int>(m->samples.size());
  m->pointCloud = d.colliderType != ColliderType::None;
  m->cloud = d.pointCloud;
  if (m->pointCloud) AddCloudPoints(d.pointCloud, mat, m);
  for (int i = 0; i < n; ++i)
    if (!(m->nodeMass[i] > 0))
      return Fail(error, prefix + "mesh: " + source + ": vertex " + std::to_string(i) +
                             " belongs to no triangle");
  std::pair<int, int> bad;
  std::vector<Eigen::Vector3i> oppositeFace;
  if (!FaceOppositeVertices(m->faces, &m->opposite, &bad, &oppositeFace))
    return Fail(error, prefix + "mesh: " + source + ": edge (" + std::to_string(bad.first) + ", " +
                           std::to_string(bad.second) +
                           ") is shared by more than two triangles (a shell is a manifold)");
  if (std::string why = Orientation(m->faces, oppositeFace); !why.empty())
    return Fail(error, prefix + "mesh: " + source + ": " + why);
  m->bending = d.bending;
  if (m->bending == ShellBendingModel::Hinge) {
    for (size_t f = 0; f < m->faces.size(); ++f)
      for (int i = 0; i < 3; ++i) {
        const int u = m->faces[f][(i + 1) % 3], v = m->faces[f][(i + 2) % 3];
        if (m->opposite[f][i] < 0 || u > v) continue;  // each interior edge once
        ShellHinge h;
        h.node[0] = u;
        h.node[1] = v;
        h.node[2] = m->faces[f][i];
        h.node[3] = m->opposite[f][i];
        const double areas = m->triangles[f].restArea + m->triangles[oppositeFace[f][i]].restArea;
        h.stiffness = HingeStiffness((X[v] - X[u]).norm(), areas, m->plateStiffness);
        h.restAngle = HingeAngle(HingeNodes(X, h), 0, nullptr, nullptr);
        m->hinges.push_back(h);
      }
  } else {
    for (size_t f = 0; f < m->faces.size(); ++f) {
      const Eigen::Vector3i& F = m->faces[f];
      bool held[3];
      for (int i = 0; i < 3; ++i) held[i] = clamped[F[(i + 1) % 3]] && clamped[F[(i + 2) % 3]];
      m->bendingTriangles.push_back(MakeMidedgeTriangle(MidedgeNodes(X, F, m->opposite[f]),
                                                        Has(m->opposite[f]).data(), held));
    }
  }
  m->freeIndex.assign(n, 0);
  for (const NodeConstraint& k : m->constraints)
    for (int i : k.nodes) m->freeIndex[i] = -1;
  int free = 0;
  for (int& i : m->freeIndex)
    if (i == 0) i = free++;
  state->x.resize(3 * n);
  state->v.resize(3 * n);
  for (int i = 0; i < n; ++i) {
    state->x.segment<3>(3 * i) = X[i];
    state->v.segment<3>(3 * i) = d.linearVelocity;
  }
  for (int i = 0; i < n; ++i)  // a prescribed node's velocity is its path's (from the steps)
    if (m->freeIndex[i] < 0) state->v.segment<3>(3 * i).setZero();
  return true;
}

}  // namespace superdex
