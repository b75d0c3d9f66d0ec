#include "core/model/node_body_kind.h"

#include <algorithm>

namespace superdex {
namespace {

Eigen::Vector3d Node(const Eigen::VectorXd& x, int i) { return x.segment<3>(3 * i); }

// Σ_a m_a u_a over the nodes (u: their positions [m] or velocities [m/s]).
Eigen::Vector3d NodeMassSum(const Eigen::VectorXd& m, const Eigen::VectorXd& u) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (Eigen::Index a = 0; a < m.size(); ++a) sum += m[a] * Node(u, static_cast<int>(a));
  return sum;
}

}  // namespace

double NodeBodyKind::KineticEnergy(const KindState& s) const {
  double e = 0.0;
  for (int i = 0; i < NumNodes(); ++i) e += 0.5 * NodeMasses()[i] * s.v.segment<3>(3 * i).squaredNorm();
  return e;
}

double NodeBodyKind::GravityEnergy(const KindState& s, const Eigen::Vector3d& gravity) const {
  double e = 0.0;
  for (int a = 0; a < NumNodes(); ++a) e += -NodeMasses()[a] * gravity.dot(Node(s.x, a));
  return e;
}

Eigen::Vector3d NodeBodyKind::LinearMomentum(const KindState& s) const {
  return NodeMassSum(NodeMasses(), s.v);
}

Eigen::Vector3d NodeBodyKind::AngularMomentum(const KindState& s) const {
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (int a = 0; a < NumNodes(); ++a)
    L += NodeMasses()[a] * Node(s.x, a).cross(Node(s.v, a));
  return L;
}

Eigen::Vector3d NodeBodyKind::CenterOfMass(const KindState& s) const {
  return NodeMassSum(NodeMasses(), s.x) / TotalMass();
}

Eigen::Vector3d NodeBodyKind::CenterOfMassVelocity(const KindState& s) const {
  return NodeMassSum(NodeMasses(), s.v) / TotalMass();
}

void NodeBodyKind::DifferenceGroups(const KindState& s,
                                    std::vector<KindDifferenceGroup>* groups) const {
  const int n = static_cast<int>(s.x.size());
  groups->resize(NumNodes());
  for (int a = 0; a < NumNodes(); ++a) {
    KindDifferenceGroup& g = (*groups)[a];
    g = KindDifferenceGroup();
    for (int c = 0; c < 3; ++c) g.directions.push_back({{{3 * a + c, 1.0}}, false, 1.0});
    for (int c = 0; c < 3; ++c) g.directions.push_back({{{n + 3 * a + c, 1.0}}, true, 1.0});
    for (int c = 0; c < 3; ++c) g.entries.push_back(3 * a + c);
    for (int c = 0; c < 3; ++c) g.entries.push_back(n + 3 * a + c);
    if (IsPrescribed(3 * a)) continue;
    for (int c = 0; c < 3; ++c) {
      g.tangentDofs.push_back(3 * a + c);
      g.tangentLength.push_back(1.0);
    }
  }
}

bool NodeBodyKind::MotionParameter(KindMotion motion, int component, const KindState& s,
                                   double* value, Eigen::VectorXd* direction) const {
  if (motion == KindMotion::AngularVelocity || component < 0 || component > 2) return false;
  const Eigen::Index n = s.x.size();
  const bool position = motion == KindMotion::Position;
  const Eigen::VectorXd& u = position ? s.x : s.v;
  double sum = 0.0;
  for (Eigen::Index i = component; i < n; i += 3) sum += u[i];
  *value = sum / static_cast<double>(n / 3);
  direction->setZero(2 * n);
  for (Eigen::Index i = component; i < n; i += 3) (*direction)[(position ? 0 : n) + i] = 1.0;
  return true;
}

Eigen::MatrixXd NodeBodyKind::CenterOfMassJacobian(const KindState& s) const {
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3, s.x.size());
  for (int a = 0; a < NumNodes(); ++a)
    C.middleCols<3>(3 * a).diagonal().setConstant(NodeMasses()[a] / TotalMass());
  return C;
}

KindSample NodeBodyKind::TriangleSample(const Eigen::Vector3i& F, const Eigen::Vector3d& bary,
                                        double weight, int face, const Eigen::VectorXd& q) {
  KindSample s;
  s.map = SamplePointMap::Face(bary);
  s.y.setZero();
  for (int a = 0; a < 3; ++a) {
    s.faceNodes[a] = Node(q, F[a]);
    s.y += bary[a] * s.faceNodes[a];
    s.dof[a] = 3 * F[a];
  }
  s.weight = weight;
  s.face = face;
  return s;
}

void NodeBodyKind::VisitTriangleSamplesNear(
    const std::vector<Eigen::Vector3i>& faces, const std::vector<int>& sampleBegin,
    const Eigen::VectorXd& q, const Eigen::VectorXd& qLast,
    const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&, double)>& keep,
    const std::function<void(int, int)>& visit) {
  for (size_t f = 0; f < faces.size(); ++f) {
    Eigen::Vector3d c, cLast;
    const double r = std::max(TriangleBall(q, faces[f], &c), TriangleBall(qLast, faces[f], &cLast));
    if (keep(c, cLast, r)) visit(sampleBegin[f], sampleBegin[f + 1]);
  }
}

}  // namespace superdex
