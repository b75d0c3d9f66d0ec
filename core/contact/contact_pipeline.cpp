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
}

void ContactPipeline::FindPairs(const KindView* kinds) {
  const size_t nk = kinds && kinds_ ? kinds_->size() : 0;
  boxes_.resize(nk);
  // With dissipation the terms read x_n's geometry too (explicit normals keep the stage-start
  // contacts; the reconstructed load φ + G·(Y_n − Y) can be positive where φ > δ, its bound
  // growing with |Y_n − Y|): the boxes sweep from x_n to x, padded by the actor's collider reach.
  for (size_t k = 0; k < nk; ++k) {
    const ActorKind& kind = *(*kinds_)[k];
    boxes_[k] = kind.Bounds((*kinds->q)[k]);
    if (kinds->qLast) boxes_[k].Extend(kind.Bounds((*kinds->qLast)[k]));
    boxes_[k].Inflate(kindInflation_[k]);
  }
  overlapCache_.Find(boxes_, &overlaps_);
  softColliderPairs_.clear();
  kindPairs_.clear();
  for (const auto& [i, j] : overlaps_) {  // each on the other's field
    ConsiderKindPair(i, j);
    ConsiderKindPair(j, i);
  }
}

void ContactPipeline::ConsiderKindPair(int a, int b) {
  if (a == b) return;  // self-contact of a kind: not in this layer yet
  if (kindTetCollider_[b]) return ConsiderKindOnTetField(a, b);
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
  p.params = CombineContactParams(A.contact, B.contact, kindStatic_[b], PadsThreshold(a));
  kindPairs_.push_back(p);
}

void ContactPipeline::ConsiderKindOnTetField(int k, int b) {
  const ActorKind& A = *(*kinds_)[k];
  if (!kindColliding_[k]) return;
  if (filter_ && !filter_->Allowed(kindActor_[k], kindActor_[b])) return;
  SoftColliderPair p;
  p.colliding = k;
  p.collider = b;
  // Both move.
  p.params = CombineContactParams(A.contact, (*kinds_)[b]->contact, false, PadsThreshold(k));
  for (p.body = 0; p.body < A.NumSampleBodies(); ++p.body) softColliderPairs_.push_back(p);
  p.body = -1;  // the kind's own samples
  if (A.NumSamples() > 0) softColliderPairs_.push_back(p);
}

void ContactPipeline::BuildLocators(const KindView& kinds, bool last) {
  if (softColliderPairs_.empty()) return;
  const size_t nk = kinds_->size();
  kindLocators_.resize(nk);
  kindLocatorsLast_.resize(nk);
  locatorBuilt_.assign(nk, 0);
  for (const SoftColliderPair& p : softColliderPairs_) {
    if (locatorBuilt_[p.collider]) continue;
    locatorBuilt_[p.collider] = 1;
    const std::vector<Eigen::Vector4i>& tets = (*kinds_)[p.collider]->TetCollider()->rest.tets;
    kindLocators_[p.collider].Build((*kinds.q)[p.collider], tets);
    if (last && kinds.qLast) kindLocatorsLast_[p.collider].Build((*kinds.qLast)[p.collider], tets);
  }
}

void ContactPipeline::SampleBodyOffsets(const KindView& kinds, int k, int body,
                                        int offs[2]) const {
  int dof[2];
  (*kinds_)[k]->SampleBodyDofs(body, dof);
  const std::vector<int>* stageDof = kinds.stageDof ? &(*kinds.stageDof)[k] : nullptr;
  for (int c = 0; c < 2; ++c) offs[c] = stageDof ? (*stageDof)[dof[c]] : -1;
}

void ContactPipeline::SoftColliderInputs(const SoftColliderPair& sp, const KindView& kinds,
                                         bool kindStart, RigidPose* pose, RigidStageStart* start,
                                         CollidingInput* a, SoftColliderInput* b) const {
  *a = CollidingInput();
  const int k = sp.colliding;
  if (sp.body < 0) {  // a kind's own samples
    a->kind = (*kinds_)[k];
    a->stageDof = &(*kinds.stageDof)[k];
    a->x = &(*kinds.q)[k];
    a->xLast = EntryOf(kinds.qLast, k);
    a->x0 = kindStart ? EntryOf(kinds.q0, k) : nullptr;
  } else {  // a kind's sample body
    const ActorKind& A = *(*kinds_)[k];
    const bool hasStart = SampleBodyAt(A, sp.body, (*kinds.q)[k], EntryOf(kinds.qLast, k),
                                       kindStart ? EntryOf(kinds.q0, k) : nullptr, pose, start);
    a->rigid = A.SampleBody(sp.body);
    a->pose = pose;
    a->start = hasStart ? start : nullptr;
    SampleBodyOffsets(kinds, k, sp.body, a->bodyOffs);
  }
  *b = SoftColliderInput();
  const int c = sp.collider;
  b->model = (*kinds_)[c]->TetCollider();
  b->x = &(*kinds.q)[c];
  b->xLast = EntryOf(kinds.qLast, c);
  b->x0 = kindStart ? EntryOf(kinds.q0, c) : nullptr;
  b->locator = &kindLocators_[c];
  b->locatorLast = kinds.qLast ? &kindLocatorsLast_[c] : &kindLocators_[c];
  b->nodeDof = &(*kinds.stageDof)[c];
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
    // A deforming surface's samples: always in parallel.
    if (kindFaceSamples_[kp.a]) return kParallelSampleWork;
    work += kindSamples_[kp.a];
  }
  return work;
}

bool ContactPipeline::SplitLastEvaluation(std::vector<double>* share,
                                          std::vector<std::pair<int, int>>* joins) const {
  if (!softColliderPairs_.empty() || kindResults_.size() != kindPairs_.size()) return false;
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
  FindPairs(&next);
  // Each side at the trial configuration, with the current one as its "last" (the samples'
  // yLast, the frame's last pose).
  kindPairLimits_.resize(kindPairs_.size());
  auto q = [](const KindView& v, int k) -> const Eigen::VectorXd& { return (*v.q)[k]; };
  auto evaluateKind = [&](size_t k) {
    const KindPair& kp = kindPairs_[k];
    kindPairLimits_[k] = 1.0;
    if (!kindStepLimit_[kp.a] || !kindStepLimit_[kp.b]) return;  // ActorKind::Shortcuts
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
    if (kindPairLimits_[k] >= 1.0) continue;
    double& a = (*kindAlpha)[kp.a];
    a = std::min(a, kindPairLimits_[k]);
    double& b = (*kindAlpha)[kp.b];
    b = std::min(b, kindPairLimits_[k]);
  }
}

template <typename Stencils>
void ContactPipeline::ReducePair(const Request& q, const Stencils& r, double* energy,
                                 ContactStats* st) const {
  ++st->candidatePairs;
  *energy += AddPairStats(r, st);
  if (q.order < 1) return;
  for (int e = 0; e < r.count; ++e) {
    const auto& cs = r.stencils[e];
    int offs6[4];  // ContactStencil::offs holds 8 blocks
    if ((q.order < 2 || q.blocks) && SixDofGroups(cs.offs, cs.blocks, offs6)) {
      ScatterStencil6(cs, offs6, cs.blocks / 2, q.potential, q.gradient, q.dissipationResidual,
                      q.order >= 2 ? q.blocks : nullptr);
    } else {
      ScatterStencil(cs, cs.offs, cs.blocks, q.potential, q.gradient, q.dissipationResidual,
                     q.order >= 2 ? q.triplets : nullptr);
    }
  }
}

double ContactPipeline::Evaluate(int order, PsdProjection projection, Eigen::VectorXd* gradient,
                                 std::vector<Eigen::Triplet<double>>* triplets,
                                 std::vector<DenseBlock6>* blockOut, ContactStats* stats,
                                 const DissipationContext* dissipation,
                                 Eigen::VectorXd* dissipationResidual, const KindView* kinds) {
  FindPairs(kinds);
  Request q;
  q.order = order;
  q.projection = projection;
  q.gradient = gradient;
  q.triplets = triplets;
  q.blocks = blockOut;
  q.dissipation = dissipation;
  q.dissipationResidual = dissipationResidual;
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
  if (softColliderPairs_.empty()) return;
  const DissipationContext* dissipation = q.dissipation;
  // Colliding ids: a kind's own samples k, its sample bodies k + nk (b + 1); collider: the kind.
  const int nk = static_cast<int>(kinds_->size());
  const auto onSoftId = [&](size_t k) {
    const SoftColliderPair& p = softColliderPairs_[k];
    return std::make_pair(p.colliding + nk * (p.body + 1), p.collider);
  };
  // Samples of kinds on tet fields, one stencil per sample.
  BuildLocators(*q.kinds, true);
  softColliderResults_.resize(softColliderPairs_.size());
  auto evaluateOnSoft = [&](size_t k) {
    const SoftColliderPair& sp = softColliderPairs_[k];
    const PenaltyParams pp = PenaltyOf(sp.params);
    CollidingInput a;
    SoftColliderInput b;
    RigidPose pose;
    RigidStageStart start;
    SoftColliderInputs(sp, *q.kinds, dissipation != nullptr, &pose, &start, &a, &b);
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
  for (size_t k = 0; k < softColliderPairs_.size(); ++k)
    ReducePair(q, softColliderResults_[k], energy, st);
}

void ContactPipeline::FormKindSides(const Request& q) {
  if (!kinds_ || !q.kinds) return;
  const size_t nk = kinds_->size();
  kindRoles_.assign(nk, 0);
  for (const KindPair& kp : kindPairs_) {
    kindRoles_[kp.b] |= 1;
    kindRoles_[kp.a] |= 2;
  }
  kindSides_.resize(nk);
  kindBodies_.resize(nk);
  const KindView& kv = *q.kinds;
  for (size_t k = 0; k < nk; ++k) {
    if (!kindRoles_[k]) continue;
    const ActorKind& kind = *(*kinds_)[k];
    const Eigen::VectorXd& x = (*kv.q)[k];
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
  const KindView& kv = *q.kinds;
  GatherKindSamples(*(*kinds_)[kp.a], (*kv.q)[kp.a], EntryOf(kv.qLast, kp.a),
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
  auto kindId = [&](size_t k) { return std::make_pair(kindPairs_[k].a, kindPairs_[k].b); };
  SweepPairs(dissipation, SlipPairKind::Kind, kindPairs_.size(),
             KindPairWork() >= kParallelSampleWork, kindId, evaluate);
  for (size_t k = 0; k < kindPairs_.size(); ++k)
    WithKindResults(k, [&](const auto& r) { ReducePair(q, r, energy, st); });
}

void ContactPipeline::CollectSamples(std::vector<ContactSampleRecord>* records,
                                     const KindView* kinds,
                                     const DissipationContext* dissipation) {
  FindPairs(kinds);
  records->clear();
  auto setupOf = [&](const PairContactParams& params) {
    return dissipation ? MakeSetup(params, *dissipation, false) : DissipationSetup();
  };
  if (!softColliderPairs_.empty()) BuildLocators(*kinds, false);
  PairStencils scratchOnSoft;
  for (const SoftColliderPair& sp : softColliderPairs_) {
    const PenaltyParams pp = PenaltyOf(sp.params);
    CollidingInput a;
    SoftColliderInput b;
    RigidPose pose;
    RigidStageStart start;
    SoftColliderInputs(sp, *kinds, false, &pose, &start, &a, &b);
    const size_t first = records->size();
    EvaluatePairOnSoftCollider(a, b, pp, sp.params.maxAlignmentNormals, nullptr, 0, &scratchOnSoft,
                               records);
    for (size_t k = first; k < records->size(); ++k) {
      (*records)[k].colliding = kindActor_[sp.colliding];
      (*records)[k].collider = kindActor_[sp.collider];
    }
  }
  Request q;
  q.kinds = kinds;
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
      (*records)[k].colliding = kindActor_[kp.a];
      (*records)[k].collider = kindActor_[kp.b];
    }
  }
}

}  // namespace superdex
