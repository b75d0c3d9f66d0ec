#include "core/model/rigid_body.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <tuple>
#include <limits>
#include <sstream>

#include "core/model/rigid_math.h"
#include "geometry/quadrature.h"

namespace superdex {
namespace {

bool IsFinite(const Eigen::MatrixXd& m) { return m.allFinite(); }

std::string Num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

constexpr EnumName<RigidShapeKind> kShapeKinds[] = {{RigidShapeKind::Sphere, "sphere"},
                                                    {RigidShapeKind::Box, "box"},
                                                    {RigidShapeKind::Capsule, "capsule"},
                                                    {RigidShapeKind::Mesh, "mesh"},
                                                    {RigidShapeKind::Plane, "plane"}};

// Samples on the exact sphere: flat icosphere quadrature points projected radially, weights scaled
// by the area ratio of the central projection, dA_sphere = r² cos(angle)/|X_flat|² dA_flat.
void SphereSamples(double r, int subdivisions, const TriangleQuadratureRule& rule,
                   std::vector<SurfaceSample>* out) {
  const TriangleMesh mesh = MakeIcosphere(r, subdivisions);
  for (int f = 0; f < mesh.NumFaces(); ++f) {
    const Eigen::Vector3i& t = mesh.faces[f];
    const double area = mesh.FaceArea(f);
    const Eigen::Vector3d nf = mesh.FaceNormal(f);
    for (size_t q = 0; q < rule.weights.size(); ++q) {
      const Eigen::Vector3d& b = rule.barycentric[q];
      const Eigen::Vector3d xf =
          b[0] * mesh.vertices[t[0]] + b[1] * mesh.vertices[t[1]] + b[2] * mesh.vertices[t[2]];
      const double len = xf.norm();
      const Eigen::Vector3d n = xf / len;
      const double jac = r * r / (len * len) * n.dot(nf);
      out->push_back({r * n, n, area * rule.weights[q] * jac});
    }
  }
}

// A capsule's triangulation (MakeCapsuleMesh): `surfaceResolution` rings per cap, six times that
// around, side rows at about the around spacing.
TriangleMesh CapsuleMesh(const RigidShape& s) {
  const int around = 6 * s.surfaceResolution;
  const double spacing = 2.0 * M_PI * s.radius / around;
  const int rows = std::clamp(static_cast<int>(std::ceil(2.0 * s.halfLength / spacing)), 1, 1000);
  return MakeCapsuleMesh(s.radius, s.halfLength, around, s.surfaceResolution, rows);
}

// Samples on a capsule: each quadrature point of its triangulation projected onto the capsule
// from the closest point c of its axis segment, X = c + r n, with the projection's area scale,
// (r/ρ) (n·n_f) beside the straight part (one direction stretched) and (r/ρ)² (n·n_f) on the
// caps, ρ = |x_f − c| (as a sphere's samples).
void CapsuleSamples(const RigidShape& shape, const TriangleQuadratureRule& rule,
                    std::vector<SurfaceSample>* out) {
  const double r = shape.radius, h = shape.halfLength;
  const TriangleMesh mesh = CapsuleMesh(shape);
  for (int f = 0; f < mesh.NumFaces(); ++f) {
    const Eigen::Vector3i& t = mesh.faces[f];
    const double area = mesh.FaceArea(f);
    const Eigen::Vector3d nf = mesh.FaceNormal(f);
    // A face lies beside the straight part or on a cap as a whole (rings at z = ±h).
    const Eigen::Vector3d centroid =
        (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0;
    const bool side = std::abs(centroid.z()) < h;
    for (size_t q = 0; q < rule.weights.size(); ++q) {
      const Eigen::Vector3d& b = rule.barycentric[q];
      const Eigen::Vector3d xf =
          b[0] * mesh.vertices[t[0]] + b[1] * mesh.vertices[t[1]] + b[2] * mesh.vertices[t[2]];
      const Eigen::Vector3d c(0.0, 0.0, side ? xf.z() : std::copysign(h, centroid.z()));
      const double rho = (xf - c).norm();
      const Eigen::Vector3d n = (xf - c) / rho;
      const double jac = (side ? r / rho : r * r / (rho * rho)) * n.dot(nf);
      out->push_back({c + r * n, n, area * rule.weights[q] * jac});
    }
  }
}

void MeshSamples(const TriangleMesh& mesh, const Eigen::Vector3d& offset,
                 const TriangleQuadratureRule& rule, std::vector<SurfaceSample>* out) {
  for (int f = 0; f < mesh.NumFaces(); ++f) {
    const Eigen::Vector3i& t = mesh.faces[f];
    const double area = mesh.FaceArea(f);
    if (!(area > 0.0)) continue;
    const Eigen::Vector3d nf = mesh.FaceNormal(f);
    for (size_t q = 0; q < rule.weights.size(); ++q) {
      const Eigen::Vector3d& b = rule.barycentric[q];
      const Eigen::Vector3d x =
          b[0] * mesh.vertices[t[0]] + b[1] * mesh.vertices[t[1]] + b[2] * mesh.vertices[t[2]];
      out->push_back({x - offset, nf, area * rule.weights[q]});
    }
  }
}

// Builds the sample tree of `samples`: median splits of the sample range along the longest side
// of its box (ties by original index, so the tree is deterministic), leaves of at most
// kSamplesPerLeaf; samples reordered into leaf order. Each node's sphere is centred on its box.
std::vector<SampleNode> BuildSampleTree(std::vector<SurfaceSample>* samples) {
  std::vector<SampleNode> tree;
  const int n = static_cast<int>(samples->size());
  if (n == 0) return tree;
  const std::vector<SurfaceSample>& s = *samples;
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  auto bound = [&](SampleNode* node) {
    Aabb box;
    for (int k = node->begin; k < node->end; ++k) box.Extend(s[order[k]].X);
    node->center = 0.5 * (box.min + box.max);
    node->radius = 0.0;
    for (int k = node->begin; k < node->end; ++k)
      node->radius = std::max(node->radius, (s[order[k]].X - node->center).norm());
    return box;
  };
  tree.reserve(2 * (n / kSamplesPerLeaf + 1));
  std::vector<int> pending = {0};
  tree.push_back({0, n});
  while (!pending.empty()) {
    const int index = pending.back();
    pending.pop_back();
    const Aabb box = bound(&tree[index]);
    const SampleNode node = tree[index];
    if (node.end - node.begin <= kSamplesPerLeaf) continue;
    int axis = 0;
    (box.max - box.min).maxCoeff(&axis);
    const int mid = (node.begin + node.end) / 2;
    std::nth_element(order.begin() + node.begin, order.begin() + mid, order.begin() + node.end,
                     [&](int a, int b) {
                       const double xa = s[a].X[axis], xb = s[b].X[axis];
                       return xa < xb || (xa == xb && a < b);
                     });
    const int left = static_cast<int>(tree.size());
    tree.push_back({node.begin, mid});
    tree.push_back({mid, node.end});
    tree[index].left = left;
    tree[index].right = left + 1;
    pending.push_back(left + 1);
    pending.push_back(left);
  }
  std::vector<SurfaceSample> sorted(n);
  for (int k = 0; k < n; ++k) sorted[k] = s[order[k]];
  *samples = std::move(sorted);
  return tree;
}

bool SameSample(const SurfaceSample& a, const SurfaceSample& b) {
  return a.X == b.X && a.normal == b.normal && a.weight == b.weight;
}

bool SameNode(const SampleNode& a, const SampleNode& b) {
  return a.begin == b.begin && a.end == b.end && a.left == b.left && a.right == b.right &&
         a.center == b.center && a.radius == b.radius;
}

}  // namespace

EnumNames<RigidShapeKind> NamesOf(RigidShapeKind) { return kShapeKinds; }

SdfSample RigidCollider::Evaluate(const Eigen::Vector3d& X) const {
  switch (type) {
    case ColliderType::Sphere: return sphere.Evaluate(X);
    case ColliderType::Box: return box.Evaluate(X);
    case ColliderType::Capsule: return capsule.Evaluate(X);
    case ColliderType::Plane: return plane.Evaluate(X);
    case ColliderType::Mesh: return mesh->Evaluate(X);
    case ColliderType::Sdf: return grid->Evaluate(X);
    default: {
      SdfSample s;
      s.value = std::numeric_limits<double>::infinity();
      return s;
    }
  }
}

double RigidCollider::Value(const Eigen::Vector3d& X) const {
  switch (type) {
    case ColliderType::Sphere: return sphere.Value(X);
    case ColliderType::Box: return box.Value(X);
    case ColliderType::Capsule: return capsule.Value(X);
    case ColliderType::Plane: return plane.Value(X);
    default: return Evaluate(X).value;
  }
}

bool RigidCollider::EvaluateBelow(const Eigen::Vector3d& X, double bound, SdfSample* s) const {
  switch (type) {
    case ColliderType::Sphere: return sphere.EvaluateBelow(X, bound, s);
    case ColliderType::Box: return box.EvaluateBelow(X, bound, s);
    case ColliderType::Capsule: return capsule.EvaluateBelow(X, bound, s);
    case ColliderType::Plane: return plane.EvaluateBelow(X, bound, s);
    default:  // mesh and grid fields evaluate in full
      *s = Evaluate(X);
      return !(s->value >= bound);
  }
}

double RigidCollider::FirstOrderLowerBound(const Eigen::Vector3d& C, double r,
                                           const Eigen::Vector3d& D) const {
  if (type == ColliderType::Plane) return plane.Value(C + D) - r;
  const double c = C.norm();
  if (type == ColliderType::Sphere && c > r) {
    // |X| >= |C| − r and X̂·D >= Ĉ·D − |X̂ − Ĉ||D|, the chord |X̂ − Ĉ| at most that of the
    // ball's half-angle asin(r/|C|) seen from the centre: 2 sin(θ/2) = √(2 − 2√(1 − (r/|C|)²)).
    const double x = r / c;
    const double chord = std::sqrt(std::max(0.0, 2.0 - 2.0 * std::sqrt(1.0 - x * x)));
    return c - r - sphere.radius + C.dot(D) / c - chord * D.norm();
  }
  return Value(C) - lipschitz * (r + D.norm());
}

Eigen::Vector3d RigidBodyState::AngularVelocity() const { return Axial(Rdot * R.transpose()); }

namespace {

// The shape's validation and mass properties (mass, second moment J about the centre of mass,
// the centre's offset in the shape frame, local bounds) into *m.
bool BuildMassProperties(const RigidActorDesc& d, const std::string& prefix, RigidBodyModel* m,
                         Error* error) {
  const RigidShape& shape = d.shape;
  // Shape, mass properties in the shape frame.
  double mass = 0.0;
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  const double rho = d.density;
  if (d.dynamic && !d.mass && !(std::isfinite(rho) && rho > 0))
    return Fail(error, prefix + "density: must be > 0, got " + Num(rho));
  switch (shape.kind) {
    case RigidShapeKind::Sphere: {
      const double r = shape.radius;
      if (!(std::isfinite(r) && r > 0)) return Fail(error, prefix + "shape.radius: must be > 0, got " + Num(r));
      if (shape.surfaceResolution < 0 || shape.surfaceResolution > 7)
        return Fail(error, prefix + "shape.surface_resolution: sphere subdivisions must be in [0, 7], got " +
                               Num(shape.surfaceResolution));
      mass = rho * 4.0 / 3.0 * M_PI * r * r * r;
      m->volume = 4.0 / 3.0 * M_PI * r * r * r;
      J = Eigen::Matrix3d::Identity() * (mass * r * r / 5.0);
      m->localBounds.Extend(Eigen::Vector3d::Constant(-r));
      m->localBounds.Extend(Eigen::Vector3d::Constant(r));
      break;
    }
    case RigidShapeKind::Box: {
      const Eigen::Vector3d& h = shape.halfExtents;
      if (!(h.allFinite() && h.minCoeff() > 0))
        return Fail(error, prefix + "shape.half_extents: must be > 0");
      if (shape.surfaceResolution < 1 || shape.surfaceResolution > 64)
        return Fail(error, prefix + "shape.surface_resolution: box divisions must be in [1, 64], got " +
                               Num(shape.surfaceResolution));
      mass = rho * 8.0 * h.prod();
      m->volume = 8.0 * h.prod();
      J = (mass / 3.0) * h.cwiseProduct(h).asDiagonal();
      m->localBounds.Extend(-h);
      m->localBounds.Extend(h);
      break;
    }
    case RigidShapeKind::Capsule: {
      const double r = shape.radius, h = shape.halfLength;
      if (!(std::isfinite(r) && r > 0)) return Fail(error, prefix + "shape.radius: must be > 0, got " + Num(r));
      if (!(std::isfinite(h) && h > 0))
        return Fail(error, prefix + "shape.half_length: must be > 0, got " + Num(h));
      if (shape.surfaceResolution < 1 || shape.surfaceResolution > 32)
        return Fail(error, prefix + "shape.surface_resolution: capsule cap rings must be in [1, 32], got " +
                               Num(shape.surfaceResolution));
      // The straight part (a cylinder) and the two caps (a sphere split at its equator, its
      // halves moved to ±h): J = diag(a, a, b) with
      //   a = m_c r²/4 + m_s r²/5,   b = m_c h²/3 + m_s (h² + 3 h r/4 + r²/5).
      const double vc = M_PI * r * r * 2.0 * h, vs = 4.0 / 3.0 * M_PI * r * r * r;
      m->volume = vc + vs;
      mass = rho * m->volume;
      const double mc = rho * vc, ms = rho * vs;
      const double a = mc * r * r / 4.0 + ms * r * r / 5.0;
      const double b = mc * h * h / 3.0 + ms * (h * h + 0.75 * h * r + r * r / 5.0);
      J = Eigen::Vector3d(a, a, b).asDiagonal();
      m->localBounds.Extend(-Eigen::Vector3d(r, r, h + r));
      m->localBounds.Extend(Eigen::Vector3d(r, r, h + r));
      break;
    }
    case RigidShapeKind::Mesh: {
      if (!shape.mesh || shape.mesh->NumFaces() == 0)
        return Fail(error, prefix + "shape.mesh: must have at least one face");
      const MassProperties mp = ComputeMassProperties(*shape.mesh, d.dynamic ? rho : 1.0);
      if (d.dynamic && !(mp.volume > 0))
        return Fail(error, prefix + "shape.mesh: encloses no positive volume (not closed or "
                                    "inward-oriented), got volume " + Num(mp.volume));
      mass = mp.mass;
      m->volume = mp.volume;
      J = mp.secondMoment;
      com = mp.volume > 0 ? mp.centerOfMass : Eigen::Vector3d::Zero();
      for (const auto& v : shape.mesh->vertices) m->localBounds.Extend(v - com);
      break;
    }
    case RigidShapeKind::Plane: {
      if (d.dynamic) return Fail(error, prefix + "shape: a plane can only be a static actor");
      if (!(shape.planeNormal.allFinite() && shape.planeNormal.norm() > 1e-12))
        return Fail(error, prefix + "shape.normal: must be a non-zero vector");
      m->shape.planeNormal.normalize();
      m->localBounds = Aabb::Everything();
      break;
    }
  }
  if (d.dynamic) {
    if (d.mass) {
      if (!(std::isfinite(*d.mass) && *d.mass > 0))
        return Fail(error, prefix + "mass: must be > 0, got " + Num(*d.mass));
      J *= *d.mass / mass;
      mass = *d.mass;
    }
    if (d.inertia) {
      const Eigen::Matrix3d& I = *d.inertia;
      if (!I.allFinite() || (I - I.transpose()).norm() > 1e-9 * I.norm())
        return Fail(error, prefix + "inertia: must be a finite symmetric matrix");
      const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
      if (ev.minCoeff() <= 0 || ev[2] > ev[0] + ev[1] * (1 + 1e-12))
        return Fail(error, prefix + "inertia: principal moments must be > 0 and satisfy the "
                                    "triangle inequality");
      J = 0.5 * I.trace() * Eigen::Matrix3d::Identity() - I;
    }
    if (!(std::isfinite(mass) && mass > 0 && J.allFinite()))
      return Fail(error, prefix + "shape: its mass properties are not representable in double "
                                  "precision (mass " + Num(mass) + " kg, second moment trace " +
                                  Num(J.trace()) + " kg m^2): the shape is too small or too large");
    m->mass = mass;
    m->secondMoment = J;
  }
  m->shapeOffset = com;
  return true;

}

// The collider role (spec: "Collider Representations"): the resolved collider type and its field.
bool BuildColliderRole(const RigidActorDesc& d, const std::string& prefix, RigidBodyModel* m,
                       Error* error) {
  const RigidShape& shape = d.shape;
  const Eigen::Vector3d com = m->shapeOffset;
  // Collider role.
  RigidCollider& c = m->collider;
  ColliderType want = d.colliderType;
  const char* shapeName = ToString(shape.kind);
  if (want == ColliderType::Auto) {
    switch (shape.kind) {
      case RigidShapeKind::Sphere: want = ColliderType::Sphere; break;
      case RigidShapeKind::Box: want = ColliderType::Box; break;
      case RigidShapeKind::Capsule: want = ColliderType::Capsule; break;
      case RigidShapeKind::Plane: want = ColliderType::Plane; break;
      case RigidShapeKind::Mesh: want = ColliderType::Sdf; break;  // spec: Sdf for rigid meshes
    }
  }
  if (want == ColliderType::PointCloud)
    return Fail(error, prefix + "collider_type: PointCloud is not available for rigid bodies "
                                "(a point cloud is a shell's collider; expected Auto, None, "
                                "Sphere, Box, Plane, Capsule, Mesh or Sdf)");
  const bool analytic = want == ColliderType::Sphere || want == ColliderType::Box ||
                        want == ColliderType::Plane || want == ColliderType::Capsule;
  const bool match = want == ColliderType::None || !analytic ||
                     (want == ColliderType::Sphere && shape.kind == RigidShapeKind::Sphere) ||
                     (want == ColliderType::Box && shape.kind == RigidShapeKind::Box) ||
                     (want == ColliderType::Capsule && shape.kind == RigidShapeKind::Capsule) ||
                     (want == ColliderType::Plane && shape.kind == RigidShapeKind::Plane);
  if (!match)
    return Fail(error, prefix + "collider_type: " + ToString(want) + " needs a " +
                           (want == ColliderType::Sphere    ? "sphere"
                            : want == ColliderType::Box     ? "box"
                            : want == ColliderType::Capsule ? "capsule"
                                                            : "plane") +
                           " shape, got " + shapeName);
  if ((want == ColliderType::Mesh || want == ColliderType::Sdf) &&
      shape.kind == RigidShapeKind::Plane)
    return Fail(error, prefix + "collider_type: " + ToString(want) +
                           " needs a closed shape, got plane");
  c.type = want;
  c.sphere.radius = shape.radius;
  c.box.halfExtents = shape.halfExtents;
  c.capsule.radius = shape.radius;
  c.capsule.halfLength = shape.halfLength;
  c.plane.normal = m->shape.planeNormal;
  c.plane.offset = 0.0;
  c.boundingRadius = shape.kind == RigidShapeKind::Plane
                         ? std::numeric_limits<double>::infinity()
                         : std::max(m->localBounds.min.norm(), m->localBounds.max.norm());
  if (shape.kind == RigidShapeKind::Sphere) c.boundingRadius = shape.radius;
  if (want == ColliderType::Mesh || want == ColliderType::Sdf) {
    // The shape's closed mesh in the body frame (origin at the centre of mass).
    TriangleMesh mesh = shape.kind == RigidShapeKind::Mesh ? *shape.mesh
                        : shape.kind == RigidShapeKind::Sphere
                            ? MakeIcosphere(shape.radius, shape.surfaceResolution)
                        : shape.kind == RigidShapeKind::Capsule
                            ? CapsuleMesh(shape)
                            : MakeBoxMesh(shape.halfExtents, shape.surfaceResolution);
    for (Eigen::Vector3d& x : mesh.vertices) x -= com;
    std::string why;
    auto exact = MeshSdf::Build(mesh, &why);
    if (!exact)
      return Fail(error, prefix + "shape." + why +
                             (shape.meshSource.empty() ? "" : " in " + shape.meshSource) +
                             "; collider_type " + ToString(want) + " needs a closed, outward "
                             "oriented mesh (or collider_type None)");
    c.boundingRadius = exact->BoundingRadius();
    if (want == ColliderType::Mesh) {
      c.mesh = exact;
    } else {
      if (std::string m2 = Validate(d.gridSdf, prefix + "grid_sdf."); !m2.empty())
        return Fail(error, m2);
      std::function<double(const Eigen::Vector3d&)> phi;
      if (shape.kind == RigidShapeKind::Sphere) {
        const SphereSdf sp{shape.radius};
        phi = [sp](const Eigen::Vector3d& X) { return sp.Evaluate(X).value; };
      } else if (shape.kind == RigidShapeKind::Box) {
        const BoxSdf bx{shape.halfExtents};
        phi = [bx](const Eigen::Vector3d& X) { return bx.Evaluate(X).value; };
      } else if (shape.kind == RigidShapeKind::Capsule) {
        const CapsuleSdf cp{shape.radius, shape.halfLength};
        phi = [cp](const Eigen::Vector3d& X) { return cp.Value(X); };
      } else {
        phi = [exact](const Eigen::Vector3d& X) { return exact->Value(X); };
      }
      std::string why2;
      c.grid = BuildGridSdf(mesh, phi, d.gridSdf, &why2);
      if (!c.grid) return Fail(error, prefix + "grid_sdf: " + why2);
      const Eigen::Vector3i nodes = c.grid->Nodes();
      const double h = c.grid->Spacing();
      c.lipschitz = std::sqrt(3.0);
      std::ostringstream note;
      note << "actor '" << d.name << "': grid SDF " << nodes.x() << " x " << nodes.y() << " x "
           << nodes.z() << " nodes, voxel " << h << " m, " << c.grid->MemoryBytes() / 1048576.0
           << " MiB";
      m->notice = note.str();
    }
  }
  return true;
}

// The rules of the kinematic and applied-load fields.
bool CheckMotion(const RigidActorDesc& d, const std::string& prefix, Error* error) {
  if (d.kinematic && d.dynamic)
    return Fail(error, prefix + "kinematic: a kinematic actor is not dynamic (dynamic must be "
                                "false)");
  if (!d.path.empty() && !d.kinematic)
    return Fail(error, prefix + "path: only a kinematic actor follows a path");
  for (size_t j = 0; j < d.path.size(); ++j) {
    const PoseKeyframe& k = d.path[j];
    const std::string field = prefix + "path[" + std::to_string(j) + "]";
    if (!std::isfinite(k.t) || !k.position.allFinite())
      return Fail(error, field + ": t and position must be finite");
    if (!(k.orientation.coeffs().allFinite() && k.orientation.norm() > 1e-12))
      return Fail(error, field + ".orientation: must be a non-zero finite quaternion");
    if (j > 0 && !(k.t > d.path[j - 1].t))
      return Fail(error, field + ".t: keyframe times must increase");
  }
  for (const auto& [keys, name] : {std::pair{&d.appliedForce, "applied_force"},
                                   std::pair{&d.appliedTorque, "applied_torque"}}) {
    if (keys->empty()) continue;
    if (!d.dynamic)
      return Fail(error, prefix + name + ": only a dynamic actor takes applied loads");
    if (std::string msg = CheckKeyframes(*keys, prefix + name); !msg.empty())
      return Fail(error, msg);
  }
  return true;
}

}  // namespace

bool BuildRigidBody(const RigidActorDesc& d, const std::string& prefix, RigidBodyModel* m,
                    RigidBodyState* st, Error* error) {
  const RigidShape& shape = d.shape;
  *m = RigidBodyModel();
  m->name = d.name;
  m->dynamic = d.dynamic;
  m->shape = shape;
  m->contact = d.contact;
  m->requestedCollider = d.colliderType;
  m->boundaryElementType = d.boundaryElementType;
  m->surfaceIntegral = d.surfaceIntegral;
  m->contactLayer = d.contactLayer;
  if (d.surfaceIntegral == SurfaceIntegral::ExactSphere && shape.kind != RigidShapeKind::Sphere)
    return Fail(error, prefix + "surface_integral: ExactSphere needs a sphere shape, got " +
                           ToString(shape.kind));

  if (std::string msg = Validate(d.contact, prefix + "contact."); !msg.empty())
    return Fail(error, msg);
  if (!IsFinite(d.position) || !IsFinite(d.linearVelocity) || !IsFinite(d.angularVelocity))
    return Fail(error, prefix + "position/velocity: must be finite");
  if (!(d.orientation.coeffs().allFinite() && d.orientation.norm() > 1e-12))
    return Fail(error, prefix + "orientation: must be a non-zero finite quaternion");

  if (!CheckMotion(d, prefix, error)) return false;

  if (!BuildMassProperties(d, prefix, m, error) || !BuildColliderRole(d, prefix, m, error))
    return false;
  const Eigen::Vector3d com = m->shapeOffset;

  // Colliding role: dynamic rigid actors only (spec: "Default Roles by Actor Type"), and the
  // kinematic ones, which collide as dynamic actors do.
  std::vector<SurfaceSample> samples;
  if (d.dynamic || d.kinematic) {
    const TriangleQuadratureRule& rule = GetTriangleQuadratureRule(d.boundaryElementType);
    switch (shape.kind) {
      case RigidShapeKind::Sphere:
        SphereSamples(shape.radius, shape.surfaceResolution, rule, &samples);
        break;
      case RigidShapeKind::Box:
        MeshSamples(MakeBoxMesh(shape.halfExtents, shape.surfaceResolution),
                    Eigen::Vector3d::Zero(), rule, &samples);
        break;
      case RigidShapeKind::Capsule: CapsuleSamples(shape, rule, &samples); break;
      case RigidShapeKind::Mesh: MeshSamples(*shape.mesh, com, rule, &samples); break;
      case RigidShapeKind::Plane: break;
    }
  }

  for (const SurfaceSample& s : samples) m->samplesRadius = std::max(m->samplesRadius, s.X.norm());
  std::vector<SampleNode> tree = BuildSampleTree(&samples);
  m->samples = SharedArray<SurfaceSample>(std::move(samples));
  m->sampleTree = SharedArray<SampleNode>(std::move(tree));

  if (d.dynamic) {
    m->appliedForce = d.appliedForce;
    m->appliedTorque = d.appliedTorque;
  }
  if (d.kinematic) {
    m->kinematic = true;
    m->path = d.path;
    for (PoseKeyframe& k : m->path) k.orientation.normalize();
    m->R0 = d.orientation.normalized().toRotationMatrix();
    m->p0 = d.position + m->R0 * com;
    m->v0 = d.linearVelocity;
    m->omega0 = d.angularVelocity;
  }
  *st = InitialRigidState(d, *m);
  return true;
}

RigidBodyState InitialRigidState(const RigidActorDesc& d, const RigidBodyModel& m) {
  if (m.kinematic) return KinematicStateAt(m, 0.0);
  RigidBodyState s;
  s.R = d.orientation.normalized().toRotationMatrix();
  s.p = d.position + s.R * m.shapeOffset;
  if (d.dynamic) {
    s.v = d.linearVelocity;
    s.Rdot = Skew(d.angularVelocity) * s.R;
  }
  return s;
}

RigidBodyState KinematicStateAt(const RigidBodyModel& m, double t) {
  RigidBodyState s;
  if (m.path.empty()) {
    s.p = m.p0 + t * m.v0;
    s.R = ExpSo3(t * m.omega0) * m.R0;
    s.v = m.v0;
    s.Rdot = Skew(m.omega0) * s.R;
    return s;
  }
  // The shape frame's origin o(t) and rotation on the segment [k − 1, k] holding t; the centre of
  // mass is o + R c, moving at ȯ + ω × R c.
  const std::vector<PoseKeyframe>& path = m.path;
  Eigen::Vector3d o = path.back().position, oDot = Eigen::Vector3d::Zero();
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
  s.R = path.back().orientation.toRotationMatrix();
  if (t <= path.front().t) {
    o = path.front().position;
    s.R = path.front().orientation.toRotationMatrix();
  } else {
    for (size_t k = 1; k < path.size(); ++k) {
      if (t > path[k].t) continue;
      const double span = path[k].t - path[k - 1].t, u = (t - path[k - 1].t) / span;
      const Eigen::Matrix3d Ra = path[k - 1].orientation.toRotationMatrix();
      const Eigen::Vector3d turn = LogSo3(path[k].orientation.toRotationMatrix() * Ra.transpose());
      oDot = (path[k].position - path[k - 1].position) / span;
      o = path[k - 1].position + (t - path[k - 1].t) * oDot;
      omega = turn / span;
      s.R = ExpSo3(u * turn) * Ra;
      break;
    }
  }
  const Eigen::Vector3d arm = s.R * m.shapeOffset;
  s.p = o + arm;
  s.v = oDot + omega.cross(arm);
  s.Rdot = Skew(omega) * s.R;
  return s;
}

bool ShareSamples(const RigidBodyModel& other, RigidBodyModel* m) {
  if (!SameElements(other.samples, m->samples, SameSample) ||
      !SameElements(other.sampleTree, m->sampleTree, SameNode))
    return false;
  m->samples = other.samples;
  m->sampleTree = other.sampleTree;
  return true;
}

std::size_t SamplesHash(const RigidBodyModel& m) {
  // FNV-1a over the bit patterns of the samples' coordinates, normals and weights, a 64-bit word
  // at a time (equal sets hash equal; ShareSamples compares the elements themselves).
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    h ^= bits;
    h *= 1099511628211ull;
  };
  mix(static_cast<double>(m.samples.size()));
  for (const SurfaceSample& s : m.samples) {
    for (int i = 0; i < 3; ++i) mix(s.X[i]);
    for (int i = 0; i < 3; ++i) mix(s.normal[i]);
    mix(s.weight);
  }
  return static_cast<std::size_t>(h);
}

double KineticEnergy(const RigidBodyModel& m, const RigidBodyState& s) {
  return 0.5 * m.mass * s.v.squaredNorm() + 0.5 * (s.Rdot * m.secondMoment * s.Rdot.transpose()).trace();
}

Eigen::Vector3d LinearMomentum(const RigidBodyModel& m, const RigidBodyState& s) {
  return m.mass * s.v;
}

Eigen::Vector3d SpinMomentum(const Eigen::Matrix3d& R, const Eigen::Matrix3d& Rdot,
                             const Eigen::Matrix3d& J) {
  return Axial(Rdot * J * R.transpose() - R * J * Rdot.transpose());
}

double RmsRadius(const RigidBodyModel& model) {
  return model.mass > 0.0 ? std::sqrt(model.secondMoment.trace() / model.mass) : 0.0;
}

Eigen::Matrix3d WorldInertia(const Eigen::Matrix3d& R, const Eigen::Matrix3d& J) {
  return R * (J.trace() * Eigen::Matrix3d::Identity() - J) * R.transpose();
}

Eigen::Vector3d AngularMomentum(const RigidBodyModel& m, const RigidBodyState& s) {
  return m.mass * s.p.cross(s.v) + SpinMomentum(s.R, s.Rdot, m.secondMoment);
}

namespace {
// The box of a plane's half-space Φ = w·(x − p) <= 0 (w = R n, the world normal): bounded by the
// face x_i = p_i when w is parallel to axis i (its other components exactly zero), else all of
// space. The face is moved outward by a round-off margin of Φ's evaluation, so that no point with
// Φ <= 0 as the field computes it lies outside.
Aabb HalfSpaceBounds(const Eigen::Vector3d& p, const Eigen::Vector3d& w) {
  Aabb b = Aabb::Everything();
  int axis = -1;
  for (int i = 0; i < 3; ++i) {
    if (w[i] == 0.0) continue;
    if (axis >= 0) return b;  // oblique: the half-space's box is everything
    axis = i;
  }
  if (axis < 0) return b;
  const double margin = 1e-12 * (1.0 + std::abs(p[axis]));
  if (w[axis] > 0.0)
    b.max[axis] = p[axis] + margin;
  else
    b.min[axis] = p[axis] - margin;
  return b;
}
}  // namespace

Aabb WorldBounds(const RigidBodyModel& m, const Eigen::Vector3d& p, const Eigen::Matrix3d& R) {
  if (m.shape.kind == RigidShapeKind::Plane)
    return HalfSpaceBounds(p, R * m.shape.planeNormal);
  Aabb b;
  if (m.shape.kind == RigidShapeKind::Sphere) {
    b.Extend(p);
    b.Inflate(m.shape.radius);
    return b;
  }
  const Eigen::Vector3d c = 0.5 * (m.localBounds.min + m.localBounds.max);
  const Eigen::Vector3d h = 0.5 * (m.localBounds.max - m.localBounds.min);
  const Eigen::Vector3d wc = p + R * c;
  const Eigen::Vector3d wh = R.cwiseAbs() * h;
  b.min = wc - wh;
  b.max = wc + wh;
  return b;
}

}  // namespace superdex
