#include "core/contact/contact_pipeline.h"

#include <tbb/parallel_for.h>

#include "core/contact/broad_phase.h"

namespace superdex {
namespace {

// Entry k of an optional per-actor list (null without the list).
const Eigen::VectorXd* EntryOf(const std::vector<Eigen::VectorXd>* v, int k) {
  return v ? &(*v)[k] : nullptr;
}

// Below this many tested samples a pair list is evaluated serially.
constexpr size_t kParallelSampleWork = 20000;

// Runs f(0), ..., f(n − 1): in parallel over TBB's workers when `parallel` and n > 1, else in
// order. Each f(k) writes only its own result slot, so the outcome does not depend on the threads.
template <typename F>
void ForEachPair(size_t n, bool parallel, F&& f) {
  if (parallel && n > 1) {
    tbb::parallel_for(size_t(0), n, f);
  } else {
    for (size_t k = 0; k < n; ++k) f(k);
  }
}

/// Adds a stencil pair's counts and energies to *st; returns the energy it adds to the stage value
/// (penalty plus dissipation) [J].
template <typename Stencil>
double AddPairStats(const BasicPairStencils<Stencil>& r, ContactStats* st) {
  double energy = 0.0;
  st->minSignedDistance = std::min(st->minSignedDistance, r.minPhi);
  if (r.activeSamples > 0) {
    ++st->activePairs;
    st->activeSamples += r.activeSamples;
    st->energy += r.penaltyValue;
    energy += r.penaltyValue;
  }
  if (r.dissipativeSamples > 0) {
    st->dissipativeSamples += r.dissipativeSamples;
    st->dissipation += r.dissipationValue;
    st->maxCoulombRatio = std::max(st->maxCoulombRatio, r.maxCoulombRatio);
    energy += r.dissipationValue;
  }
  return energy;
}

/// How far beyond its shape a collider's field can act [m]: a pair is possible when A's samples
/// come within δ of B's shape, and δ comes from the collider (with its padding, never below 0),
/// plus the field's distance error bound.
double ColliderReach(const ContactParams& c) {
  return std::max(0.0, c.penaltyThresholdDefault + c.penaltyThresholdExtraPadding) +
         c.distanceErrorBound;
}

/// Whether a soft colliding actor takes the threshold padding (spec,
/// penaltyThresholdExtraPadding): its own collider is None or PointCloud, not a grid Sdf.
bool PadsThreshold(const SoftBodyModel& A) {
  return A.collider == ColliderType::None || A.collider == ColliderType::PointCloud;
}

/// The penalty part of a pair's combined parameters.
PenaltyParams PenaltyOf(const PairContactParams& p) {
  PenaltyParams pp;
  pp.k = p.penaltyCoefficient;
  pp.eps = p.smoothingHalfDistance;
  pp.delta = p.threshold;
  return pp;
}

}  // namespace

void ContactPipeline::Configure(const ContactFilter* filter,
                                const std::vector<SoftBodyModel>* softModels,
                                std::vector<int> softActor,
                                const std::vector<const ActorKind*>* kinds,
                                std::vector<int> kindActor) {
  kinds_ = kinds && !kinds->empty() ? kinds : nullptr;
  kindActor_ = std::move(kindActor);
  kindInflation_.clear();
  kindHasDofs_.clear();
  kindColliding_.clear();
  kindCollider_.clear();
  kindTetCollider_.clear();
  kindStatic_.clear();
  kindSamples_.clear();
  kindStepLimit_.clear();
  kindFaceSamples_.clear();
  if (kinds_)
    for (const ActorKind* k : *kinds_) {
      const bool tet = k->TetCollider() && k->TetCollider()->collider == ColliderType::Sdf;
      kindInflation_.push_back(k->Collider() || tet ? ColliderReach(k->contact) : 0.0);
      kindCollider_.push_back(k->Collider() != nullptr);
      kindTetCollider_.push_back(tet);
      kindHasDofs_.push_back(k->HasFreeDof());
      kindColliding_.push_back(k->IsColliding());
      kindStatic_.push_back(k->IsStatic());
      size_t samples = static_cast<size_t>(k->NumSamples());
      for (int b = 0; b < k->NumSampleBodies(); ++b) samples += k->SampleBody(b)->samples.size();
      kindSamples_.push_back(samples);
      kindStepLimit_.push_back(k->Shortcuts().stepLimit);
      kindFaceSamples_.push_back(k->NumSamples() > 0 &&
                                 k->Sample(0, k->InitialState().x).faceNormal);
    }
  filter_ = filter;
  softModels_ = softModels && !softModels->empty() ? softModels : nullptr;
  softActor_ = std::move(softActor);
  softInflation_.clear();
  if (softModels_)
    for (const SoftBodyModel& m : *softModels_)
      softInflation_.push_back(m.collider == ColliderType::Sdf ? ColliderReach(m.contact) : 0.0);
}

void ContactPipeline::FindPairs(const SoftView* soft, const KindView* kinds) {
  const size_t ns = soft && softModels_ ? softModels_->size() : 0;
  const size_t nk = kinds && kinds_ ? kinds_->size() : 0;
  boxes_.resize(ns + nk);
  // With dissipation the terms read x_n's geometry too (explicit normals keep the stage-start
  // contacts; the reconstructed load φ + G·(Y_n − Y) can be positive where φ > δ, its bound
  // growing with |Y_n − Y|): the boxes sweep from x_n to x. A soft actor is colliding only
  // (its Sdf collider's reach pads it).
  for (size_t s = 0; s < ns; ++s) {
    boxes_[s] = SoftBounds((*soft->x)[s]);
    if (soft->xLast) boxes_[s].Extend(SoftBounds((*soft->xLast)[s]));
    boxes_[s].Inflate(softInflation_[s]);
  }
  // The generic layer's actors after the soft ones.
  for (size_t k = 0; k < nk; ++k) {
    const ActorKind& kind = *(*kinds_)[k];
    boxes_[ns + k] = kind.Bounds((*kinds->q)[kinds->first + k]);
    if (kinds->qLast) boxes_[ns + k].Extend(kind.Bounds((*kinds->qLast)[k]));
    boxes_[ns + k].Inflate(kindInflation_[k]);
  }
  overlapCache_.Find(boxes_, &overlaps_);
  softColliderPairs_.clear();
  kindPairs_.clear();
  // Soft A on the soft collider B (B's collider is an Sdf grid mapped by its deformation).
  auto softOnSoft = [&](int a, int b) {
    const SoftBodyModel& B = (*softModels_)[b];
    if (B.collider != ColliderType::Sdf || a == b) return;
    if (filter_ && !filter_->Allowed(softActor_[a], softActor_[b])) return;
    SoftColliderPair p;
    p.collidingSoft = true;
    p.colliding = a;
    p.collider = b;
    // Both actors are dynamic.
    const SoftBodyModel& A = (*softModels_)[a];
    p.params = CombineContactParams(A.contact, B.contact, false, PadsThreshold(A));
    softColliderPairs_.push_back(p);
  };
  const int firstKind = static_cast<int>(ns);
  for (const auto& [i, j] : overlaps_) {
    const bool ki = i >= firstKind, kj = j >= firstKind;
    if (ki && kj) {  // two kinds' actors, each on the other's field
      ConsiderKindPair(i - firstKind, j - firstKind);
      ConsiderKindPair(j - firstKind, i - firstKind);
    } else if (kj) {  // soft i and kind j, each on the other's field
      ConsiderSoftPair(i, j - firstKind);
      ConsiderKindOnSoft(j - firstKind, i);
    } else if (ki) {
      ConsiderSoftPair(j, i - firstKind);
      ConsiderKindOnSoft(i - firstKind, j);
    } else {
      softOnSoft(i, j);
      softOnSoft(j, i);
    }
  }
}

void ContactPipeline::ConsiderKindPair(int a, int b) {
  if (a == b) return;  // self-contact of a kind: not in this layer yet
  if (kindTetCollider_[b]) return ConsiderKindOnSoft(a, b, true);
  const ActorKind& A = *(*kinds_)[a];
  const ActorKind& B = *(*kinds_)[b];
  if (!kindColliding_[a] || !kindCollider_[b]) return;
  // Neither has a stage unknown (static, kinematic or all prescribed): nothing to solve for.
  if (!kindHasDofs_[a] && !kindHasDofs_[b]) return;
  if (filter_ && !filter_->Allowed(kindActor_[a], kindActor_[b])) return;
  KindPair p;
  p.a = a;
  p.b = b;
  // A kinematic collider moves: its parameters combine as a dynamic one's (spec: "taken from the
  // colliding actor when the collider is static").
  // The threshold padding applies when A has no collider of its own (spec: None or PointCloud).
  p.params = CombineContactParams(A.contact, B.contact, kindStatic_[b],
                                  !kindCollider_[a] && !kindTetCollider_[a]);
  kindPairs_.push_back(p);
}

void ContactPipeline::ConsiderSoftPair(int s, int b) {
  const ActorKind& kind = *(*kinds_)[b];
  if (kindTetCollider_[b]) {  // on the kind's tet field, as on a soft actor's
    if (filter_ && !filter_->Allowed(softActor_[s], kindActor_[b])) return;
    SoftColliderPair p;
    p.collidingSoft = true;
    p.colliding = s;
    p.colliderKind = true;
    p.collider = b;
    const SoftBodyModel& A = (*softModels_)[s];
    p.params = CombineContactParams(A.contact, kind.contact, false, PadsThreshold(A));
    softColliderPairs_.push_back(p);
    return;
  }
  if (!kindCollider_[b]) return;
  if (filter_ && !filter_->Allowed(softActor_[s], kindActor_[b])) return;
  KindPair p;
  p.aSoft = true;
  p.a = s;
  p.b = b;
  // A kinematic collider moves: its parameters combine as a dynamic one's.
  const SoftBodyModel& A = (*softModels_)[s];
  p.params = CombineContactParams(A.contact, kind.contact, kindStatic_[b], PadsThreshold(A));
  kindPairs_.push_back(p);
}

void ContactPipeline::ConsiderKindOnSoft(int k, int b, bool bKind) {
  const ActorKind& A = *(*kinds_)[k];
  if (bKind ? !kindTetCollider_[b] : (*softModels_)[b].collider != ColliderType::Sdf) return;
  if (!kindColliding_[k]) return;
  if (filter_ && !filter_->Allowed(kindActor_[k], bKind ? kindActor_[b] : softActor_[b])) return;
  SoftColliderPair p;
  p.colliding = k;
  p.colliderKind = bKind;
  p.collider = b;
  // Both move; A's own collider type decides the threshold padding.
  const ContactParams& bContact = bKind ? (*kinds_)[b]->contact : (*softModels_)[b].contact;
  p.params = CombineContactParams(A.contact, bContact, false,
                                  A.Collider() == nullptr && !kindTetCollider_[k]);
  for (p.body = 0; p.body < A.NumSampleBodies(); ++p.body) softColliderPairs_.push_back(p);
  p.body = -1;  // the kind's own samples
  if (A.NumSamples() > 0) softColliderPairs_.push_back(p);
}

void ContactPipeline::BuildLocators(const SoftView* soft, const KindView* kinds, bool last) {
  if (softColliderPairs_.empty()) return;
  const size_t ns = softModels_ ? softModels_->size() : 0;
  const size_t nk = kinds_ ? kinds_->size() : 0;
  locators_.resize(ns);
  locatorsLast_.resize(ns);
  kindLocators_.resize(nk);
  kindLocatorsLast_.resize(nk);
  std::vector<char> built(ns + nk, 0);
  for (const SoftColliderPair& p : softColliderPairs_)
    built[p.colliderKind ? ns + p.collider : p.collider] = 1;
  for (size_t b = 0; b < ns; ++b) {
    if (!built[b]) continue;
    const std::vector<Eigen::Vector4i>& tets = (*softModels_)[b].rest.tets;
    locators_[b].Build((*soft->x)[b], tets);
    if (last && soft->xLast) locatorsLast_[b].Build((*soft->xLast)[b], tets);
  }
  for (size_t k = 0; k < nk; ++k) {
    if (!built[ns + k]) continue;
    const std::vector<Eigen::Vector4i>& tets = (*kinds_)[k]->TetCollider()->rest.tets;
    kindLocators_[k].Build((*kinds->q)[kinds->first + k], tets);
    if (last && kinds->qLast) kindLocatorsLast_[k].Build((*kinds->qLast)[k], tets);
  }
}

void ContactPipeline::SampleBodyOffsets(const KindView& kinds, int k, int body,
                                        int offs[2]) const {
  int dof[2];
  (*kinds_)[k]->SampleBodyDofs(body, dof);
  const std::vector<int>* stageDof = kinds.stageDof ? &(*kinds.stageDof)[k] : nullptr;
  for (int c = 0; c < 2; ++c) offs[c] = stageDof ? (*stageDof)[dof[c]] : -1;
}

void ContactPipeline::SoftColliderInputs(const SoftColliderPair& sp, const SoftView& soft,
                                         const KindView* kinds, bool kindStart, RigidPose* pose,
                                         RigidStageStart* start, CollidingInput* a,
                                         SoftColliderInput* b) const {
  *a = CollidingInput();
  if (sp.collidingSoft) {
    a->soft = &(*softModels_)[sp.colliding];
    a->x = &(*soft.x)[sp.colliding];
    a->xLast = soft.xLast ? &(*soft.xLast)[sp.colliding] : nullptr;
    a->x0 = soft.x0 ? &(*soft.x0)[sp.colliding] : nullptr;
    a->dofOffset = soft.dofOffset ? (*soft.dofOffset)[sp.colliding] : 0;
  } else if (sp.body < 0) {  // a kind's own samples
    a->kind = (*kinds_)[sp.colliding];
    a->stageDof = &(*kinds->stageDof)[sp.colliding];
    a->x = &(*kinds->q)[kinds->first + sp.colliding];
    a->xLast = EntryOf(kinds->qLast, sp.colliding);
    a->x0 = kindStart ? EntryOf(kinds->q0, sp.colliding) : nullptr;
  } else {  // a kind's sample body
    const ActorKind& A = *(*kinds_)[sp.colliding];
    const bool hasStart =
        SampleBodyAt(A, sp.body, (*kinds->q)[kinds->first + sp.colliding],
                     EntryOf(kinds->qLast, sp.colliding),
                     kindStart ? EntryOf(kinds->q0, sp.colliding) : nullptr, pose, start);
    a->rigid = A.SampleBody(sp.body);
    a->pose = pose;
    a->start = hasStart ? start : nullptr;
    SampleBodyOffsets(*kinds, sp.colliding, sp.body, a->bodyOffs);
  }
  *b = SoftColliderInput();
  if (sp.colliderKind) {  // a kind's tet field
    const int k = sp.collider;
    b->model = (*kinds_)[k]->TetCollider();
    b->x = &(*kinds->q)[kinds->first + k];
    b->xLast = EntryOf(kinds->qLast, k);
    b->x0 = kindStart ? EntryOf(kinds->q0, k) : nullptr;
    b->locator = &kindLocators_[k];
    b->locatorLast = kinds->qLast ? &kindLocatorsLast_[k] : &kindLocators_[k];
    b->nodeDof = &(*kinds->stageDof)[k];
    return;
  }
  b->model = &(*softModels_)[sp.collider];
  b->x = &(*soft.x)[sp.collider];
  b->xLast = soft.xLast ? &(*soft.xLast)[sp.collider] : nullptr;
  b->x0 = soft.x0 ? &(*soft.x0)[sp.collider] : nullptr;
  b->locator = &locators_[sp.collider];
  b->locatorLast = soft.xLast ? &locatorsLast_[sp.collider] : &locators_[sp.collider];
  b->dofOffset = soft.dofOffset ? (*soft.dofOffset)[sp.collider] : 0;
}

template <typename Id>
void ContactPipeline::BeginSlips(const DissipationContext* dissipation, SlipPairKind kind,
                                 size_t n, Id id) {
  SlipLists& lists = slipLists_[static_cast<int>(kind)];
  lists.use.clear();  // no slips in use: SlipUse gives every pair none
  if (!dissipation || !dissipation->slips) return;
  lists.use.resize(n);
  if (dissipation->recordSlips) {
    lists.record.assign(n, PairSlips());
    for (size_t k = 0; k < n; ++k) lists.use[k] = {&lists.record[k], true};
    return;
  }
  for (size_t k = 0; k < n; ++k) {
    const std::pair<int, int> p = id(k);
    lists.use[k].slips = dissipation->slips->Find(kind, p.first, p.second);
  }
}

template <typename Id>
void ContactPipeline::EndSlips(const DissipationContext* dissipation, SlipPairKind kind, size_t n,
                               Id id) {
  if (!dissipation || !dissipation->slips || !dissipation->recordSlips) return;
  SlipLists& lists = slipLists_[static_cast<int>(kind)];
  for (size_t k = 0; k < n; ++k) {
    if (lists.record[k].samples.empty()) continue;
    const std::pair<int, int> p = id(k);
    dissipation->slips->Add(kind, p.first, p.second, std::move(lists.record[k]));
  }
}

template <typename Id, typename PairFn>
void ContactPipeline::SweepPairs(const DissipationContext* dissipation, SlipPairKind kind,
                                 size_t n, bool parallel, Id id, PairFn&& evaluate) {
  BeginSlips(dissipation, kind, n, id);
  ForEachPair(n, parallel, evaluate);
  EndSlips(dissipation, kind, n, id);
}

DissipationSetup ContactPipeline::MakeSetup(const PairContactParams& params,
                                            const DissipationContext& dissipation,
                                            bool isotropicFriction) const {
  DissipationSetup setup;
  setup.isotropicFrictionHessian = isotropicFriction;
  setup.mode = dissipation.mode;
  setup.fadeFriction = dissipation.fadeFriction;
  setup.dt = dissipation.dt;
  setup.penalty = PenaltyOf(params);
  setup.coefficients.mu = params.coulombFrictionCoefficient;
  setup.coefficients.ct = params.viscousFrictionCoefficient;
  setup.coefficients.cn = params.normalViscousDampingCoefficient;
  setup.coefficients.vf = params.frictionFalloffVel;
  setup.maxAlignment = params.maxAlignmentNormals;
  setup.frictionWithColliderNormal = params.frictionWithColliderNormal;
  return setup;
}

size_t ContactPipeline::KindPairWork() const {
  size_t work = 0;
  for (const KindPair& kp : kindPairs_) {
    // A soft surface's samples: always in parallel.
    if (kp.aSoft || kindFaceSamples_[kp.a]) return kParallelSampleWork;
    work += kindSamples_[kp.a];
  }
  return work;
}

bool ContactPipeline::SplitLastEvaluation(std::vector<double>* share,
                                          std::vector<std::pair<int, int>>* joins) const {
  if (!softColliderPairs_.empty() || kindResults_.size() != kindPairs_.size()) return false;
  for (const KindPair& kp : kindPairs_)
    if (kp.aSoft) return false;  // soft actors are not split
  // Each pair's values to its first dynamic actor; two dynamic actors with an active sample join.
  for (size_t k = 0; k < kindPairs_.size(); ++k) {
    const KindPair& kp = kindPairs_[k];
    const bool aDynamic = kindHasDofs_[kp.a] != 0, bDynamic = kindHasDofs_[kp.b] != 0;
    WithKindResults(k, [&](const auto& r) {
      if (r.activeSamples == 0 && r.dissipativeSamples == 0) return;
      if (!aDynamic && !bDynamic) return;
      const int owner = aDynamic ? kp.a : kp.b;
      if (r.activeSamples > 0) (*share)[owner] += r.penaltyValue;
      if (r.dissipativeSamples > 0) (*share)[owner] += r.dissipationValue;
      if (aDynamic && bDynamic) joins->emplace_back(kp.a, kp.b);
    });
  }
  return true;
}

void ContactPipeline::StepLimits(const KindView& now, const KindView& next,
                                 std::vector<double>* kindAlpha) {
  if (!kinds_) return;
  kindAlpha->assign(kinds_->size(), 1.0);
  FindPairs(nullptr, &next);
  // Each side at the trial configuration, with the current one as its "last" (the samples'
  // yLast, the frame's last pose).
  kindPairLimits_.resize(kindPairs_.size());
  auto q = [](const KindView& v, int k) -> const Eigen::VectorXd& { return (*v.q)[v.first + k]; };
  auto evaluateKind = [&](size_t k) {
    const KindPair& kp = kindPairs_[k];
    kindPairLimits_[k] = 1.0;
    // Soft nodes take no step limit (SceneStageProblem::LimitStep), nor kinds that refuse it.
    if (kp.aSoft || !kindStepLimit_[kp.a] || !kindStepLimit_[kp.b]) return;
    const PenaltyParams penalty = PenaltyOf(kp.params);
    const FrameSide B = KindFrameSide(*(*kinds_)[kp.b], q(next, kp.b), &q(now, kp.b), nullptr,
                                      (*next.stageDof)[kp.b]);
    const double phiLimit = penalty.delta - 0.5 * penalty.eps;
    StepLimitSink sink(B, penalty);
    GatherKindSamples(*(*kinds_)[kp.a], q(next, kp.a), &q(now, kp.a), nullptr,
                      (*next.stageDof)[kp.a], B, phiLimit, nullptr, &sink);
    kindPairLimits_[k] = sink.Alpha();
  };
  ForEachPair(kindPairs_.size(), KindPairWork() >= kParallelSampleWork, evaluateKind);
  for (size_t k = 0; k < kindPairs_.size(); ++k) {
    const KindPair& kp = kindPairs_[k];
    if (kp.aSoft || kindPairLimits_[k] >= 1.0) continue;
    double& a = (*kindAlpha)[kp.a];
    a = std::min(a, kindPairLimits_[k]);
    double& b = (*kindAlpha)[kp.b];
    b = std::min(b, kindPairLimits_[k]);
  }
}

template <typename Stencils>
void ContactPipeline::ReducePair(const Request& q, const Stencils& r, bool aSoft, int a, int b,
                                 double* energy, ContactStats* st, const int* aOffs) const {
  ++st->candidatePairs;
  *energy += AddPairStats(r, st);
  if (q.order < 1) return;
  const SoftView* soft = q.soft;
  // A node's 3-dof block (−1: a prescribed node).
  auto node = [&](int actor, int vertex) {
    const int free = (*softModels_)[actor].freeIndex[vertex];
    return free < 0 ? -1 : (*soft->dofOffset)[actor] + 3 * free;
  };
  for (int e = 0; e < r.count; ++e) {
    const auto& cs = r.stencils[e];
    if (cs.blocks > 0) {
      int offs6[4];  // ContactStencil::offs holds 8 blocks
      if ((q.order < 2 || q.blocks) && SixDofGroups(cs.offs, cs.blocks, offs6)) {
        ScatterStencil6(cs, offs6, cs.blocks / 2, q.potential, q.gradient, q.dissipationResidual,
                        q.order >= 2 ? q.blocks : nullptr);
      } else {
        ScatterStencil(cs, cs.offs, cs.blocks, q.potential, q.gradient, q.dissipationResidual,
                       q.order >= 2 ? q.triplets : nullptr);
      }
      continue;
    }
    // A pair on a soft collider's field: A's face nodes or sample body's [δp, δθ], B's tet nodes.
    int offs[7];
    int blocks = 0;
    if (aSoft) {  // the face's three nodes
      for (int c = 0; c < 3; ++c) offs[blocks++] = node(a, (*softModels_)[a].faces[cs.aFace][c]);
    } else {  // a kind's sample body's [δp, δθ]
      offs[blocks++] = aOffs[0];
      offs[blocks++] = aOffs[1];
    }
    for (int c = 0; c < 4; ++c) offs[blocks++] = node(b, (*softModels_)[b].rest.tets[cs.bTet][c]);
    ScatterStencil(cs, offs, blocks, q.potential, q.gradient, q.dissipationResidual,
                   q.order >= 2 ? q.triplets : nullptr);
  }
}

double ContactPipeline::Evaluate(int order, PsdProjection projection, Eigen::VectorXd* gradient,
                                 std::vector<Eigen::Triplet<double>>* triplets,
                                 std::vector<DenseBlock6>* blockOut, ContactStats* stats,
                                 const DissipationContext* dissipation,
                                 Eigen::VectorXd* dissipationResidual, const SoftView* soft,
                                 const KindView* kinds) {
  FindPairs(soft, kinds);
  Request q;
  q.order = order;
  q.projection = projection;
  q.gradient = gradient;
  q.triplets = triplets;
  q.blocks = blockOut;
  q.dissipation = dissipation;
  q.dissipationResidual = dissipationResidual;
  q.soft = soft;
  q.kinds = kinds;
  q.potential = !dissipation || dissipation->mode == DissipationMode::ExplicitNormals;
  // Projected Hessians are the globalization model: the Coulomb term's isotropic majorizer.
  q.isotropic = q.potential && projection != PsdProjection::None;
  if (dissipation && dissipation->slips && dissipation->recordSlips) dissipation->slips->Clear();
  // Each pair kind in parallel over its pairs, then reduced in a fixed order into one sum.
  double energy = 0.0;
  ContactStats st;
  EvaluateKindPairs(q, &energy, &st);
  EvaluateOnSoftPairs(q, &energy, &st);
  if (dissipation && dissipation->slips && dissipation->recordSlips) dissipation->slips->Seal();
  if (stats) *stats = st;
  return energy;
}

void ContactPipeline::EvaluateOnSoftPairs(const Request& q, double* energy, ContactStats* st) {
  const SoftView* soft = q.soft;
  const DissipationContext* dissipation = q.dissipation;
  // Colliding ids: soft actors (−1 − s), kinds' own samples (k), their sample bodies
  // (k + nk (b + 1)).
  const int nk = static_cast<int>(kinds_ ? kinds_->size() : 0);
  // Collider ids: soft actors (s), kinds' tet fields (−1 − k).
  const auto onSoftId = [&](size_t k) {
    const SoftColliderPair& p = softColliderPairs_[k];
    return std::make_pair(p.collidingSoft ? -1 - p.colliding : p.colliding + nk * (p.body + 1),
                          p.colliderKind ? -1 - p.collider : p.collider);
  };
  // Samples of soft actors and kinds on soft colliders' fields, one stencil per sample.
  BuildLocators(soft, q.kinds, true);
  softColliderResults_.resize(softColliderPairs_.size());
  auto evaluateOnSoft = [&](size_t k) {
    const SoftColliderPair& sp = softColliderPairs_[k];
    const PenaltyParams pp = PenaltyOf(sp.params);
    CollidingInput a;
    SoftColliderInput b;
    RigidPose pose;
    RigidStageStart start;
    SoftColliderInputs(sp, soft ? *soft : SoftView(), q.kinds, dissipation != nullptr, &pose, &start, &a, &b);
    DissipationSetup setup;
    if (dissipation) setup = MakeSetup(sp.params, *dissipation, q.isotropic);
    setup.slips = SlipUse(SlipPairKind::OnSoft, k);
    PairStencils& r = softColliderResults_[k];
    EvaluatePairOnSoftCollider(a, b, pp, sp.params.maxAlignmentNormals,
                               dissipation ? &setup : nullptr, q.order, &r);
    if (q.order < 2) return;
    for (int e = 0; e < r.count; ++e) ProjectStencil(q.potential, q.projection, &r.stencils[e]);
  };
  SweepPairs(dissipation, SlipPairKind::OnSoft, softColliderPairs_.size(), true, onSoftId,
             evaluateOnSoft);
  for (size_t k = 0; k < softColliderPairs_.size(); ++k) {
    const SoftColliderPair& sp = softColliderPairs_[k];
    int aOffs[2] = {-1, -1};
    if (!sp.collidingSoft && sp.body >= 0)
      SampleBodyOffsets(*q.kinds, sp.colliding, sp.body, aOffs);
    ReducePair(q, softColliderResults_[k], sp.collidingSoft, sp.colliding, sp.collider, energy,
               st, aOffs);
  }
}

SoftPairInput ContactPipeline::SoftInputOf(const SoftView& soft, int s) const {
  SoftPairInput in;
  in.model = &(*softModels_)[s];
  in.x = &(*soft.x)[s];
  in.xLast = EntryOf(soft.xLast, s);
  in.x0 = EntryOf(soft.x0, s);
  in.dofOffset = soft.dofOffset ? (*soft.dofOffset)[s] : 0;  // none: value only
  return in;
}

void ContactPipeline::FormKindSides(const Request& q) {
  if (!kinds_ || !q.kinds) return;
  const size_t nk = kinds_->size();
  kindRoles_.assign(nk, 0);
  for (const KindPair& kp : kindPairs_) {
    kindRoles_[kp.b] |= 1;
    if (!kp.aSoft) kindRoles_[kp.a] |= 2;
  }
  kindSides_.resize(nk);
  kindBodies_.resize(nk);
  const KindView& kv = *q.kinds;
  for (size_t k = 0; k < nk; ++k) {
    if (!kindRoles_[k]) continue;
    const ActorKind& kind = *(*kinds_)[k];
    const Eigen::VectorXd& x = (*kv.q)[kv.first + k];
    const Eigen::VectorXd* x0 = q.dissipation ? EntryOf(kv.q0, k) : nullptr;  // with dissipation
    if (kindRoles_[k] & 1)
      kindSides_[k] = KindFrameSide(kind, x, EntryOf(kv.qLast, k), x0, (*kv.stageDof)[k]);
    if ((kindRoles_[k] & 2) && kind.NumSampleBodies() > 0)
      kindBodies_[k].Form(kind, x, EntryOf(kv.qLast, k), x0);
  }
}

void ContactPipeline::GatherKindPairSamples(const Request& q, const KindPair& kp,
                                            const FrameSide& B, const DissipationSetup* setup,
                                            SampleSink* sink) const {
  if (kp.aSoft) {  // x⁰ is read only with dissipation (setup)
    GatherSoftSamples(SoftInputOf(*q.soft, kp.a), B, kp.params.threshold, setup, sink);
    return;
  }
  const KindView& kv = *q.kinds;
  GatherKindSamples(*(*kinds_)[kp.a], (*kv.q)[kv.first + kp.a], EntryOf(kv.qLast, kp.a),
                    q.dissipation ? EntryOf(kv.q0, kp.a) : nullptr, (*kv.stageDof)[kp.a], B,
                    kp.params.threshold, setup, sink, &kindBodies_[kp.a]);
}

void ContactPipeline::EvaluateKindPairs(const Request& q, double* energy, ContactStats* st) {
  const DissipationContext* dissipation = q.dissipation;
  kindResults_.resize(kindPairs_.size());
  kindWideResults_.resize(kindPairs_.size());
  kindWide_.resize(kindPairs_.size());
  FormKindSides(q);
  auto evaluate = [&](size_t k) {
    const KindPair& kp = kindPairs_[k];
    DissipationSetup setup;
    if (dissipation) setup = MakeSetup(kp.params, *dissipation, q.isotropic);
    setup.slips = SlipUse(SlipPairKind::Kind, k);
    const FrameSide& B = kindSides_[kp.b];
    // Evaluated into the worker's own stencils, then kept in the pair's compact ones where they
    // fit (a pair of rigid bodies' [δp, δθ]: the memory the sweeps touch is a quarter).
    static thread_local PairStencils scratch;
    FrameEvaluation evaluation(B, PenaltyOf(kp.params), kp.params.maxAlignmentNormals,
                               dissipation ? &setup : nullptr, q.order, &scratch);
    GatherKindPairSamples(q, kp, B, dissipation ? &setup : nullptr, &evaluation);
    evaluation.Finish();
    bool fits = true;
    for (int e = 0; e < scratch.count; ++e) {
      if (3 * scratch.stencils[e].blocks > kMaxSmallStencil) fits = false;
      if (q.order >= 2) ProjectStencil(q.potential, q.projection, &scratch.stencils[e]);
    }
    kindWide_[k] = !fits;
    if (fits)
      kindResults_[k].CopyFrom(scratch, q.order);
    else
      kindWideResults_[k].CopyFrom(scratch, q.order);
  };
  const int nk = static_cast<int>(kinds_ ? kinds_->size() : 0);
  auto kindId = [&](size_t k) {  // kinds, then soft actors
    const KindPair& kp = kindPairs_[k];
    return std::make_pair(kp.aSoft ? nk + kp.a : kp.a, kp.b);
  };
  SweepPairs(dissipation, SlipPairKind::Kind, kindPairs_.size(),
             KindPairWork() >= kParallelSampleWork, kindId, evaluate);
  for (size_t k = 0; k < kindPairs_.size(); ++k)
    WithKindResults(k, [&](const auto& r) { ReducePair(q, r, false, -1, -1, energy, st); });
}

void ContactPipeline::CollectSamples(std::vector<ContactSampleRecord>* records,
                                     const SoftView* soft, const KindView* kinds,
                                     const DissipationContext* dissipation) {
  FindPairs(soft, kinds);
  records->clear();
  auto setupOf = [&](const PairContactParams& params) {
    return dissipation ? MakeSetup(params, *dissipation, false) : DissipationSetup();
  };
  BuildLocators(soft, kinds, false);
  PairStencils scratchOnSoft;
  for (const SoftColliderPair& sp : softColliderPairs_) {
    const PenaltyParams pp = PenaltyOf(sp.params);
    CollidingInput a;
    SoftColliderInput b;
    RigidPose pose;
    RigidStageStart start;
    SoftColliderInputs(sp, soft ? *soft : SoftView(), kinds, false, &pose, &start, &a, &b);
    const size_t first = records->size();
    EvaluatePairOnSoftCollider(a, b, pp, sp.params.maxAlignmentNormals, nullptr, 0, &scratchOnSoft,
                               records);
    for (size_t k = first; k < records->size(); ++k) {
      (*records)[k].colliding =
          sp.collidingSoft ? softActor_[sp.colliding] : kindActor_[sp.colliding];
      (*records)[k].collider =
          sp.colliderKind ? kindActor_[sp.collider] : softActor_[sp.collider];
    }
  }
  Request q;
  q.kinds = kinds;
  q.soft = soft;
  q.dissipation = dissipation;
  PairStencils scratchKind;
  FormKindSides(q);
  for (const KindPair& kp : kindPairs_) {
    const FrameSide& B = kindSides_[kp.b];
    const DissipationSetup setup = setupOf(kp.params);
    const size_t first = records->size();
    FrameEvaluation evaluation(B, PenaltyOf(kp.params), kp.params.maxAlignmentNormals,
                               dissipation ? &setup : nullptr, 0, &scratchKind, records);
    GatherKindPairSamples(q, kp, B, dissipation ? &setup : nullptr, &evaluation);
    evaluation.Finish();
    for (size_t k = first; k < records->size(); ++k) {
      (*records)[k].colliding = kp.aSoft ? softActor_[kp.a] : kindActor_[kp.a];
      (*records)[k].collider = kindActor_[kp.b];
    }
  }
}

}  // namespace superdex
