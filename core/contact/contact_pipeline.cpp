#include "core/contact/contact_pipeline.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>

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
  kindCloud_.clear();
  kindCloudSelf_.clear();
  cloudSamples_.clear();  // their reference places are the kinds'
  cloudPoints_.clear();
  kindTetFields_.clear();
  staticSides_.clear();  // the kinds may be new ones
  pairsFormed_ = false;
  if (kinds_)
    for (const ActorKind* k : *kinds_) {
      const bool tet = k->TetCollider() && k->TetCollider()->collider == ColliderType::Sdf;
      // The reference grid of a tet field as a field (the pullback is the tet's).
      RigidCollider field;
      if (tet) {
        field.type = ColliderType::Sdf;
        field.grid = k->TetCollider()->colliderGrid;
        field.lipschitz = std::sqrt(3.0);
        field.boundingRadius = INFINITY;
      }
      kindTetFields_.push_back(field);
      const PointCloudColliderParams* cloud = k->PointCloud();
      kindCloud_.push_back(cloud != nullptr);
      kindCloudSelf_.push_back(cloud && cloud->selfContact);
      // A point cloud's spheres reach L_B beyond its points.
      kindInflation_.push_back(k->Collider() || tet ? ColliderReach(k->contact)
                               : cloud          ? cloud->radius + ColliderReach(k->contact)
                                                : 0.0);
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
  // The eligible pairs and their combined parameters depend on the overlaps, the filter and the
  // kinds (Configure) only.
  const long version = filter_ ? filter_->Version() : 0;
  if (pairsFormed_ && version == pairFilterVersion_ && overlaps_ == pairOverlaps_) return;
  kindPairs_.clear();
  for (const auto& [i, j] : overlaps_) {  // each on the other's field
    ConsiderKindPair(i, j);
    ConsiderKindPair(j, i);
  }
  for (size_t k = 0; k < nk; ++k)
    if (kindCloudSelf_[k]) ConsiderKindPair(static_cast<int>(k), static_cast<int>(k));
  pairOverlaps_ = overlaps_;
  pairFilterVersion_ = version;
  pairsFormed_ = true;
}

void ContactPipeline::ConsiderKindPair(int a, int b) {
  const ActorKind& A = *(*kinds_)[a];
  const ActorKind& B = *(*kinds_)[b];
  const bool tet = kindTetCollider_[b] != 0;
  // Point clouds meet point clouds only (spec), themselves only with selfContact.
  const bool cloud = kindCloud_[a] && kindCloud_[b] && (a != b || kindCloudSelf_[b]);
  if (!kindColliding_[a] || !(kindCollider_[b] || tet || cloud)) return;
  // Neither has a stage unknown (static, kinematic or all prescribed): nothing to solve for.
  if (!kindHasDofs_[a] && !kindHasDofs_[b]) return;
  if (filter_ && !filter_->Allowed(kindActor_[a], kindActor_[b])) return;
  if (cloud) return AddCloudPieces(a, b, CombineContactParams(A.contact, B.contact, false, true));
  KindPair p;
  p.a = a;
  p.b = b;
  // A kinematic collider moves: its parameters combine as a dynamic one's (spec: "taken from the
  // colliding actor when the collider is static"); a tet field always moves.
  // The threshold padding applies when A has no collider of its own (spec: None or PointCloud).
  p.params = CombineContactParams(A.contact, B.contact, !tet && kindStatic_[b], PadsThreshold(a));
  kindPairs_.push_back(p);
}

void ContactPipeline::AddCloudPieces(int a, int b, const PairContactParams& params) {
  const int n = (*kinds_)[b]->NumCloudPoints();
  for (int begin = 0; begin < n; begin += kCloudPiece) {
    KindPair p;
    p.a = a;
    p.b = b;
    p.params = params;
    p.cloudBegin = begin;
    p.cloudEnd = std::min(n, begin + kCloudPiece);
    kindPairs_.push_back(p);
  }
}

void ContactPipeline::EvaluateCloudPiece(const KindView& kv, const KindPair& kp,
                                         const DissipationSetup* setup, int order,
                                         PairStencils* out,
                                         std::vector<ContactSampleRecord>* records) const {
  out->Reset();
  const PointCloudColliderParams& cloud = *(*kinds_)[kp.b]->PointCloud();
  EvaluateCloudPoints(cloudSamples_[kp.a], cloudPoints_[kp.b], (*kv.stageDof)[kp.b], kp.a == kp.b,
                      cloud.selfContactExclusionRatio, kp.cloudBegin, kp.cloudEnd,
                      PenaltyOf(kp.params), setup, order, out, records);
}

FrameSide ContactPipeline::TetSide(const KindView& kinds, int k,
                                   const DissipationContext* dissipation) {
  TetFieldSide& tet = kindTetSides_[k];
  tet.model = (*kinds_)[k]->TetCollider();
  tet.x = &(*kinds.q)[k];
  tet.xLast = kinds.qLast ? &(*kinds.qLast)[k] : tet.x;
  tet.x0 = dissipation ? EntryOf(kinds.q0, k) : nullptr;
  tet.nodeDof = &(*kinds.stageDof)[k];
  kindLocators_[k].Build(*tet.x, tet.model->rest.tets);
  tet.locator = &kindLocators_[k];
  tet.locatorLast = tet.locator;
  // Explicit normals locate the samples' x_n points at x_n.
  if (dissipation && dissipation->mode == DissipationMode::ExplicitNormals && kinds.qLast) {
    kindLocatorsLast_[k].Build(*tet.xLast, tet.model->rest.tets);
    tet.locatorLast = &kindLocatorsLast_[k];
  }
  tet.FormBoxes();
  FrameSide side;
  side.motion = FrameSide::Motion::Tet;
  side.field = &kindTetFields_[k];
  side.tet = &tet;
  side.hasLast = true;
  side.hasStart = tet.x0 != nullptr;
  return side;
}

void ContactPipeline::BeginSlips(const DissipationContext* dissipation) {
  slipUse_.clear();  // no slips in use: SlipUse gives every pair none
  if (!dissipation || !dissipation->slips) return;
  const size_t n = kindPairs_.size();
  slipUse_.resize(n);
  if (dissipation->recordSlips) {
    slipRecord_.assign(n, PairSlips());
    for (size_t k = 0; k < n; ++k) slipUse_[k] = {&slipRecord_[k], true};
    return;
  }
  for (size_t k = 0; k < n; ++k)
    slipUse_[k].slips = dissipation->slips->Find(kindPairs_[k].a, kindPairs_[k].b);
}

void ContactPipeline::EndSlips(const DissipationContext* dissipation) {
  if (!dissipation || !dissipation->slips || !dissipation->recordSlips) return;
  for (size_t k = 0; k < kindPairs_.size(); ++k) {
    if (slipRecord_[k].samples.empty()) continue;
    dissipation->slips->Add(kindPairs_[k].a, kindPairs_[k].b, std::move(slipRecord_[k]));
  }
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
    // A deforming surface's samples, or a tet field's pullbacks: always in parallel.
    if (kindFaceSamples_[kp.a] || kindTetCollider_[kp.b] || kp.Cloud()) return kParallelSampleWork;
    work += kindSamples_[kp.a];
  }
  return work;
}

bool ContactPipeline::SplitLastEvaluation(std::vector<double>* share,
                                          std::vector<std::pair<int, int>>* joins) const {
  if (evaluatedTetPairs_ || kindResults_.size() != kindPairs_.size()) return false;
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
    if (kindTetCollider_[kp.b] || kp.Cloud()) return;  // none on a tet field or a point cloud
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
  evaluatedTetPairs_ = std::any_of(kindPairs_.begin(), kindPairs_.end(),
                                   [&](const KindPair& kp) { return kindTetCollider_[kp.b] != 0; });
  if (dissipation && dissipation->slips && dissipation->recordSlips) dissipation->slips->Seal();
  if (stats) *stats = st;
  return energy;
}

void ContactPipeline::FormKindSides(const Request& q) {
  if (!kinds_ || !q.kinds) return;
  const size_t nk = kinds_->size();
  kindRoles_.assign(nk, 0);
  cloudSamples_.resize(nk);
  cloudPoints_.resize(nk);
  std::vector<double>& cell = cloudCell_;
  cell.assign(nk, 0.0);
  for (const KindPair& kp : kindPairs_) {
    if (kp.Cloud()) {  // the hash's cells: the largest reach L_B + δ of A's pairs
      kindRoles_[kp.b] |= 4;
      kindRoles_[kp.a] |= 8;
      cell[kp.a] = std::max(cell[kp.a], (*kinds_)[kp.b]->PointCloud()->radius + kp.params.threshold);
      continue;
    }
    kindRoles_[kp.b] |= 1;
    kindRoles_[kp.a] |= 2;
  }
  kindSides_.resize(nk);
  staticSides_.resize(nk);
  kindBodies_.resize(nk);
  kindTetSides_.resize(nk);  // sized before TetSide points into it
  kindLocators_.resize(nk);
  kindLocatorsLast_.resize(nk);
  const KindView& kv = *q.kinds;
  for (size_t k = 0; k < nk; ++k) {
    if (!kindRoles_[k]) continue;
    const ActorKind& kind = *(*kinds_)[k];
    const Eigen::VectorXd& x = (*kv.q)[k];
    const Eigen::VectorXd* x0 = q.dissipation ? EntryOf(kv.q0, k) : nullptr;  // with dissipation
    if ((kindRoles_[k] & 1) && kindTetCollider_[k])
      kindSides_[k] = TetSide(kv, k, q.dissipation);
    else if ((kindRoles_[k] & 1) && kindStatic_[k])
      FormStaticSide(k, x, EntryOf(kv.qLast, k), x0, (*kv.stageDof)[k]);
    else if (kindRoles_[k] & 1)
      FormKindFrameSide(kind, x, EntryOf(kv.qLast, k), x0, (*kv.stageDof)[k], &kindSides_[k]);
    if ((kindRoles_[k] & 2) && kind.NumSampleBodies() > 0)
      kindBodies_[k].Form(kind, x, EntryOf(kv.qLast, k), x0);
    if (kindRoles_[k] & 4)
      cloudPoints_[k].Form(kind, x, EntryOf(kv.qLast, k), x0, kindCloudSelf_[k]);
    if (kindRoles_[k] & 8)
      cloudSamples_[k].Form(kind, x, EntryOf(kv.qLast, k), x0, (*kv.stageDof)[k], cell[k],
                            kind.PointCloud()->spatialHashLoadFactor, kindCloudSelf_[k]);
  }
}

void ContactPipeline::FormStaticSide(int k, const Eigen::VectorXd& x, const Eigen::VectorXd* qLast,
                                     const Eigen::VectorXd* x0, const std::vector<int>& stageDof) {
  auto same = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
  };
  FrameSide& side = kindSides_[k];
  StaticSide& held = staticSides_[k];
  if ((qLast && !same(*qLast, x)) || (x0 && !same(*x0, x))) {  // moved by hand within a stage
    held.formed = false;
    return FormKindFrameSide(*(*kinds_)[k], x, qLast, x0, stageDof, &side);
  }
  // Its x_n and x⁰ the same values as x: the frame at all three is the frame at x.
  if (!held.formed || !same(held.x, x) || held.stageDof != stageDof) {
    FormKindFrameSide(*(*kinds_)[k], x, &x, &x, stageDof, &side);
    held.x = x;
    held.stageDof = stageDof;
    held.formed = true;
  }
  side.field = (*kinds_)[k]->Collider();  // the kind itself may have been replaced since
  side.hasLast = qLast != nullptr;
  side.hasStart = x0 != nullptr;
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
    DissipationSetup setup =
        dissipation ? MakeSetup(kp.params, *dissipation, q.isotropic) : DissipationSetup();
    setup.slips = SlipUse(k);
    const FrameSide& B = kindSides_[kp.b];
    // Evaluated into the worker's own stencils, then kept in the pair's compact ones where they
    // fit (a pair of rigid bodies' [δp, δθ]: the memory the sweeps touch is a quarter).
    static thread_local PairStencils scratch;
    if (kp.Cloud()) {
      EvaluateCloudPiece(*q.kinds, kp, dissipation ? &setup : nullptr, q.order, &scratch);
    } else {
      FrameEvaluation evaluation(B, PenaltyOf(kp.params), kp.params.maxAlignmentNormals,
                                 dissipation ? &setup : nullptr, q.order, &scratch);
      GatherKindPairSamples(q, kp, B, dissipation ? &setup : nullptr, &evaluation);
      evaluation.Finish();
    }
    bool fits = true;
    for (int e = 0; e < scratch.count; ++e) {
      if (3 * scratch.stencils[e].blocks > kMaxSmallStencil) fits = false;
      if (q.order >= 2) ProjectStencil(q.potential, q.projection, &scratch.stencils[e]);
    }
    kindWide_[k] = !fits;
    if (fits)
      kindResults_[k].CopyFrom(scratch, q.order, q.potential);
    else
      kindWideResults_[k].CopyFrom(scratch, q.order, q.potential);
  };
  BeginSlips(dissipation);
  ForEachPair(kindPairs_.size(), KindPairWork() >= kParallelSampleWork, evaluate);
  EndSlips(dissipation);
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
  Request q;
  q.kinds = kinds;
  q.dissipation = dissipation;
  PairStencils scratchKind;
  FormKindSides(q);
  for (const KindPair& kp : kindPairs_) {
    const FrameSide& B = kindSides_[kp.b];
    const DissipationSetup setup = setupOf(kp.params);
    const size_t first = records->size();
    if (kp.Cloud()) {
      EvaluateCloudPiece(*kinds, kp, dissipation ? &setup : nullptr, 0, &scratchKind, records);
    } else {
      FrameEvaluation evaluation(B, PenaltyOf(kp.params), kp.params.maxAlignmentNormals,
                                 dissipation ? &setup : nullptr, 0, &scratchKind, records);
      GatherKindPairSamples(q, kp, B, dissipation ? &setup : nullptr, &evaluation);
      evaluation.Finish();
    }
    for (size_t k = first; k < records->size(); ++k) {
      (*records)[k].colliding = kindActor_[kp.a];
      (*records)[k].collider = kindActor_[kp.b];
    }
  }
}

}  // namespace superdex
