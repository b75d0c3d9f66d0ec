// Scene: state and parameter access beyond stepping — actor lookup, replacing states and
// parameters, and the dynamic state as one vector (the layout core/sensitivity/sensitivity.h differentiates).
#include <cmath>
#include <algorithm>
#include <sstream>

#include "core/dynamics/integrators.h"
#include "core/scene.h"

namespace superdex {
namespace {

bool ValidHandle(const Scene& scene, ActorHandle a, Error* error) {
  if (a.index >= 0 && a.index < scene.NumActors()) return true;
  return Fail(error, "actor: invalid handle " + std::to_string(a.index));
}

}  // namespace

RigidBodyState Scene::State(ActorHandle a) const { return RigidKind::Unpack(KindStateOf(a)); }

const SoftBodyModel& Scene::SoftModel(ActorHandle a) const { return SoftOf(a).Model(); }

const SoftBodyState& Scene::SoftState(ActorHandle a) const { return step_.vectorStates[a.index]; }

const KindState& Scene::KindStateOf(ActorHandle a) const { return step_.vectorStates[a.index]; }

bool Scene::SetSoftState(ActorHandle a, const SoftBodyState& state, Error* error) {
  if (!ValidHandle(*this, a, error)) return false;
  if (!actors_[a.index].soft) return Fail(error, "actor: " + ActorName(a) + " is not soft");
  const int n = 3 * SoftModel(a).NumNodes();
  if (state.x.size() != n || state.v.size() != n)
    return Fail(error, "state: x and v need " + std::to_string(n) + " entries (3 per node)");
  if (!state.x.allFinite() || !state.v.allFinite())
    return Fail(error, "state: x and v must be finite");
  step_.vectorStates[a.index] = state;
  ClearHistory();
  return true;
}

std::string Scene::ValidateKind(const ActorKind& kind) const {
  const std::string name = "actor (" + kind.KindName() + ")";
  if (std::string m = kind.Validate(); !m.empty()) return m;
  if (std::string m = Validate(kind.contact, "contact."); !m.empty()) return m;
  const int n = kind.NumDofs();
  if (n <= 0) return name + ": NumDofs must be > 0";
  const KindState s = kind.InitialState();
  if (s.x.size() != n || s.v.size() != n)
    return name + ": the initial state needs " + std::to_string(n) + " entries in x and v";
  if (!s.x.allFinite() || !s.v.allFinite()) return name + ": the initial state must be finite";
  const int m = kind.NumTangentDofs();
  if (m <= 0 || m > n) return name + ": NumTangentDofs must be in [1, NumDofs]";
  {  // A stage load at the first stage's time: m finite entries.
    KindStageData stage;
    stage.dt = 1.0;
    stage.gravity = settings_.gravity;
    stage.qHat = stage.q0 = stage.qLast = s.x;
    Eigen::VectorXd f;
    if (kind.StageLoad(stage, &f) && (f.size() != m || !f.allFinite()))
      return name + ": StageLoad must give NumTangentDofs (" + std::to_string(m) +
             ") finite entries, got " + std::to_string(f.size());
  }
  // Blocks read by the contact assembler: whole 3-dof blocks of δ, prescribed all or none.
  auto badBlock = [&](int first) {
    if (first < 0 || first + 3 > m) return true;
    return kind.IsPrescribed(first) != kind.IsPrescribed(first + 1) ||
           kind.IsPrescribed(first) != kind.IsPrescribed(first + 2);
  };
  for (int k = 0; k < kind.NumSamples(); ++k) {
    const KindSample ks = kind.Sample(k, s.x);
    const std::string sample = name + ": sample " + std::to_string(k);
    if (ks.map.kind == SamplePointMap::Kind::Nodes && (ks.map.nodes < 1 || ks.map.nodes > 4))
      return sample + " needs a Nodes map of 1 to 4 nodes";
    for (int b = 0; b < ks.Blocks(); ++b)
      if (badBlock(ks.dof[b])) return sample + " reads a dof block outside δ or partly prescribed";
    if (!(ks.weight >= 0.0)) return name + ": sample weights must be >= 0";
    if (ks.hasNormal && !(std::abs(ks.n.norm() - 1.0) < 1e-9))
      return sample + ": its colliding normal must be a unit vector";
  }
  for (int b = 0; b < kind.NumSampleBodies(); ++b) {
    const std::string body = name + ": sample body " + std::to_string(b);
    int dof[2];
    kind.SampleBodyDofs(b, dof);
    if (!kind.SampleBody(b)) return body + " has no geometry (SampleBody is null)";
    if (badBlock(dof[0]) || badBlock(dof[1]) ||
        kind.IsPrescribed(dof[0]) != kind.IsPrescribed(dof[1]))
      return body + " reads a dof block outside δ or partly prescribed";
  }
  if (const RigidCollider* c = kind.Collider()) {
    // The assembler and the step limit take φ >= |Y| − boundingRadius (the shape within it).
    if (!(c->boundingRadius > 0.0))
      return name + ": the collider's boundingRadius must be > 0 (max |X| over its shape, m)";
    const KindFrame f = kind.ColliderFrame(s.x);
    if (f.rigid && f.blocks != 2)
      return name + ": a rigid collider frame moves with 2 blocks, [δp] and [δθ]";
    if (f.blocks < 0 || f.blocks > 4) return name + ": the collider frame moves with 0 to 4 blocks";
    if (!f.rigid && !f.F.bottomRows<3>().isZero())
      return name + ": a collider frame that rotates with a general map of the dofs is not supported yet";
    for (int b = 0; b < f.blocks; ++b)
      if (badBlock(f.dof[b]))
        return name + ": the collider frame reads a dof block outside δ or partly prescribed";
  }
  return {};
}

bool Scene::SetKindState(ActorHandle a, const KindState& state, Error* error) {
  if (!ValidHandle(*this, a, error)) return false;
  const int n = Kind(a).NumDofs();
  if (state.x.size() != n || state.v.size() != n)
    return Fail(error, "state: x and v need " + std::to_string(n) + " entries");
  if (!state.x.allFinite() || !state.v.allFinite())
    return Fail(error, "state: x and v must be finite");
  step_.vectorStates[a.index] = state;
  ClearHistory();
  return true;
}

template <typename Change>
void Scene::ChangeKind(int a, Change&& change) {
  std::shared_ptr<ActorKind> changed = kinds_[a]->Clone();
  change(*changed);
  kinds_[a] = std::move(changed);
  prepared_ = false;
}

bool Scene::SetContactParams(ActorHandle a, const ContactParams& params, Error* error) {
  if (!ValidHandle(*this, a, error)) return false;
  if (std::string m = Validate(params, "contact."); !m.empty()) return Fail(error, m);
  const ActorRef& r = actors_[a.index];
  ChangeKind(a.index, [&](ActorKind& k) {
    k.contact = params;
    if (r.rigid) static_cast<RigidKind&>(k).SetContactParams(params);
  });
  if (r.rigid) rigidDescs_[r.desc].contact = params;
  if (r.soft) softDescs_[r.desc].contact = params;
  return true;
}

const ContactParams& Scene::GetContactParams(ActorHandle a) const { return Kind(a).contact; }

const SoftActorDesc& Scene::SoftDesc(ActorHandle a) const {
  return softDescs_[actors_[a.index].desc];
}

bool Scene::SetRigidMass(ActorHandle a, double mass, Error* error) {
  if (!ValidHandle(*this, a, error)) return false;
  const ActorRef& r = actors_[a.index];
  if (!r.rigid || !Model(a).dynamic)
    return Fail(error, "mass: '" + ActorName(a) + "' is not a dynamic rigid actor");
  if (!(std::isfinite(mass) && mass > 0))
    return Fail(error, "mass: must be > 0 and finite, got " + std::to_string(mass));
  RigidActorDesc& d = rigidDescs_[r.desc];
  if (d.inertia) *d.inertia *= mass / Model(a).mass;
  d.mass = mass;
  ChangeKind(a.index, [&](ActorKind& k) { static_cast<RigidKind&>(k).SetMass(mass); });
  return true;
}

bool Scene::SetSoftMaterial(ActorHandle a, double youngsModulus, double density, Error* error) {
  if (!ValidHandle(*this, a, error)) return false;
  if (!actors_[a.index].soft) return Fail(error, "actor: " + ActorName(a) + " is not soft");
  SoftMaterial changed = SoftModel(a).material;
  changed.youngsModulus = youngsModulus;
  changed.density = density;
  if (std::string msg = Validate(changed, "material."); !msg.empty()) return Fail(error, msg);
  ChangeKind(a.index, [&](ActorKind& k) {
    static_cast<SoftKind&>(k).SetMaterial(youngsModulus, density);
  });
  softDescs_[actors_[a.index].desc].material = SoftModel(a).material;
  return true;
}

double Scene::MinFrictionFalloffVel() const {
  double v = INFINITY;
  for (const auto& k : kinds_) v = std::min(v, k->contact.frictionFalloffVel);
  return v;
}

ActorHandle Scene::FindActor(const std::string& name) const {
  for (int i = 0; i < NumActors(); ++i)
    if (ActorName({i}) == name) return {i};
  return {};
}

const std::string& Scene::ActorName(ActorHandle a) const { return Kind(a).name; }

int Scene::HistoryBlocks() const {
  return IsMultistep(settings_.integrator) ? BdfSteps(settings_.integrator) - 1 : 0;
}

template <typename Visit>
void Scene::VisitStateLayout(int blocks, Visit&& visit) const {
  int offset = 0;
  for (int b = 0; b < blocks; ++b)
    for (int i = 0; i < NumActors(); ++i) {
      if (actors_[i].rigid && !RigidOf({i}).Model().dynamic) continue;
      visit(b, offset, i);
      offset += BlockSize(i);
    }
}

int Scene::StateOffset(ActorHandle a) {
  int found = -1;
  VisitStateLayout(1, [&](int, int offset, int i) {
    if (i == a.index) found = offset;
  });
  return found;
}

int Scene::StateSize() {
  int size = 0;
  VisitStateLayout(1 + HistoryBlocks(), [&](int, int offset, int i) {
    size = offset + BlockSize(i);
  });
  return size;
}

int Scene::FilledStateBlocks() const {
  return 1 + std::min(HistoryBlocks(), static_cast<int>(step_.vectorHistory.size()));
}

Eigen::VectorXd Scene::PackState() {
  Eigen::VectorXd s = Eigen::VectorXd::Zero(StateSize());
  VisitStateLayout(FilledStateBlocks(), [&](int b, int o, int v) {
    const SoftBodyState& st = b == 0 ? step_.vectorStates[v] : step_.vectorHistory[b - 1][v];
    const int n = static_cast<int>(st.x.size());
    s.segment(o, n) = st.x;
    s.segment(o + n, n) = st.v;
  });
  return s;
}

Eigen::VectorXd Scene::PackedVelocityMask() {
  Eigen::VectorXd mask = Eigen::VectorXd::Zero(StateSize());
  VisitStateLayout(1 + HistoryBlocks(), [&](int, int o, int i) {
    const int n = BlockSize(i) / 2;
    mask.segment(o + n, n).setOnes();
  });
  return mask;
}

void Scene::UnpackState(const Eigen::VectorXd& s) {
  VisitStateLayout(FilledStateBlocks(), [&](int b, int o, int v) {
    SoftBodyState& st = b == 0 ? step_.vectorStates[v] : step_.vectorHistory[b - 1][v];
    const int n = static_cast<int>(st.x.size());
    st.x = s.segment(o, n);
    st.v = s.segment(o + n, n);
  });
}

// A snapshot's layout is the one of checkpoint files and of Python's SceneState: the rigid
// actors' states in their order of creation under `states` (p, R, v, Ṙ), the other actors' (soft
// actors and other kinds, in their order of creation) under `vectorStates`. Inside the scene a
// rigid actor's state is its RigidKind's vector state (RigidKind::Pack, exact both ways).
void Scene::SplitRigid(const std::vector<VectorState>& vector, std::vector<RigidBodyState>* rigid,
                       std::vector<VectorState>* rest) const {
  std::vector<char> isRigid(vector.size(), 0);
  rigid->assign(rigidDescs_.size(), RigidBodyState());
  for (size_t i = 0; i < actors_.size(); ++i)
    if (actors_[i].rigid) {
      isRigid[i] = 1;
      (*rigid)[actors_[i].desc] = RigidKind::Unpack(vector[i]);
    }
  rest->clear();
  for (size_t v = 0; v < vector.size(); ++v)
    if (!isRigid[v]) rest->push_back(vector[v]);
}

void Scene::HoldStatic(int a, const RigidBodyState& state) {
  const RigidKind& kind = RigidOf({a});
  if (kind.Model().dynamic) return;
  const RigidBodyState& held = kind.Held();
  if (held.p == state.p && held.R == state.R && held.v == state.v && held.Rdot == state.Rdot) return;
  ChangeKind(a, [&](ActorKind& k) { static_cast<RigidKind&>(k).Hold(state); });
}

void Scene::JoinRigid(const std::vector<RigidBodyState>& rigid,
                      const std::vector<VectorState>& rest,
                      std::vector<VectorState>* vector) const {
  vector->assign(rigid.size() + rest.size(), SoftBodyState());
  std::vector<char> isRigid(vector->size(), 0);
  for (size_t i = 0; i < actors_.size(); ++i)
    if (actors_[i].rigid) {
      isRigid[i] = 1;
      (*vector)[i] = RigidKind::Pack(rigid[actors_[i].desc]);
    }
  size_t next = 0;
  for (size_t v = 0; v < vector->size(); ++v)
    if (!isRigid[v]) (*vector)[v] = rest[next++];
}

Scene::Snapshot Scene::Save() const {
  Snapshot s{StepState(), driver_.GetState()};
  s.step.time = step_.time;
  s.step.historyTimes = step_.historyTimes;
  SplitRigid(step_.vectorStates, &s.step.rigidStates, &s.step.vectorStates);
  s.step.rigidHistory.resize(step_.vectorHistory.size());
  s.step.vectorHistory.resize(step_.vectorHistory.size());
  for (size_t h = 0; h < step_.vectorHistory.size(); ++h)
    SplitRigid(step_.vectorHistory[h], &s.step.rigidHistory[h], &s.step.vectorHistory[h]);
  return s;
}

void Scene::Restore(const Snapshot& s) {
  step_.time = s.step.time;
  step_.historyTimes = s.step.historyTimes;
  JoinRigid(s.step.rigidStates, s.step.vectorStates, &step_.vectorStates);
  for (size_t i = 0; i < actors_.size(); ++i)
    if (actors_[i].rigid) HoldStatic(static_cast<int>(i), s.step.rigidStates[actors_[i].desc]);
  step_.vectorHistory.resize(s.step.vectorHistory.size());
  for (size_t h = 0; h < s.step.vectorHistory.size(); ++h)
    JoinRigid(s.step.rigidHistory[h], s.step.vectorHistory[h], &step_.vectorHistory[h]);
  driver_.SetState(s.driver);
  buffers_.reportStage.valid = false;  // the state is not the last stage's any more
}

void Scene::ClearHistory() {
  step_.rigidHistory.clear();
  step_.vectorHistory.clear();
  step_.historyTimes.clear();
  buffers_.reportStage.valid = false;
}

const std::vector<int>& Scene::KindStageDofs(ActorHandle a) const {
  return kindStageDof_[a.index];
}

int Scene::StageDofOffset(ActorHandle a) const {
  for (int d : kindStageDof_[a.index])
    if (d >= 0) return d;
  return -1;
}

}  // namespace superdex
