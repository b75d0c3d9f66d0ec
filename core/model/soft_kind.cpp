#include "core/model/soft_kind.h"

#include <algorithm>

#include "energies/stable_neo_hookean.h"

namespace superdex {
namespace {

Eigen::Vector3d Node(const Eigen::VectorXd& x, int i) { return x.segment<3>(3 * i); }

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

double SoftKind::InternalEnergy(const KindState& s) const {
  return ElasticEnergy(model_, s.x, nullptr);
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
    const double r = std::max(TriangleBall(q, model_.faces[f], &c), TriangleBall(qLast, model_.faces[f], &cLast));
    if (keep(c, cLast, r)) visit(model_.faceSampleBegin[f], model_.faceSampleBegin[f + 1]);
  }
}

}  // namespace superdex
