#include "core/model/shell_kind.h"

#include <iterator>

namespace superdex {
namespace {

Eigen::Vector3d Node(const Eigen::VectorXd& x, int i) { return x.segment<3>(3 * i); }

// Appends the dense block Hl over the nodes `nodes` (3 dofs each) as triplets.
// A node index −1 (a missing neighbour) is skipped.
template <int N>
void AppendBlock(const Eigen::Matrix<double, 3 * N, 3 * N>& Hl, const int (&nodes)[N],
                 std::vector<Eigen::Triplet<double>>* H) {
  for (int a = 0; a < N; ++a)
    for (int b = 0; b < N; ++b)
      if (nodes[a] >= 0 && nodes[b] >= 0)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          H->emplace_back(3 * nodes[a] + i, 3 * nodes[b] + j, Hl(3 * a + i, 3 * b + j));
}

// A shell's working memory for one stage (KindStageData::scratch): the elements' damping
// stiffnesses K_e at the predictor (ShellKind::ElasticTerms' element order).
struct ShellStageScratch : KindScratch {
  std::vector<Eigen::MatrixXd> damping;
  bool prepared = false;
};

// The nodes of element k in ElasticTerms' order (membrane triangles, then bending triangles or
// hinges) into nodes (−1: a missing neighbour); returns their count.
int ElementNodes(const ShellModel& m, size_t k, int nodes[6]) {
  if (k < m.faces.size()) {
    for (int a = 0; a < 3; ++a) nodes[a] = m.faces[k][a];
    return 3;
  }
  k -= m.faces.size();
  if (k < m.bendingTriangles.size()) {
    for (int a = 0; a < 3; ++a) {
      nodes[a] = m.faces[k][a];
      nodes[3 + a] = m.opposite[k][a];
    }
    return 6;
  }
  k -= m.bendingTriangles.size();
  for (int a = 0; a < 4; ++a) nodes[a] = m.hinges[k].node[a];
  return 4;
}

}  // namespace

ShellKind::ShellKind(ShellModel model, const VectorState& initial)
    : model_(std::move(model)), rest_(initial) {
  name = model_.name;
}

std::unique_ptr<ShellKind> ShellKind::Build(const ShellActorDesc& desc, Error* error) {
  ShellModel model;
  VectorState state;
  if (!BuildShell(desc, "", &model, &state, error)) return nullptr;
  auto kind = std::make_unique<ShellKind>(std::move(model), state);
  kind->contact = desc.contact;
  return kind;
}

std::unique_ptr<ActorKind> ShellKind::Clone() const { return std::make_unique<ShellKind>(*this); }

KindState ShellKind::InitialState() const {
  KindState s = rest_;
  Prescribe(0.0, &s.x);
  return s;
}

void ShellKind::Prescribe(double t, Eigen::VectorXd* q) const {
  ApplyNodeConstraints(model_.constraints, rest_.x, t, q);
}

double ShellKind::ElasticTerms(const Eigen::VectorXd& x, int order, bool project,
                               Eigen::VectorXd* g, std::vector<Eigen::Triplet<double>>* H,
                               std::vector<Eigen::MatrixXd>* elementHessians) const {
  const ShellModel& m = model_;
  const double h = m.material.thickness;
  double value = 0.0;
  // An element's gradient and Hessian over `nodes` (−1: none): into g and H, or its Hessian
  // kept (elementHessians).
  auto add = [&](const auto& gl, const auto& Hl, const auto& nodes) {
    if (elementHessians) return elementHessians->push_back(Hl);
    if (order >= 1)
      for (size_t a = 0; a < std::size(nodes); ++a)
        if (nodes[a] >= 0) g->segment<3>(3 * nodes[a]) += gl.template segment<3>(3 * a);
    if (order >= 2) AppendBlock(Hl, nodes, H);
  };
  for (size_t f = 0; f < m.faces.size(); ++f) {
    const int nodes[3] = {m.faces[f][0], m.faces[f][1], m.faces[f][2]};
    Eigen::Matrix<double, 9, 1> xl, gl = Eigen::Matrix<double, 9, 1>::Zero();
    Eigen::Matrix<double, 9, 9> Hl = Eigen::Matrix<double, 9, 9>::Zero();
    for (int a = 0; a < 3; ++a) xl.segment<3>(3 * a) = Node(x, nodes[a]);
    value += MembraneEnergy(xl, m.triangles[f], m.lame, h, order, project, &gl, &Hl);
    add(gl, Hl, nodes);
  }
  for (size_t f = 0; f < m.bendingTriangles.size(); ++f) {  // Midedge
    const Eigen::Vector3i& F = m.faces[f];
    const Eigen::Vector3i& P = m.opposite[f];
    Eigen::Matrix<double, 18, 1> xl = Eigen::Matrix<double, 18, 1>::Zero(),
                                 gl = Eigen::Matrix<double, 18, 1>::Zero();
    Eigen::Matrix<double, 18, 18> Hl = Eigen::Matrix<double, 18, 18>::Zero();
    int nodes[6];
    for (int k = 0; k < 3; ++k) {
      nodes[k] = F[k];
      nodes[3 + k] = P[k];
      xl.segment<3>(3 * k) = Node(x, F[k]);
      if (P[k] >= 0) xl.segment<3>(9 + 3 * k) = Node(x, P[k]);
    }
    value += MidedgeBendingEnergy(xl, m.bendingTriangles[f], m.lame, h, order, project, &gl, &Hl);
    add(gl, Hl, nodes);
  }
  for (const ShellHinge& e : m.hinges) {
    const int nodes[4] = {e.node[0], e.node[1], e.node[2], e.node[3]};
    Eigen::Matrix<double, 12, 1> xl, gl = Eigen::Matrix<double, 12, 1>::Zero();
    Eigen::Matrix<double, 12, 12> Hl = Eigen::Matrix<double, 12, 12>::Zero();
    for (int a = 0; a < 4; ++a) xl.segment<3>(3 * a) = Node(x, nodes[a]);
    value += HingeBendingEnergy(xl, e.stiffness, e.restAngle, order, project, &gl, &Hl);
    add(gl, Hl, nodes);
  }
  return value;
}

void ShellKind::PrepareStage(KindStageData* stage) const {
  ShellStageScratch& s = stage->scratch.Get<ShellStageScratch>();
  s.damping.clear();
  if (model_.material.stiffnessDamping > 0.0)
    ElasticTerms(stage->qHat, 2, true, nullptr, nullptr, &s.damping);
  s.prepared = true;
}

double ShellKind::DampingTerms(const KindStageData& stage, const Eigen::VectorXd& x, int order,
                               Eigen::VectorXd* g, std::vector<Eigen::Triplet<double>>* H) const {
  const double beta = model_.material.stiffnessDamping;
  if (!(beta > 0.0)) return 0.0;
  ShellStageScratch& s = stage.scratch.Get<ShellStageScratch>();
  if (!s.prepared) {  // stage data built by hand
    s.damping.clear();
    ElasticTerms(stage.qHat, 2, true, nullptr, nullptr, &s.damping);
    s.prepared = true;
  }
  const double c = beta / stage.dt;
  double value = 0.0;
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 18, 1> u, f;
  int nodes[6];
  for (size_t k = 0; k < s.damping.size(); ++k) {
    const int n = ElementNodes(model_, k, nodes);
    u.setZero(3 * n);
    for (int a = 0; a < n; ++a)
      if (nodes[a] >= 0) u.segment<3>(3 * a) = x.segment<3>(3 * nodes[a]) - stage.q0.segment<3>(3 * nodes[a]);
    const Eigen::MatrixXd& K = s.damping[k];
    f.noalias() = c * (K * u);
    value += 0.5 * u.dot(f);
    for (int a = 0; a < n && order >= 1; ++a)
      if (nodes[a] >= 0) g->segment<3>(3 * nodes[a]) += f.segment<3>(3 * a);
    if (order < 2) continue;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        if (nodes[a] >= 0 && nodes[b] >= 0)
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              H->emplace_back(3 * nodes[a] + i, 3 * nodes[b] + j, c * K(3 * a + i, 3 * b + j));
  }
  return value;
}

double ShellKind::StageEnergy(const KindStageData& stage, const Eigen::VectorXd& q, int order,
                              PsdProjection projection, Eigen::VectorXd* g,
                              std::vector<Eigen::Triplet<double>>* H) const {
  const ShellModel& m = model_;
  const double dt2 = stage.dt * stage.dt;
  double value = 0.0;
  for (int a = 0; a < m.NumNodes(); ++a) {  // inertia and gravity
    const Eigen::Vector3d u = Node(q, a) - stage.qHat.segment<3>(3 * a);
    value += 0.5 * m.nodeMass[a] / dt2 * u.squaredNorm() - m.nodeMass[a] * stage.gravity.dot(Node(q, a));
    if (order >= 1) g->segment<3>(3 * a) += m.nodeMass[a] * (u / dt2 - stage.gravity);
    if (order >= 2)
      for (int i = 0; i < 3; ++i) H->emplace_back(3 * a + i, 3 * a + i, m.nodeMass[a] / dt2);
  }
  for (const NodeLoad& load : m.loads) {  // dead loads: −f(t)·x
    const Eigen::Vector3d f = PiecewiseLinear(load.force, stage.time);
    for (int a : load.nodes) {
      value -= f.dot(Node(q, a));
      if (order >= 1) g->segment<3>(3 * a) -= f;
    }
  }
  value += DampingTerms(stage, q, order, g, H);
  return value + ElasticTerms(q, order, projection != PsdProjection::None, g, H);
}

double ShellKind::InternalEnergy(const KindState& s) const {
  return ElasticTerms(s.x, 0, false, nullptr, nullptr);
}

KindSample ShellKind::Sample(int k, const Eigen::VectorXd& q) const {
  const ShellSample& ss = model_.samples[k];
  return TriangleSample(model_.faces[ss.face], ss.bary, ss.weight, ss.face, q);
}

KindSample ShellKind::CloudPoint(int j, const Eigen::VectorXd& q) const {
  const ShellCloudPoint& c = model_.cloudPoints[j];
  if (c.face >= 0) return TriangleSample(model_.faces[c.face], c.bary, c.weight, c.face, q);
  KindSample s;
  s.y = Node(q, c.node);
  s.weight = c.weight;
  s.map = SamplePointMap::Point();
  s.dof[0] = 3 * c.node;
  return s;
}

void ShellKind::ForEachSampleNear(
    const Eigen::VectorXd& q, const Eigen::VectorXd& qLast,
    const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&, double)>& keep,
    const std::function<void(int, int)>& visit) const {
  VisitTriangleSamplesNear(model_.faces, model_.faceSampleBegin, q, qLast, keep, visit);
}

}  // namespace superdex
