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

const SoftBodyModel& Scene::SoftModel(ActorHandle a) const {
  return static_cast<const SoftKind&>(Kind(a)).Model();
}

const SoftBodyState& Scene::SoftState(ActorHandle a) const { return step_.vectorStates[a.index]; }

const KindState& Scene::KindStateOf(ActorHandle a) const { return step_.vectorStates[a.index]; }

bool Scene::SetSoftState(ActorHandle a, const SoftBodyState& state, Error* error) {
  if (!ValidHandle(*this, a, error)) return false;
  if (!actors_[a.index].soft) return Fail(error, "actor: " + ActorName(a) + " is not soft");
  return SetKindState(a, state, error);
}

bool Scene::SetKindState(ActorHandle a, const KindState& state, Error* error) {
  if (!ValidHandle(*this, a, error)) return false;
  const int n = Kind(a).NumDofs();
  if (state.x.size() != n || state.v.size() != n)
    return Fail(error, "state: x and v need " + std::to_string(n) + " entries" +
                           (actors_[a.index].soft ? " (3 per node)" : ""));
  if (!state.x.allFinite() || !state.v.allFinite())
    return Fail(error, "state: x and v must be finite");
  if (IsAttached(a))
    return Fail(error, "actor: '" + ActorName(a) +
                           "' is attached to its carrier: its state follows the carrier's");
  step_.vectorStates[a.index] = state;
  ClearHistory();
  SyncAttachedStates();
  return true;
}

template <typename Change>
void Scene::ChangeKind(int a, Change&& change) {
  std::shared_ptr<ActorKind> changed = kinds_[a]->Clone();
  change(*changed);
  kinds_[a] = std::move(changed);
  prepared_ = false;
}

namespace {
// Actor a's articulated kind, or null with *error.
const ArticulatedKind* ArticulatedOf(const Scene& scene, ActorHandle a, int link, Error* error) {
  const auto* k = a.index >= 0 && a.index < scene.NumActors()
                      ? dynamic_cast<const ArticulatedKind*>(&scene.Kind(a))
                      : nullptr;
  if (!k) return Fail(error, "actor: not an articulated actor"), nullptr;
  if (link < 0 || link >= k->NumLinks())
    return Fail(error, "link: no link " + std::to_string(link) + " in '" + scene.ActorName(a) +
                           "'"),
           nullptr;
  return k;
}
}  // namespace

template <typename Edit>
bool Scene::EditLink(ActorHandle a, int link, Error* error, Edit&& edit) {
  const ArticulatedKind* k = ArticulatedOf(*this, a, link, error);
  if (!k) return false;
  ArticulatedKind trial = *k;  // validated on a copy first
  if (std::string m = edit(trial); !m.empty())
    return Fail(error, "link '" + k->LinkName(link) + "': " + m);
  ChangeKind(a.index, [&](ActorKind& kind) { edit(static_cast<ArticulatedKind&>(kind)); });
  return true;
}

bool Scene::SetLinkMass(ActorHandle a, int link, double mass, Error* error) {
  return EditLink(a, link, error, [&](ArticulatedKind& k) { return k.SetLinkMass(link, mass); });
}

bool Scene::SetLinkJointParams(ActorHandle a, int link, const JointParams& params, Error* error) {
  return EditLink(a, link, error,
                  [&](ArticulatedKind& k) { return k.SetLinkJointParams(link, params); });
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
      if (IsAttached({i})) continue;  // follows its carrier
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
  SyncAttachedStates();
}

void Scene::HoldStatic(int a, const RigidBodyState& state) {
  const RigidKind& kind = RigidOf({a});
  if (kind.Model().dynamic) return;
  const RigidBodyState& held = kind.Held();
  if (held.p == state.p && held.R == state.R && held.v == state.v && held.Rdot == state.Rdot) return;
  ChangeKind(a, [&](ActorKind& k) { static_cast<RigidKind&>(k).Hold(state); });
}

namespace {

// A snapshot's layout is the one of checkpoint files and of Python's SceneState: the rigid
// actors' states in their order of creation under `rigidStates` (p, R, v, Ṙ), the other actors'
// (soft actors and other kinds, in their order of creation) under `vectorStates`. Inside the scene a
// rigid actor's state is its RigidKind's vector state (RigidKind::Pack, exact both ways).
// rigidDesc[i]: actor i's index among the rigid actors, −1 for another kind.
void SplitRigid(const std::vector<int>& rigidDesc, const std::vector<VectorState>& vector,
                std::vector<RigidBodyState>* rigid, std::vector<VectorState>* rest) {
  rigid->clear();
  rest->clear();
  for (size_t i = 0; i < vector.size(); ++i) {
    if (rigidDesc[i] < 0) {
      rest->push_back(vector[i]);
      continue;
    }
    if (static_cast<int>(rigid->size()) <= rigidDesc[i]) rigid->resize(rigidDesc[i] + 1);
    (*rigid)[rigidDesc[i]] = RigidKind::Unpack(vector[i]);
  }
}

void JoinRigid(const std::vector<int>& rigidDesc, const std::vector<RigidBodyState>& rigid,
               const std::vector<VectorState>& rest, std::vector<VectorState>* vector) {
  vector->assign(rigidDesc.size(), VectorState());
  size_t next = 0;
  for (size_t i = 0; i < rigidDesc.size(); ++i)
    (*vector)[i] = rigidDesc[i] >= 0 ? RigidKind::Pack(rigid[rigidDesc[i]]) : rest[next++];
}

}  // namespace

std::vector<int> Scene::RigidDescs() const {
  std::vector<int> desc(actors_.size(), -1);
  for (size_t i = 0; i < actors_.size(); ++i)
    if (actors_[i].rigid) desc[i] = actors_[i].desc;
  return desc;
}

Scene::Snapshot Scene::Save() const {
  Snapshot s{StepState(), driver_.GetState()};
  const std::vector<int> rigidDesc = RigidDescs();
  s.step.time = step_.time;
  s.step.historyTimes = step_.historyTimes;
  SplitRigid(rigidDesc, step_.vectorStates, &s.step.rigidStates, &s.step.vectorStates);
  s.step.rigidHistory.resize(step_.vectorHistory.size());
  s.step.vectorHistory.resize(step_.vectorHistory.size());
  for (size_t h = 0; h < step_.vectorHistory.size(); ++h)
    SplitRigid(rigidDesc, step_.vectorHistory[h], &s.step.rigidHistory[h],
               &s.step.vectorHistory[h]);
  return s;
}

void Scene::Restore(const Snapshot& s) {
  step_.time = s.step.time;
  step_.historyTimes = s.step.historyTimes;
  const std::vector<int> rigidDesc = RigidDescs();
  JoinRigid(rigidDesc, s.step.rigidStates, s.step.vectorStates, &step_.vectorStates);
  for (size_t i = 0; i < actors_.size(); ++i)
    if (actors_[i].rigid) HoldStatic(static_cast<int>(i), s.step.rigidStates[actors_[i].desc]);
  step_.vectorHistory.resize(s.step.vectorHistory.size());
  for (size_t h = 0; h < s.step.vectorHistory.size(); ++h)
    JoinRigid(rigidDesc, s.step.rigidHistory[h], s.step.vectorHistory[h],
              &step_.vectorHistory[h]);
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
