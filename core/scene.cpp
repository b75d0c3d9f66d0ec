#include "core/scene.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/dynamics/integrators.h"
#include "core/dynamics/scene_stage.h"
#include "core/model/rigid_math.h"

namespace superdex {
namespace {

int Severity(StageStatus s) {
  return s == StageStatus::Converged ? 0 : s == StageStatus::Stopped ? 1 : 2;
}

// Adds one stage's work, contact figures and status to the step's report.
void AccountStage(const SolverStats& st, const ContactStats& stageContact, StepReport* r) {
  StepReport& rep = *r;
  rep.maxCoulombRatio = std::max(rep.maxCoulombRatio, stageContact.maxCoulombRatio);
  rep.dissipativeSamples = std::max(rep.dissipativeSamples, stageContact.dissipativeSamples);
  rep.dissipation += stageContact.dissipation;
  ++rep.stages;
  rep.newtonIterations += st.iterations;
  rep.lineSearchSteps += st.lineSearchSteps;
  if (st.closedForm) ++rep.freeStages;
  if (st.fallback) {
    ++rep.fallbacks;
    if (rep.fallbackMessage.empty()) rep.fallbackMessage = st.Message();
  }
  rep.assemblySeconds += st.assemblySeconds;
  rep.factorizationSeconds += st.factorizationSeconds;
  rep.lineSearchSeconds += st.lineSearchSeconds;
  rep.krylovIterations += st.krylovIterations;
  rep.krylovFallbacks += st.krylovFallbacks;
  rep.finalGradientNorm = std::max(rep.finalGradientNorm, st.finalGradientNorm);
  if (Severity(st.status) > Severity(rep.status)) {
    rep.status = st.status;
    rep.message = st.Message();
  }
}

// The dissipation coefficients of ContactParams, each combined by the geometric mean of a pair's
// two actors (HasDissipation, ZeroByCombinationNotices).
struct DissipationCoefficient {
  const char* name;
  double ContactParams::*member;
};
constexpr DissipationCoefficient kDissipationCoefficients[] = {
    {"coulomb_friction_coefficient", &ContactParams::coulombFrictionCoefficient},
    {"viscous_friction_coefficient", &ContactParams::viscousFrictionCoefficient},
    {"normal_viscous_damping_coefficient", &ContactParams::normalViscousDampingCoefficient}};

// Notices for the dissipation coefficients that combine to 0 (Notices).
void ZeroByCombinationNotices(const Scene& scene, std::vector<std::string>* out) {
  // A pair's μ, c_t and c_n are geometric means (spec: "Contact Parameter Combination"): one
  // actor's 0 makes its pairs' 0 whatever the other sets. Noted where an actor sets a nonzero
  // value other than the default and another has 0 (a 0 against the default is the usual way to
  // make a pair frictionless or undamped).
  const ContactParams defaults;
  auto notice = [&](const char* field, auto coefficient) {
    std::vector<std::string> set, zero;
    for (int i = 0; i < scene.NumActors(); ++i) {
      const double c = coefficient(scene.GetContactParams({i}));
      if (c > 0 && c != coefficient(defaults)) set.push_back("'" + scene.ActorName({i}) + "'");
      if (c == 0) zero.push_back("'" + scene.ActorName({i}) + "'");
    }
    if (set.empty() || zero.empty()) return;
    auto list = [](const std::vector<std::string>& names) {
      std::string s = names.front();
      if (names.size() > 1) s += " and " + std::to_string(names.size() - 1) + " more";
      return s;
    };
    out->push_back(std::string("contact.") + field + ": set on " + list(set) + " but 0 on " +
                   list(zero) + "; a pair combines it by the geometric mean of its two actors, "
                   "so every pair with an actor at 0 has none (set it on both actors)");
  };
  for (const DissipationCoefficient& d : kDissipationCoefficients)
    notice(d.name, [&](const ContactParams& c) { return c.*d.member; });
}

// The smallest det F over the soft actors' tets (+∞ without).
double MinDetF(const Scene& scene) {
  double minDet = INFINITY;
  for (ActorHandle a : scene.SoftActors()) {
    double md = INFINITY;
    ElasticEnergy(scene.SoftModel(a), scene.SoftState(a).x, &md);
    minDet = std::min(minDet, md);
  }
  return minDet;
}

}  // namespace

Scene::Scene(const SceneSettings& settings)
    : settings_(settings), settingsError_(Validate(settings)) {}

bool Scene::SetStageSolver(StageSolverKind kind, Error* error) {
  if (kind == StageSolverKind::Ipopt && HasDissipation() && !settings_.eval.explicitNormals)
    return Fail(error, "stage_solver: ipopt minimizes potential stages only, and this scene's "
                       "dissipation is not a potential (explicit_normals = false); use newton or "
                       "ceres, or set experimental_eval_params.explicit_normals = true");
  settings_.stageSolver = kind;
  settingsError_ = Validate(settings_);
  return true;
}

bool Scene::ValidParent(ActorHandle parent, Error* error) const {
  return parent.index < NumActors() ||
         Fail(error, "parent: invalid actor handle " + std::to_string(parent.index));
}

ActorHandle Scene::Register(std::shared_ptr<ActorKind> k, const std::string& layer,
                            ActorHandle parent) {
  step_.vectorStates.push_back(k->InitialState());
  kinds_.push_back(std::move(k));
  filter_.AddActor(layer, parent.index);
  actors_.emplace_back();
  prepared_ = false;
  ClearHistory();
  return {NumActors() - 1};
}

bool Scene::UniqueName(const std::string& name, Error* error) const {
  if (name.empty() || !FindActor(name).IsValid()) return true;
  return Fail(error, "name: duplicate actor name \"" + name + "\" (actor names are unique)");
}

ActorHandle Scene::AddRigidActor(const RigidActorDesc& desc, Error* error, ActorHandle parent) {
  if (!ValidParent(parent, error) || !UniqueName(desc.name, error)) return {};
  RigidBodyModel model;
  RigidBodyState state;
  if (!BuildRigidBody(desc, "", &model, &state, error)) return {};
  if (!model.samples.empty()) {
    // One buffer for the samples of identical shapes (a grid of spheres).
    const std::size_t hash = SamplesHash(model);
    bool shared = false;
    for (auto [it, end] = sampleSets_.equal_range(hash); it != end && !shared; ++it)
      shared = ShareSamples(static_cast<const RigidKind&>(*kinds_[it->second]).Model(), &model);
    if (!shared) sampleSets_.emplace(hash, static_cast<int>(kinds_.size()));
  }
  // A rigid actor is the generic layer's RigidKind.
  rigidDescs_.push_back(desc);
  const ActorHandle h =
      Register(std::make_shared<RigidKind>(std::move(model), state), desc.contactLayer, parent);
  actors_[h.index].rigid = true;
  actors_[h.index].desc = static_cast<int>(rigidDescs_.size()) - 1;
  return h;
}

ActorHandle Scene::AddSoftActor(const SoftActorDesc& desc, Error* error, ActorHandle parent) {
  if (!ValidParent(parent, error) || !UniqueName(desc.name, error)) return {};
  // A soft actor is the generic layer's SoftKind.
  std::shared_ptr<SoftKind> kind = SoftKind::Build(desc, error);
  if (!kind) return {};
  if (!desc.skin.empty()) {  // a soft skin on its skeleton's links
    std::vector<CarriedPart> parts;
    if (!SkinParts(desc, *kind, parent, &parts, error)) return {};
    kind->SetCarriedParts(std::move(parts));
    if (!CheckCarried(*kind, parent, error)) return {};
  }
  softDescs_.push_back(desc);
  const bool carried = kind->IsCarried();
  const ActorHandle h = Register(std::move(kind), desc.contactLayer, parent);
  actors_[h.index].soft = true;
  actors_[h.index].desc = static_cast<int>(softDescs_.size()) - 1;
  if (carried) AttachToCarrier(h, parent);
  return h;
}

ActorHandle Scene::AddActor(std::unique_ptr<ActorKind> actor, Error* error,
                            const std::string& contactLayer, ActorHandle parent) {
  if (!ValidParent(parent, error)) return {};
  if (!actor) return Fail(error, "actor: null"), ActorHandle();
  if (!UniqueName(actor->name, error)) return {};
  if (std::string m = ValidateKindLayout(*actor, settings_.gravity); !m.empty())
    return Fail(error, m), ActorHandle();
  const bool carried = actor->IsCarried();
  if (carried && !CheckCarried(*actor, parent, error)) return {};
  const ActorHandle h = Register(std::move(actor), contactLayer, parent);
  if (carried) AttachToCarrier(h, parent);
  return h;
}

void Scene::SyncAttachedStates() {
  auto sync = [&](std::vector<VectorState>* states) {
    for (size_t a = 0; a < actors_.size(); ++a) {
      const int c = actors_[a].carrier;
      if (c < 0 || static_cast<size_t>(c) >= states->size()) continue;
      const std::vector<CarriedPart>& parts = *kinds_[a]->CarriedParts();
      AttachedConfiguration(*kinds_[c], parts, (*states)[c].x, &(*states)[a].x);
      AttachedConfiguration(*kinds_[c], parts, (*states)[c].v, &(*states)[a].v);
    }
  };
  sync(&step_.vectorStates);
  for (std::vector<VectorState>& h : step_.vectorHistory) sync(&h);
}

std::vector<ActorHandle> Scene::ActorsWhere(bool ActorRef::*flag) const {
  std::vector<ActorHandle> out;
  for (int i = 0; i < NumActors(); ++i)
    if (actors_[i].*flag) out.push_back({i});
  return out;
}

Eigen::Vector3d Scene::CenterOfMass(ActorHandle a) const {
  return Kind(a).CenterOfMass(KindStateOf(a));
}

Eigen::Vector3d Scene::CenterOfMassVelocity(ActorHandle a) const {
  return Kind(a).CenterOfMassVelocity(KindStateOf(a));
}

namespace {
bool ValidHandle(ActorHandle a, int n, const char* field, Error* error) {
  if (a.index >= 0 && a.index < n) return true;
  return Fail(error, std::string(field) + ": invalid actor handle " + std::to_string(a.index));
}
}  // namespace

bool Scene::SetContactLayer(ActorHandle actor, const std::string& layer, Error* error) {
  if (!ValidHandle(actor, NumActors(), "actor", error)) return false;
  filter_.SetLayer(actor.index, layer);
  const ActorRef& r = actors_[actor.index];
  // The filter holds the layer; the descriptions keep it for the writer.
  if (r.rigid) rigidDescs_[r.desc].contactLayer = layer;
  if (r.soft) softDescs_[r.desc].contactLayer = layer;
  return true;
}

const std::string& Scene::ContactLayer(ActorHandle actor) const {
  return filter_.Layer(actor.index);
}

bool Scene::EnableLayerContactAsymmetric(const std::string& layerA, const std::string& layerB,
                                         bool enable, Error*) {
  filter_.EnableLayer(layerA, layerB, enable);
  return true;
}

bool Scene::EnableLayerContactSymmetric(const std::string& layerA, const std::string& layerB,
                                        bool enable, Error*) {
  filter_.EnableLayer(layerA, layerB, enable);
  filter_.EnableLayer(layerB, layerA, enable);
  return true;
}

bool Scene::EnableActorContactAsymmetric(ActorHandle a, ActorHandle b, bool enable,
                                         IncludeNestedActors nested, Error* error) {
  if (!ValidHandle(a, NumActors(), "A", error) || !ValidHandle(b, NumActors(), "B", error))
    return false;
  filter_.EnableActors(a.index, b.index, enable, nested == IncludeNestedActors::Yes);
  return true;
}

bool Scene::EnableActorContactSymmetric(ActorHandle a, ActorHandle b, bool enable,
                                        IncludeNestedActors nested, Error* error) {
  return EnableActorContactAsymmetric(a, b, enable, nested, error) &&
         EnableActorContactAsymmetric(b, a, enable, nested, error);
}

void Scene::DisableAdjacentContact(ActorHandle a, ActorHandle b) {
  filter_.EnableActors(a.index, b.index, false, false);
  filter_.EnableActors(b.index, a.index, false, false);
}

bool Scene::ContactAllowed(ActorHandle a, ActorHandle b) const {
  return filter_.Allowed(a.index, b.index);
}

bool Scene::SetIntegrator(IntegrationMethod method, Error* error) {
  SceneSettings s = settings_;
  s.integrator = method;
  if (std::string m = Validate(s); !m.empty()) return Fail(error, m);
  settings_ = s;
  settingsError_.clear();
  ClearHistory();
  return true;
}

bool Scene::SetSolverParams(const NonlinearSolverParams& params, Error* error) {
  SceneSettings s = settings_;
  s.solver = params;
  if (std::string m = Validate(s); !m.empty()) return Fail(error, m);
  settings_ = s;
  settingsError_.clear();
  return true;
}

bool Scene::SetState(ActorHandle a, const RigidBodyState& state, Error* error) {
  if (a.index < 0 || a.index >= NumActors()) return Fail(error, "actor: invalid handle");
  if (!actors_[a.index].rigid) return Fail(error, "actor: '" + ActorName(a) + "' is not rigid");
  if (Model(a).kinematic)
    return Fail(error, "actor: '" + Model(a).name +
                           "' is a kinematic actor: its motion is prescribed (path or velocity)");
  if (!state.p.allFinite() || !state.R.allFinite() || !state.v.allFinite() ||
      !state.Rdot.allFinite())
    return Fail(error, "state: must be finite");
  if ((state.R.transpose() * state.R - Eigen::Matrix3d::Identity()).norm() > 1e-9 ||
      state.R.determinant() <= 0)
    return Fail(error, "state.R: must be a rotation matrix");
  HoldStatic(a.index, state);
  step_.vectorStates[a.index] = RigidKind::Pack(state);
  ClearHistory();
  return true;
}

void Scene::Prepare() {
  if (prepared_) return;
  numDofs_ = 0;
  // Every actor's free tangent dofs, in creation order.
  kindPtrs_.clear();
  kindStageDof_.resize(kinds_.size());
  attached_.clear();
  for (size_t k = 0; k < kinds_.size(); ++k) {
    kindPtrs_.push_back(kinds_[k].get());
    kindStageDof_[k].resize(kinds_[k]->NumTangentDofs());
    // A carried part's dofs are no unknowns (they follow the carrier's).
    std::vector<char> carried(kindStageDof_[k].size(), 0);
    if (actors_[k].carrier >= 0) {
      for (const CarriedPart& p : *kinds_[k]->CarriedParts())
        std::fill_n(carried.begin() + p.dof, p.Size(), 1);
      attached_.push_back({static_cast<int>(k), actors_[k].carrier});
    }
    for (int i = 0; i < kinds_[k]->NumTangentDofs(); ++i)
      kindStageDof_[k][i] = !carried[i] && !kinds_[k]->IsPrescribed(i) ? numDofs_++ : -1;
  }
  // The contact's numbering: the carried parts' dofs after the unknowns, where the carrier has
  // some.
  numContactDofs_ = numDofs_;
  kindContactDof_.clear();
  if (!attached_.empty()) {
    kindContactDof_ = kindStageDof_;
    for (const KindStage::Attached& a : attached_)
      if (kinds_[a.carrier]->HasFreeDof())
        for (const CarriedPart& p : *kinds_[a.actor]->CarriedParts())
          for (int i = p.dof; i < p.dof + p.Size(); ++i)
            kindContactDof_[a.actor][i] = numContactDofs_++;
  }
  std::vector<int> kindActor(kinds_.size());
  for (int i = 0; i < NumActors(); ++i) kindActor[i] = i;
  pipeline_.Configure(&filter_, &kindPtrs_, kindActor);
  hasDissipation_ = HasDissipation();  // actors' contact parameters are fixed once added
  coldStages_ = false;
  for (const auto& k : kinds_) coldStages_ = coldStages_ || !k->Shortcuts().warmStart;
  prepared_ = true;
}

void Scene::CurrentPositions(std::vector<Eigen::VectorXd>* x) const {
  x->resize(step_.vectorStates.size());
  for (size_t s = 0; s < step_.vectorStates.size(); ++s) (*x)[s] = step_.vectorStates[s].x;
}

void Scene::MakeStage(double dt, double t, const std::vector<VectorState>& start,
                      const std::vector<Eigen::VectorXd>& last, KindStage* out) const {
  KindStage& ks = *out;
  ks.kinds = &kindPtrs_;
  ks.stageDof = kindStageDof_;
  ks.data.resize(kinds_.size());
  ks.q0.resize(kinds_.size());
  ks.qLast.resize(kinds_.size());
  for (size_t k = 0; k < kinds_.size(); ++k) {
    KindStageData& d = ks.data[k];
    d.dt = dt;
    d.time = t;
    d.gravity = settings_.gravity;
    d.qHat = start[k].x + dt * start[k].v;
    d.q0 = start[k].x;
    d.qLast = last[k];
  }
  for (const KindStage::Attached& a : attached_) {  // the carried parts' from the carrier's
    const std::vector<CarriedPart>& parts = *kinds_[a.actor]->CarriedParts();
    const KindStageData& c = ks.data[a.carrier];
    KindStageData& d = ks.data[a.actor];
    AttachedConfiguration(*kinds_[a.carrier], parts, c.qHat, &d.qHat);
    AttachedConfiguration(*kinds_[a.carrier], parts, c.q0, &d.q0);
    AttachedConfiguration(*kinds_[a.carrier], parts, c.qLast, &d.qLast);
  }
  for (size_t k = 0; k < kinds_.size(); ++k) {
    kinds_[k]->PrepareStage(&ks.data[k]);
    ks.q0[k] = ks.data[k].q0;
    ks.qLast[k] = ks.data[k].qLast;
  }
  ks.attached = attached_;
  ks.contactDof = kindContactDof_;
  ks.numContactDofs = numContactDofs_;
}

void Scene::ApplyConstraints(double t, std::vector<Eigen::VectorXd>* x) const {
  for (size_t k = 0; k < kinds_.size(); ++k) kinds_[k]->Prescribe(t, &(*x)[k]);
}

void Scene::SolveStage(double dt, const KindStage& stage, std::vector<Eigen::VectorXd>* x,
                       double predictTime, StepReport* rep) {
  StageScene scene;
  scene.numDofs = numDofs_;
  scene.pipeline = &pipeline_;
  scene.coldStages = coldStages_;
  scene.hasDissipation = hasDissipation_;
  scene.vectorStates = &step_.vectorStates;
  scene.vectorHistory = &step_.vectorHistory;
  scene.historyTimes = &step_.historyTimes;
  scene.time = step_.time;
  ContactStats contact;
  const SolverStats st =
      driver_.Solve(settings_, scene, dt, &contact, stage, x, predictTime, recorder_);
  AccountStage(st, contact, rep);
  // What ContactSamples needs to report this stage's dissipation at the state it produced.
  ReportStage& r = buffers_.reportStage;
  r.valid = hasDissipation_;
  if (!r.valid) return;
  r.dt = dt;
  r.mode = st.fallback ? DissipationMode::ExplicitNormals : ModeOf(settings_.eval);
  r.fadeFriction = settings_.eval.fadeFriction;
  r.q0 = stage.q0;  // copies into the kept storage
  r.qLast = stage.qLast;
}

bool Scene::Step(double h, StepReport* report, Error* error, StageRecorder* recorder) {
  if (!(std::isfinite(h) && h > 0)) {
    std::ostringstream s;
    s << "dt: must be > 0 and finite, got " << h;
    return Fail(error, s.str());
  }
  if (!settingsError_.empty()) return Fail(error, settingsError_);
  if (settings_.stageSolver == StageSolverKind::Ipopt && !SetStageSolver(settings_.stageSolver, error))
    return false;
  const auto t0 = std::chrono::steady_clock::now();
  Prepare();
  recorder_ = recorder;
  if (recorder_) recorder_->BeginStep();
  CurrentPositions(&buffers_.x);
  buffers_.stepStart = buffers_.x;
  buffers_.next = step_.vectorStates;
  StepWork w{buffers_.x, buffers_.stepStart, buffers_.next, StepReport()};
  StepReport& rep = w.report;
  rep.dt = h;
  const IntegrationMethod method = settings_.integrator;

  // BDF3 starts with DIRK33 steps while its history fills: a Backward Euler start (local error
  // O(h²)) would cap its global order at 2. BDF2 starts with one BDF1 (Backward Euler) step, whose
  // O(h²) local error is within BDF2's own global order (core/dynamics/time_stepper.h).
  const bool bdf3Startup = method == IntegrationMethod::BDF3 && step_.vectorHistory.size() < 2;
  if (IsMultistep(method) && !bdf3Startup)
    StepBdf(step_, h, method, *this, &buffers_, &w);
  else
    StepDirk(step_, h, bdf3Startup ? IntegrationMethod::DIRK33 : method, *this, &buffers_, &w);
  EndStep(h, &w, &step_);
  if (!attached_.empty()) SyncAttachedStates();
  rep.time = step_.time;
  const bool supplied = recorder_ && recorder_->Supplies();
  recorder_ = nullptr;
  if (supplied) {  // the state only
    if (report) *report = rep;
    return true;
  }
  if (!softDescs_.empty()) rep.minDetF = MinDetF(*this);
  rep.contact = ContactState();
  rep.wallSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (report) *report = rep;
  return true;
}

ContactStats Scene::ContactState() {
  Prepare();
  ContactStats st;
  std::vector<Eigen::VectorXd>& x = buffers_.x;  // scratch between steps
  CurrentPositions(&x);
  const KindView kinds = CurrentKindView(x);
  pipeline_.Evaluate(0, PsdProjection::None, nullptr, nullptr, nullptr, &st, nullptr, nullptr,
                     &kinds);
  return st;
}

KindView Scene::CurrentKindView(const std::vector<Eigen::VectorXd>& x) const {
  KindView kinds;
  kinds.q = &x;
  kinds.stageDof = attached_.empty() ? &kindStageDof_ : &kindContactDof_;
  return kinds;
}

std::vector<ContactSampleRecord> Scene::ContactSamples() {
  Prepare();
  std::vector<ContactSampleRecord> out;
  std::vector<Eigen::VectorXd>& x = buffers_.x;  // scratch between steps
  CurrentPositions(&x);
  KindView kinds = CurrentKindView(x);
  const ReportStage& r = buffers_.reportStage;
  if (!r.valid) {
    pipeline_.CollectSamples(&out, &kinds);
    return out;
  }
  // The last stage's dissipation at the state it produced.
  kinds.q0 = r.q0.empty() ? nullptr : &r.q0;
  kinds.qLast = r.qLast.empty() ? nullptr : &r.qLast;
  DissipationContext context;
  context.dt = r.dt;
  context.mode = r.mode;
  context.fadeFriction = r.fadeFriction;
  pipeline_.CollectSamples(&out, &kinds, &context);
  return out;
}

bool Scene::SoftFaceTractions(ActorHandle a, std::vector<Eigen::Vector3d>* tractions,
                              Error* error) {
  if (a.index < 0 || a.index >= NumActors() || !actors_[a.index].soft)
    return Fail(error, "actor: not a soft actor handle");
  const SoftBodyModel& m = SoftModel(a);
  tractions->assign(m.faces.size(), Eigen::Vector3d::Zero());
  for (const ContactSampleRecord& r : ContactSamples())
    if (r.colliding == a.index && r.face >= 0)
      (*tractions)[r.face] += r.weight * (r.traction + r.friction + r.damping) / m.faceArea[r.face];
  return true;
}

EnergyReport Scene::Energies() {
  EnergyReport e;
  for (size_t k = 0; k < kinds_.size(); ++k) {
    const KindState& st = step_.vectorStates[k];
    e.kinetic += kinds_[k]->KineticEnergy(st);
    e.gravity += kinds_[k]->GravityEnergy(st, settings_.gravity);
    e.elastic += kinds_[k]->InternalEnergy(st);
  }
  e.contact = ContactState().energy;
  return e;
}

Eigen::Vector3d Scene::TotalLinearMomentum() const {
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < kinds_.size(); ++k) L += kinds_[k]->LinearMomentum(step_.vectorStates[k]);
  return L;
}

Eigen::Vector3d Scene::TotalAngularMomentum() const {
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < kinds_.size(); ++k) L += kinds_[k]->AngularMomentum(step_.vectorStates[k]);
  return L;
}

std::vector<std::string> Scene::Notices() const {
  std::vector<std::string> out;
  for (ActorHandle a : RigidActors())
    if (!Model(a).notice.empty()) out.push_back(Model(a).notice);
  for (ActorHandle a : SoftActors())
    if (!SoftModel(a).notice.empty()) out.push_back(SoftModel(a).notice);
  // Kinds' own samples without a rigid or deforming face's normal do not collide on soft
  // fields (CollidesOnTetField).
  bool softCollider = false;
  for (const auto& k : kinds_) softCollider = softCollider || k->TetCollider();
  for (const auto& k : kinds_) {
    if (!softCollider || k->NumSamples() == 0) continue;
    if (CollidesOnTetField(k->Sample(0, k->InitialState().x))) continue;
    out.push_back("actors of the generic layer (" + k->KindName() +
                  ") whose samples have no colliding normal do not collide on a soft actor's "
                  "field: that pair is not supported yet (soft actors do collide on theirs)");
    break;
  }
  ZeroByCombinationNotices(*this, &out);
  return out;
}

bool Scene::HasDissipation() const {
  // A pair's μ, c_t and c_n are geometric means: dissipation needs two actors, one of them
  // dynamic, that both have a nonzero coefficient of the same kind (a point cloud in self-contact
  // is both).
  auto twoWith = [&](auto coefficient) {
    int count = 0, dynamic = 0;
    for (const auto& k : kinds_)  // a kind's actor is, where a dof is free
      if (coefficient(k->contact) > 0) {
        count += k->PointCloud() && k->PointCloud()->selfContact ? 2 : 1;
        dynamic += k->HasFreeDof();
      }
    return count >= 2 && dynamic >= 1;
  };
  for (const DissipationCoefficient& d : kDissipationCoefficients)
    if (twoWith([&](const ContactParams& c) { return c.*d.member; })) return true;
  return false;
}

}  // namespace superdex
