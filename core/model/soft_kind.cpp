#include "core/model/soft_kind.h"

#include "energies/stable_neo_hookean.h"

namespace superdex {

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
  KindSample s = TriangleSample(model_.faces[ss.face], ss.bary, ss.weight, ss.face, q);
  s.hasNormal = true;
  s.faceNormal = true;
  s.n = SoftFaceNormal(model_, q, ss.face);
  return s;
}

void SoftKind::ForEachSampleNear(
    const Eigen::VectorXd& q, const Eigen::VectorXd& qLast,
    const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&, double)>& keep,
    const std::function<void(int, int)>& visit) const {
  VisitTriangleSamplesNear(model_.faces, model_.faceSampleBegin, q, qLast, keep, visit);
}

}  // namespace superdex
