#include "core/model/soft_kind.h"

#include <algorithm>

#include "energies/stable_neo_hookean.h"

namespace superdex {
namespace {

Eigen::Vector3d Node(const Eigen::VectorXd& x, int i) { return x.segment<3>(3 * i); }

// Σ_a m_a u_a over the nodes (u: their positions [m] or velocities [m/s]).
Eigen::Vector3d NodeMassSum(const SoftBodyModel& m, const Eigen::VectorXd& u) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int a = 0; a < m.NumNodes(); ++a) sum += m.nodeMass[a] * Node(u, a);
  return sum;
}

// The centroid of face F at positions x and its largest distance to a corner [m].
double FaceBall(const Eigen::VectorXd& x, const Eigen::Vector3i& F, Eigen::Vector3d* c) {
  const Eigen::Vector3d a = Node(x, F[0]), b = Node(x, F[1]), d = Node(x, F[2]);
  *c = (a + b + d) / 3.0;
  return std::max({(a - *c).norm(), (b - *c).norm(), (d - *c).norm()});
}

}  // namespace

SoftKind::SoftKind(SoftBodyModel model, const SoftBodyState& initial)
    : model_(std::move(model)), initial_(initial) {
  contact = model_.contact;
  name = model_.name;
}

std::unique_ptr<SoftKind> SoftKind::Build(const SoftActorDesc& desc, Error* error) {
  SoftBodyModel model;
  SoftBodyState state;
  if (!BuildSoftBody(desc, "", &model, &state, error)) return nullptr;
  return std::make_unique<SoftKind>(std::move(model), state);
}

void SoftKind::SetMaterial(double youngsModulus, double density) {
  const double scale = density / model_.material.density;
  model_.material.youngsModulus = youngsModulus;
  model_.material.density = density;
  model_.lame = LameFromYoungPoisson(youngsModulus, model_.material.poissonRatio);
  model_.nodeMass *= scale;
  model_.mass *= scale;
}

std::unique_ptr<ActorKind> SoftKind::Clone() const { return std::make_unique<SoftKind>(*this); }

namespace {

// A soft body's working memory for one actor's stages (KindStageData::scratch).
struct SoftStageScratch : KindScratch {
  SoftStageTarget target;
  bool prepared = false;
  SoftTermScratch terms;
};

// The stage's target from its data.
void Prepare(const SoftBodyModel& model, const KindStageData& stage, SoftStageScratch* s) {
  s->target.xHat = stage.qHat;
  s->target.x0 = stage.q0;
  s->target.xLast = stage.qLast;
  PrepareSoftDamping(model, &s->target);
  s->prepared = true;
}

}  // namespace

void SoftKind::PrepareStage(KindStageData* stage) const {
  Prepare(model_, *stage, &stage->scratch.Get<SoftStageScratch>());
}

double SoftKind::StageEnergy(const KindStageData& stage, const Eigen::VectorXd& q, int order,
                             PsdProjection projection, Eigen::VectorXd* g,
                             std::vector<Eigen::Triplet<double>>* H) const {
  SoftStageScratch& s = stage.scratch.Get<SoftStageScratch>();
  if (!s.prepared) Prepare(model_, stage, &s);  // stage data built by hand
  // The soft terms on the free nodes, at their local dofs (node a: 3a).
  return EvaluateSoftStageTerms(model_, s.target, stage.dt, stage.gravity, q, order, projection,
                                order >= 1 ? g : nullptr, order >= 2 ? H : nullptr, &s.terms);
}

void SoftKind::Prescribe(double t, Eigen::VectorXd* q) const {
  ApplyNodeConstraints(model_, initial_.x, t, q);
}

double SoftKind::KineticEnergy(const KindState& s) const { return superdex::KineticEnergy(model_, s); }

double SoftKind::GravityEnergy(const KindState& s, const Eigen::Vector3d& gravity) const {
  double e = 0.0;
  for (int a = 0; a < model_.NumNodes(); ++a) e += -model_.nodeMass[a] * gravity.dot(Node(s.x, a));
  return e;
}

double SoftKind::InternalEnergy(const KindState& s) const {
  return ElasticEnergy(model_, s.x, nullptr);
}

Eigen::Vector3d SoftKind::LinearMomentum(const KindState& s) const {
  return NodeMassSum(model_, s.v);
}

Eigen::Vector3d SoftKind::AngularMomentum(const KindState& s) const {
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (int a = 0; a < model_.NumNodes(); ++a)
    L += model_.nodeMass[a] * Node(s.x, a).cross(Node(s.v, a));
  return L;
}

Eigen::Vector3d SoftKind::CenterOfMass(const KindState& s) const {
  return NodeMassSum(model_, s.x) / model_.mass;
}

Eigen::Vector3d SoftKind::CenterOfMassVelocity(const KindState& s) const {
  return NodeMassSum(model_, s.v) / model_.mass;
}

void SoftKind::DifferenceGroups(const KindState& s,
                                std::vector<KindDifferenceGroup>* groups) const {
  const int n = static_cast<int>(s.x.size());
  groups->resize(model_.NumNodes());
  for (int a = 0; a < model_.NumNodes(); ++a) {
    KindDifferenceGroup& g = (*groups)[a];
    g = KindDifferenceGroup();
    for (int c = 0; c < 3; ++c) g.directions.push_back({{{3 * a + c, 1.0}}, false, 1.0});
    for (int c = 0; c < 3; ++c) g.directions.push_back({{{n + 3 * a + c, 1.0}}, true, 1.0});
    for (int c = 0; c < 3; ++c) g.entries.push_back(3 * a + c);
    for (int c = 0; c < 3; ++c) g.entries.push_back(n + 3 * a + c);
    if (model_.freeIndex[a] < 0) continue;
    for (int c = 0; c < 3; ++c) {
      g.tangentDofs.push_back(3 * a + c);
      g.tangentLength.push_back(1.0);
    }
  }
}

bool SoftKind::MotionParameter(KindMotion motion, int component, const KindState& s,
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

Eigen::MatrixXd SoftKind::CenterOfMassJacobian(const KindState& s) const {
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3, s.x.size());
  for (int a = 0; a < model_.NumNodes(); ++a)
    C.middleCols<3>(3 * a).diagonal().setConstant(model_.nodeMass[a] / model_.mass);
  return C;
}

KindSample SoftKind::Sample(int k, const Eigen::VectorXd& q) const {
  const SoftSurfaceSample& ss = model_.samples[k];
  const Eigen::Vector3i& F = model_.faces[ss.face];
  KindSample s;
  s.map = SamplePointMap::Face(ss.bary);
  s.y.setZero();
  for (int a = 0; a < 3; ++a) {
    s.faceNodes[a] = Node(q, F[a]);
    s.y += ss.bary[a] * s.faceNodes[a];
    s.dof[a] = 3 * F[a];
  }
  s.weight = ss.weight;
  s.hasNormal = true;
  s.faceNormal = true;
  s.face = ss.face;
  s.n = SoftFaceNormal(model_, q, ss.face);
  return s;
}

void SoftKind::ForEachSampleNear(
    const Eigen::VectorXd& q, const Eigen::VectorXd& qLast,
    const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&, double)>& keep,
    const std::function<void(int, int)>& visit) const {
  for (size_t f = 0; f < model_.faces.size(); ++f) {
    Eigen::Vector3d c, cLast;
    const double r = std::max(FaceBall(q, model_.faces[f], &c), FaceBall(qLast, model_.faces[f], &cLast));
    if (keep(c, cLast, r)) visit(model_.faceSampleBegin[f], model_.faceSampleBegin[f + 1]);
  }
}

}  // namespace superdex
