#include "core/contact/contact_pipeline.h"

#include <tbb/parallel_for.h>

#include "core/contact/broad_phase.h"

namespace superdex {
namespace {

bool IsColliding(const RigidBodyModel& m) { return !m.samples.empty(); }
bool IsCollider(const RigidBodyModel& m) { return m.collider.type != ColliderType::None; }
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

void ContactPipeline::Configure(const std::vector<RigidBodyModel>* models,
                                const ContactFilter* filter,
                                const std::vector<SoftBodyModel>* softModels,
                                std::vector<int> rigidActor, std::vector<int> softActor,
                                const std::vector<const ActorKind*>* kinds,
                                std::vector<int> kindActor) {
  models_ = models;
  kinds_ = kinds && !kinds->empty() ? kinds : nullptr;
  kindActor_ = std::move(kindActor);
  kindInflation_.clear();
  kindHasDofs_.clear();
  kindColliding_.clear();
  kindCollider_.clear();
  kindStatic_.clear();
  kindSamples_.clear();
  if (kinds_)
    for (const ActorKind* k : *kinds_) {
      kindInflation_.push_back(k->Collider() ? ColliderReach(k->contact) : 0.0);
      kindCollider_.push_back(k->Collider() != nullptr);
      kindHasDofs_.push_back(k->HasFreeDof());
      kindColliding_.push_back(k->IsColliding());
      kindStatic_.push_back(k->IsStatic());
      size_t samples = static_cast<size_t>(k->NumSamples());
      for (int b = 0; b < k->NumSampleBodies(); ++b) samples += k->SampleBody(b)->samples.size();
      kindSamples_.push_back(samples);
    }
  filter_ = filter;
  softModels_ = softModels && !softModels->empty() ? softModels : nullptr;
  rigidActor_ = std::move(rigidActor);
  softActor_ = std::move(softActor);
  softInflation_.clear();
  if (softModels_)
    for (const SoftBodyModel& m : *softModels_)
      softInflation_.push_back(m.collider == ColliderType::Sdf ? ColliderReach(m.contact) : 0.0);
  const size_t n = models->size();
  inflation_.assign(n, 0.0);
  for (size_t i = 0; i < n; ++i) inflation_[i] = ColliderReach((*models)[i].contact);
}

void ContactPipeline::FindPairs(const std::vector<RigidPose>& poses,
                                const DissipationContext* dissipation,
                                const std::vector<RigidStageStart>* stageStart,
                                const SoftView* soft, const KindView* kinds) {
  const std::vector<RigidBodyModel>& models = *models_;
  const size_t n = models.size();
  const size_t ns = soft && softModels_ ? softModels_->size() : 0;
  const size_t nk = kinds && kinds_ ? kinds_->size() : 0;
  boxes_.resize(n + ns + nk);
  // With dissipation the terms read x_n's geometry too (explicit normals keep the stage-start
  // contacts; the reconstructed load φ + G·(Y_n − Y) can be positive where φ > δ, its bound
  // growing with |Y_n − Y|): the boxes sweep from x_n to x, as the soft actors' and the kinds' do.
  const bool sweep = dissipation && stageStart;
  for (size_t i = 0; i < n; ++i) {
    boxes_[i] = WorldBounds(models[i], poses[i].p, poses[i].R);
    if (sweep) {
      const RigidStageStart& s = (*stageStart)[i];
      const Aabb b0 = WorldBounds(models[i], s.last.p, s.last.R);
      boxes_[i].Extend(b0.min);
      boxes_[i].Extend(b0.max);
    }
    boxes_[i].Inflate(inflation_[i]);
  }
  // Soft actors after the rigid ones; a soft actor is colliding only, so no padding of its own.
  for (size_t s = 0; s < ns; ++s) {
    boxes_[n + s] = SoftBounds((*soft->x)[s]);
    if (soft->xLast) boxes_[n + s].Extend(SoftBounds((*soft->xLast)[s]));
    boxes_[n + s].Inflate(softInflation_[s]);
  }
  // The generic layer's actors last, swept over x_n as soft actors are.
  for (size_t k = 0; k < nk; ++k) {
    const ActorKind& kind = *(*kinds_)[k];
    boxes_[n + ns + k] = kind.Bounds((*kinds->q)[kinds->first + k]);
    if (kinds->qLast) boxes_[n + ns + k].Extend(kind.Bounds((*kinds->qLast)[k]));
    boxes_[n + ns + k].Inflate(kindInflation_[k]);
  }
  overlapCache_.Find(boxes_, &overlaps_);
  pairs_.clear();
  softColliderPairs_.clear();
  kindPairs_.clear();
  // A on the soft collider B (B's collider is an Sdf grid mapped by its deformation).
  auto considerOnSoft = [&](bool aSoft, int a, int b) {
    const SoftBodyModel& B = (*softModels_)[b];
    if (B.collider != ColliderType::Sdf) return;
    if (aSoft ? a == b : !IsColliding(models[a])) return;
    const int actorA = aSoft ? softActor_[a] : RigidActor(a);
    if (filter_ && !filter_->Allowed(actorA, softActor_[b])) return;
    SoftColliderPair p;
    p.collidingSoft = aSoft;
    p.colliding = a;
    p.collider = b;
    // Both actors are dynamic; A's own collider type decides the threshold padding.
    const bool aNoCollider =
        aSoft ? (*softModels_)[a].collider == ColliderType::None
              : (models[a].collider.type == ColliderType::None ||
                 models[a].collider.type == ColliderType::PointCloud);
    p.params = CombineContactParams(aSoft ? (*softModels_)[a].contact : models[a].contact, B.contact,
                                    false, aNoCollider);
    softColliderPairs_.push_back(p);
  };
  auto consider = [&](int a, int b) {
    const RigidBodyModel& A = models[a];
    const RigidBodyModel& B = models[b];
    if (!IsColliding(A) || !IsCollider(B)) return;
    if (!A.dynamic && !B.dynamic) return;  // neither has dofs (static or kinematic)
    if (filter_ && !filter_->Allowed(RigidActor(a), RigidActor(b))) return;
    ContactPair p;
    p.colliding = a;
    p.collider = b;
    const bool noCollider = A.collider.type == ColliderType::None ||
                            A.collider.type == ColliderType::PointCloud;
    p.params = CombineContactParams(A.contact, B.contact, !B.Moves(), noCollider);
    pairs_.push_back(p);
  };
  const int firstKind = static_cast<int>(n + ns);
  for (const auto& [i, j] : overlaps_) {
    if (i >= firstKind || j >= firstKind) {  // a kind's actor with a rigid one or another kind's
      const bool ki = i >= firstKind, kj = j >= firstKind;
      if (!ki && i >= static_cast<int>(n)) {  // soft i and kind j, each on the other's field
        ConsiderSoftPair(i - static_cast<int>(n), true, j - firstKind);
        ConsiderKindOnSoft(j - firstKind, i - static_cast<int>(n));
        continue;
      }
      if (!kj && j >= static_cast<int>(n)) {
        ConsiderSoftPair(j - static_cast<int>(n), true, i - firstKind);
        ConsiderKindOnSoft(i - firstKind, j - static_cast<int>(n));
        continue;
      }
      const int a = ki ? i - firstKind : i, b = kj ? j - firstKind : j;
      ConsiderKindPair(ki, a, kj, b);
      ConsiderKindPair(kj, b, ki, a);
      continue;
    }
    const bool si = i >= static_cast<int>(n), sj = j >= static_cast<int>(n);
    if (!si && !sj) {
      consider(i, j);
      consider(j, i);
    } else if (si && !sj) {
      ConsiderSoftPair(i - static_cast<int>(n), false, j);
      considerOnSoft(false, j, i - static_cast<int>(n));
    } else if (!si && sj) {
      ConsiderSoftPair(j - static_cast<int>(n), false, i);
      considerOnSoft(false, i, j - static_cast<int>(n));
    } else {
      considerOnSoft(true, i - static_cast<int>(n), j - static_cast<int>(n));
      considerOnSoft(true, j - static_cast<int>(n), i - static_cast<int>(n));
    }
  }
}

void ContactPipeline::ConsiderKindPair(bool aKind, int a, bool bKind, int b) {
  const std::vector<RigidBodyModel>& models = *models_;
  if (aKind == bKind && a == b) return;  // self-contact of a kind: not in this layer yet
  const ActorKind* A = aKind ? (*kinds_)[a] : nullptr;
  const ActorKind* B = bKind ? (*kinds_)[b] : nullptr;
  if (aKind ? !kindColliding_[a] : !IsColliding(models[a])) return;
  if (bKind ? !kindCollider_[b] : !IsCollider(models[b])) return;
  if (!aKind && !bKind) return;
  // Neither has a stage unknown (static, kinematic or all prescribed): nothing to solve for.
  const bool aDofs = aKind ? kindHasDofs_[a] : models[a].dynamic;
  const bool bDofs = bKind ? kindHasDofs_[b] : models[b].dynamic;
  if (!aDofs && !bDofs) return;
  const int actorA = aKind ? kindActor_[a] : RigidActor(a);
  const int actorB = bKind ? kindActor_[b] : RigidActor(b);
  if (filter_ && !filter_->Allowed(actorA, actorB)) return;
  KindPair p;
  p.aKind = aKind;
  p.bKind = bKind;
  p.a = a;
  p.b = b;
  const bool aNoCollider =
      aKind ? !kindCollider_[a]
            : (models[a].collider.type == ColliderType::None ||
               models[a].collider.type == ColliderType::PointCloud);
  // A kinematic collider moves: its parameters combine as a dynamic one's (spec: "taken from the
  // colliding actor when the collider is static").
  p.params = CombineContactParams(aKind ? A->contact : models[a].contact,
                                  bKind ? B->contact : models[b].contact,
                                  bKind ? kindStatic_[b] : !models[b].Moves(), aNoCollider);
  kindPairs_.push_back(p);
}

void ContactPipeline::ConsiderSoftPair(int s, bool bKind, int b) {
  const ActorKind* kind = bKind ? (*kinds_)[b] : nullptr;
  const RigidBodyModel* rigid = bKind ? nullptr : &(*models_)[b];
  if (bKind ? kind->Collider() == nullptr : !IsCollider(*rigid)) return;
  if (filter_ && !filter_->Allowed(softActor_[s], bKind ? kindActor_[b] : RigidActor(b))) return;
  KindPair p;
  p.aSoft = true;
  p.bKind = bKind;
  p.a = s;
  p.b = b;
  // The threshold padding applies when A's own collider is None or PointCloud (spec,
  // penaltyThresholdExtraPadding), not when it is a grid Sdf. A kinematic rigid collider moves:
  // its parameters combine as a dynamic one's.
  const SoftBodyModel& A = (*softModels_)[s];
  p.params = CombineContactParams(
      A.contact, bKind ? kind->contact : rigid->contact, bKind ? kind->IsStatic() : !rigid->Moves(),
      A.collider == ColliderType::None || A.collider == ColliderType::PointCloud);
  kindPairs_.push_back(p);
}

void ContactPipeline::ConsiderKindOnSoft(int k, int b) {
  const SoftBodyModel& B = (*softModels_)[b];
  const ActorKind& A = *(*kinds_)[k];
  if (B.collider != ColliderType::Sdf || A.NumSampleBodies() == 0) return;
  if (filter_ && !filter_->Allowed(kindActor_[k], softActor_[b])) return;
  SoftColliderPair p;
  p.collidingKind = true;
  p.colliding = k;
  p.collider = b;
  // Both move; A's own collider type decides the threshold padding.
  p.params = CombineContactParams(A.contact, B.contact, false, A.Collider() == nullptr);
  for (p.body = 0; p.body < A.NumSampleBodies(); ++p.body) softColliderPairs_.push_back(p);
}

void ContactPipeline::SampleBodyOffsets(const KindView& kinds, int k, int body,
                                        int offs[2]) const {
  int dof[2];
  (*kinds_)[k]->SampleBodyDofs(body, dof);
  const std::vector<int>* stageDof = kinds.stageDof ? &(*kinds.stageDof)[k] : nullptr;
  for (int c = 0; c < 2; ++c) offs[c] = stageDof ? (*stageDof)[dof[c]] : -1;
}

void ContactPipeline::SoftColliderInputs(const SoftColliderPair& sp,
                                         const std::vector<RigidPose>& poses,
                                         const std::vector<RigidStageStart>* stageStart,
                                         const SoftView& soft, const KindView* kinds,
                                         bool kindStart, RigidPose* pose,
                                         RigidStageStart* start, CollidingInput* a,
                                         SoftColliderInput* b) const {
  *a = CollidingInput();
  if (sp.collidingKind) {
    const ActorKind& A = *(*kinds_)[sp.colliding];
    const bool hasStart =
        SampleBodyAt(A, sp.body, (*kinds->q)[kinds->first + sp.colliding],
                     EntryOf(kinds->qLast, sp.colliding),
                     kindStart ? EntryOf(kinds->q0, sp.colliding) : nullptr, pose, start);
    a->rigid = A.SampleBody(sp.body);
    a->pose = pose;
    a->start = hasStart ? start : nullptr;
  } else if (sp.collidingSoft) {
    a->soft = &(*softModels_)[sp.colliding];
    a->x = &(*soft.x)[sp.colliding];
    a->xLast = soft.xLast ? &(*soft.xLast)[sp.colliding] : nullptr;
    a->x0 = soft.x0 ? &(*soft.x0)[sp.colliding] : nullptr;
  } else {
    a->rigid = &(*models_)[sp.colliding];
    a->pose = &poses[sp.colliding];
    a->start = stageStart ? &(*stageStart)[sp.colliding] : nullptr;
  }
  *b = SoftColliderInput();
  b->model = &(*softModels_)[sp.collider];
  b->x = &(*soft.x)[sp.collider];
  b->xLast = soft.xLast ? &(*soft.xLast)[sp.collider] : nullptr;
  b->x0 = soft.x0 ? &(*soft.x0)[sp.collider] : nullptr;
  b->locator = &locators_[sp.collider];
  b->locatorLast = soft.xLast ? &locatorsLast_[sp.collider] : &locators_[sp.collider];
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

size_t ContactPipeline::RigidPairWork() const {
  size_t work = 0;
  for (const ContactPair& p : pairs_) work += (*models_)[p.colliding].samples.size();
  return work;
}

size_t ContactPipeline::KindPairWork() const {
  size_t work = 0;
  for (const KindPair& kp : kindPairs_) {
    if (kp.aSoft) return kParallelSampleWork;  // a soft surface's samples: always in parallel
    work += kp.aKind ? kindSamples_[kp.a] : (*models_)[kp.a].samples.size();
  }
  return work;
}

bool ContactPipeline::SplitLastEvaluation(const std::vector<int>& dofOffset,
                                          std::vector<double>* share,
                                          std::vector<std::pair<int, int>>* joins) const {
  if (!softColliderPairs_.empty() || results_.size() != pairs_.size() ||
      kindResults_.size() != kindPairs_.size())
    return false;
  for (const KindPair& kp : kindPairs_)
    if (kp.aSoft) return false;  // soft actors are not split
  // Each pair's values to its first dynamic actor; two dynamic actors with an active sample join.
  auto add = [&](const auto& r, int a, bool aDynamic, int b, bool bDynamic) {
    if (r.activeSamples == 0 && r.dissipativeSamples == 0) return;
    if (!aDynamic && !bDynamic) return;
    const int owner = aDynamic ? a : b;
    if (r.activeSamples > 0) (*share)[owner] += r.penaltyValue;
    if (r.dissipativeSamples > 0) (*share)[owner] += r.dissipationValue;
    if (aDynamic && bDynamic) joins->emplace_back(a, b);
  };
  for (size_t k = 0; k < pairs_.size(); ++k) {
    const int a = pairs_[k].colliding, b = pairs_[k].collider;
    add(results_[k], a, dofOffset[a] >= 0, b, dofOffset[b] >= 0);
  }
  const int n = static_cast<int>(dofOffset.size());
  for (size_t k = 0; k < kindPairs_.size(); ++k) {
    const KindPair& kp = kindPairs_[k];
    const int a = kp.aKind ? n + kp.a : kp.a, b = kp.bKind ? n + kp.b : kp.b;
    const bool aDynamic = kp.aKind ? kindHasDofs_[kp.a] != 0 : dofOffset[kp.a] >= 0;
    const bool bDynamic = kp.bKind ? kindHasDofs_[kp.b] != 0 : dofOffset[kp.b] >= 0;
    WithKindResults(k, [&](const auto& r) { add(r, a, aDynamic, b, bDynamic); });
  }
  return true;
}

void ContactPipeline::StepLimits(const std::vector<RigidPose>& poses,
                                 const std::vector<RigidPose>& trial,
                                 std::vector<double>* alpha, const KindView* now,
                                 const KindView* next, std::vector<double>* kindAlpha) {
  const std::vector<RigidBodyModel>& models = *models_;
  alpha->assign(models.size(), 1.0);
  const bool kinds = now && next && kindAlpha && kinds_;
  if (kinds) kindAlpha->assign(kinds_->size(), 1.0);
  FindPairs(trial, nullptr, nullptr, nullptr, kinds ? next : nullptr);
  pairLimits_.resize(pairs_.size());
  auto evaluate = [&](size_t k) {
    const ContactPair& cp = pairs_[k];
    pairLimits_[k] =
        RigidPairStepLimit(models[cp.colliding], poses[cp.colliding], trial[cp.colliding],
                           models[cp.collider], poses[cp.collider], trial[cp.collider],
                           PenaltyOf(cp.params));
  };
  ForEachPair(pairs_.size(), RigidPairWork() >= kParallelSampleWork, evaluate);
  for (size_t k = 0; k < pairs_.size(); ++k) {
    double& a = (*alpha)[pairs_[k].colliding];
    double& b = (*alpha)[pairs_[k].collider];
    a = std::min(a, pairLimits_[k]);
    b = std::min(b, pairLimits_[k]);
  }
  if (!kinds) return;
  // Pairs of the generic layer: each side at the trial configuration, with the current one as
  // its "last" (the samples' yLast, the frame's last pose).
  kindPairLimits_.resize(kindPairs_.size());
  auto q = [](const KindView* v, int k) -> const Eigen::VectorXd& {
    return (*v->q)[v->first + k];
  };
  auto evaluateKind = [&](size_t k) {
    const KindPair& kp = kindPairs_[k];
    kindPairLimits_[k] = 1.0;
    if (kp.aSoft) return;  // soft nodes take no step limit (SceneStageProblem::LimitStep)
    const PenaltyParams penalty = PenaltyOf(kp.params);
    RigidStageStart bNow, aNow;
    FrameSide B;
    if (kp.bKind) {
      B = KindFrameSide(*(*kinds_)[kp.b], q(next, kp.b), &q(now, kp.b), nullptr,
                        (*next->stageDof)[kp.b]);
    } else {
      bNow.last = poses[kp.b];
      B = RigidFrameSide(models[kp.b], trial[kp.b], &bNow, -1);
    }
    const double phiLimit = penalty.delta - 0.5 * penalty.eps;
    StepLimitSink sink(B, penalty);
    if (kp.aKind) {
      GatherKindSamples(*(*kinds_)[kp.a], q(next, kp.a), &q(now, kp.a), nullptr,
                        (*next->stageDof)[kp.a], B, phiLimit, nullptr, &sink);
    } else {
      aNow.last = poses[kp.a];
      GatherRigidSamples(models[kp.a], trial[kp.a], &aNow, -1, B, phiLimit, nullptr, &sink);
    }
    kindPairLimits_[k] = sink.Alpha();
  };
  ForEachPair(kindPairs_.size(), KindPairWork() >= kParallelSampleWork, evaluateKind);
  for (size_t k = 0; k < kindPairs_.size(); ++k) {
    const KindPair& kp = kindPairs_[k];
    if (kp.aSoft) continue;
    double& a = kp.aKind ? (*kindAlpha)[kp.a] : (*alpha)[kp.a];
    a = std::min(a, kindPairLimits_[k]);
    double& b = kp.bKind ? (*kindAlpha)[kp.b] : (*alpha)[kp.b];
    b = std::min(b, kindPairLimits_[k]);
  }
}

template <typename Stencils>
void ContactPipeline::ReducePair(const Request& q, const Stencils& r, bool aSoft, int a,
                                 bool bSoft, int b, double* energy, ContactStats* st,
                                 const int* aOffs) const {
  ++st->candidatePairs;
  *energy += AddPairStats(r, st);
  if (q.order < 1) return;
  const SoftView* soft = q.soft;
  const std::vector<int>& dofOffset = *q.dofOffset;
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
    int offs[7];
    int blocks = 0;
    if (aSoft) {  // the face's three nodes
      for (int c = 0; c < 3; ++c) offs[blocks++] = node(a, (*softModels_)[a].faces[cs.aFace][c]);
    } else if (aOffs) {  // a kind's sample body's [δp, δθ]
      offs[blocks++] = aOffs[0];
      offs[blocks++] = aOffs[1];
    } else {  // the rigid body's [δp, δθ]
      const int o = dofOffset[a];
      offs[blocks++] = o;
      offs[blocks++] = o < 0 ? -1 : o + 3;
    }
    if (bSoft) {  // the tet's four nodes
      for (int c = 0; c < 4; ++c) offs[blocks++] = node(b, (*softModels_)[b].rest.tets[cs.bTet][c]);
    } else if ((*models_)[b].dynamic) {
      offs[blocks++] = dofOffset[b];
      offs[blocks++] = dofOffset[b] + 3;
    }
    ScatterStencil(cs, offs, blocks, q.potential, q.gradient, q.dissipationResidual,
                   q.order >= 2 ? q.triplets : nullptr);
  }
}

double ContactPipeline::Evaluate(const std::vector<RigidPose>& poses,
                                 const std::vector<int>& dofOffset, int order,
                                 PsdProjection projection, Eigen::VectorXd* gradient,
                                 std::vector<Eigen::Triplet<double>>* triplets,
                                 std::vector<DenseBlock6>* blockOut, ContactStats* stats,
                                 const DissipationContext* dissipation,
                                 Eigen::VectorXd* dissipationResidual,
                                 const std::vector<RigidStageStart>* stageStart,
                                 const SoftView* soft, const KindView* kinds) {
  FindPairs(poses, dissipation, stageStart, soft, kinds);
  Request q;
  q.poses = &poses;
  q.dofOffset = &dofOffset;
  q.order = order;
  q.projection = projection;
  q.gradient = gradient;
  q.triplets = triplets;
  q.blocks = blockOut;
  q.dissipation = dissipation;
  q.dissipationResidual = dissipationResidual;
  q.stageStart = stageStart;
  q.soft = soft;
  q.kinds = kinds;
  q.potential = !dissipation || dissipation->mode == DissipationMode::ExplicitNormals;
  // Projected Hessians are the globalization model: the Coulomb term's isotropic majorizer.
  q.isotropic = q.potential && projection != PsdProjection::None;
  if (dissipation && dissipation->slips && dissipation->recordSlips) dissipation->slips->Clear();
  // Each pair kind in parallel over its pairs, then reduced in a fixed order into one sum.
  double energy = 0.0;
  ContactStats st;
  EvaluateRigidPairs(q, &energy, &st);
  EvaluateKindPairs(q, &energy, &st);
  EvaluateOnSoftPairs(q, &energy, &st);
  if (dissipation && dissipation->slips && dissipation->recordSlips) dissipation->slips->Seal();
  if (stats) *stats = st;
  return energy;
}

void ContactPipeline::EvaluateRigidPairs(const Request& q, double* energy, ContactStats* st) {
  const std::vector<RigidBodyModel>& models = *models_;
  const std::vector<RigidPose>& poses = *q.poses;
  const std::vector<int>& dofOffset = *q.dofOffset;
  const int order = q.order;
  const DissipationContext* dissipation = q.dissipation;
  const bool potential = q.potential;
  results_.resize(pairs_.size());
  const std::vector<RigidStageStart>* start = q.stageStart;
  const auto rigidId = [&](size_t k) { return std::make_pair(pairs_[k].colliding, pairs_[k].collider); };
  auto evaluate = [&](size_t k) {
    const ContactPair& cp = pairs_[k];
    DissipationSetup setup;
    if (dissipation) {
      setup = MakeSetup(cp.params, *dissipation, q.isotropic);
      setup.slips = SlipUse(SlipPairKind::Rigid, k);
    }
    const int a = cp.colliding, b = cp.collider;
    const FrameSide B = RigidFrameSide(models[b], poses[b], start ? &(*start)[b] : nullptr,
                                       dofOffset[b]);
    // Evaluated into the worker's own stencils, then kept in the pair's compact ones.
    static thread_local PairStencils scratch;
    FrameEvaluation evaluation(B, PenaltyOf(cp.params), cp.params.maxAlignmentNormals,
                               dissipation ? &setup : nullptr, order, &scratch);
    GatherRigidSamples(models[a], poses[a], start ? &(*start)[a] : nullptr, dofOffset[a], B,
                       cp.params.threshold, dissipation ? &setup : nullptr, &evaluation);
    evaluation.Finish();
    if (order >= 2)
      for (int e = 0; e < scratch.count; ++e)
        ProjectStencil(potential, q.projection, &scratch.stencils[e]);
    results_[k].CopyFrom(scratch, order);
  };
  SweepPairs(dissipation, SlipPairKind::Rigid, pairs_.size(),
             RigidPairWork() >= kParallelSampleWork, rigidId, evaluate);
  // Fixed-order reduction; the matrices as dense 6 × 6 blocks.
  for (size_t k = 0; k < pairs_.size(); ++k) {
    const RigidPairStencils& r = results_[k];
    ++st->candidatePairs;
    *energy += AddPairStats(r, st);
    if (order < 1) continue;
    const int offs[2] = {dofOffset[pairs_[k].colliding], dofOffset[pairs_[k].collider]};
    const int groups = models[pairs_[k].collider].dynamic ? 2 : 1;
    for (int e = 0; e < r.count; ++e)
      ScatterStencil6(r.stencils[e], offs, groups, potential, q.gradient, q.dissipationResidual,
                      order >= 2 ? q.blocks : nullptr);
  }
}

void ContactPipeline::EvaluateOnSoftPairs(const Request& q, double* energy, ContactStats* st) {
  const SoftView* soft = q.soft;
  const DissipationContext* dissipation = q.dissipation;
  // Colliding ids: rigid models (i), soft actors (−1 − s), kinds' sample bodies (n + k + nk b).
  const int n = static_cast<int>(models_->size());
  const int nk = static_cast<int>(kinds_ ? kinds_->size() : 0);
  const auto onSoftId = [&](size_t k) {
    const SoftColliderPair& p = softColliderPairs_[k];
    return std::make_pair(p.collidingSoft   ? -1 - p.colliding
                          : p.collidingKind ? n + p.colliding + nk * p.body
                                            : p.colliding,
                          p.collider);
  };
  // Samples of rigid and soft actors and kinds' bodies on soft colliders, one stencil per sample.
  if (!softColliderPairs_.empty()) {
    const size_t ns = softModels_->size();
    locators_.resize(ns);
    locatorsLast_.resize(ns);
    std::vector<char> built(ns, 0);
    for (const SoftColliderPair& p : softColliderPairs_) built[p.collider] = 1;
    for (size_t b = 0; b < ns; ++b) {
      if (!built[b]) continue;
      locators_[b].Build((*soft->x)[b], (*softModels_)[b].rest.tets);
      if (soft->xLast) locatorsLast_[b].Build((*soft->xLast)[b], (*softModels_)[b].rest.tets);
    }
  }
  softColliderResults_.resize(softColliderPairs_.size());
  auto evaluateOnSoft = [&](size_t k) {
    const SoftColliderPair& sp = softColliderPairs_[k];
    const PenaltyParams pp = PenaltyOf(sp.params);
    CollidingInput a;
    SoftColliderInput b;
    RigidPose pose;
    RigidStageStart start;
    SoftColliderInputs(sp, *q.poses, q.stageStart, *soft, q.kinds, dissipation != nullptr, &pose,
                       &start, &a, &b);
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
    int aOffs[2];
    if (sp.collidingKind) SampleBodyOffsets(*q.kinds, sp.colliding, sp.body, aOffs);
    ReducePair(q, softColliderResults_[k], sp.collidingSoft, sp.colliding, true, sp.collider,
               energy, st, sp.collidingKind ? aOffs : nullptr);
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

const FrameSide& ContactPipeline::KindPairCollider(const Request& q, const KindPair& kp,
                                                  FrameSide* rigid) const {
  if (kp.bKind) return kindSides_[kp.b];
  *rigid = RigidFrameSide((*models_)[kp.b], (*q.poses)[kp.b],
                          q.stageStart ? &(*q.stageStart)[kp.b] : nullptr, (*q.dofOffset)[kp.b]);
  return *rigid;
}

void ContactPipeline::FormKindSides(const Request& q) {
  if (!kinds_ || !q.kinds) return;
  const size_t nk = kinds_->size();
  kindRoles_.assign(nk, 0);
  for (const KindPair& kp : kindPairs_) {
    if (kp.bKind) kindRoles_[kp.b] |= 1;
    if (kp.aKind) kindRoles_[kp.a] |= 2;
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
  } else if (kp.aKind) {
    const KindView& kv = *q.kinds;
    GatherKindSamples(*(*kinds_)[kp.a], (*kv.q)[kv.first + kp.a], EntryOf(kv.qLast, kp.a),
                      q.dissipation ? EntryOf(kv.q0, kp.a) : nullptr, (*kv.stageDof)[kp.a], B,
                      kp.params.threshold, setup, sink, &kindBodies_[kp.a]);
  } else {
    GatherRigidSamples((*models_)[kp.a], (*q.poses)[kp.a],
                       q.stageStart ? &(*q.stageStart)[kp.a] : nullptr, (*q.dofOffset)[kp.a], B,
                       kp.params.threshold, setup, sink);
  }
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
    FrameSide rigidB;
    const FrameSide& B = KindPairCollider(q, kp, &rigidB);
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
  const int n = static_cast<int>(models_->size());
  const int nk = static_cast<int>(kinds_ ? kinds_->size() : 0);
  auto kindId = [&](size_t k) {  // rigid models, then kinds, then soft actors
    const KindPair& kp = kindPairs_[k];
    return std::make_pair(kp.aSoft ? n + nk + kp.a : kp.aKind ? n + kp.a : kp.a,
                          kp.bKind ? n + kp.b : kp.b);
  };
  SweepPairs(dissipation, SlipPairKind::Kind, kindPairs_.size(),
             KindPairWork() >= kParallelSampleWork, kindId, evaluate);
  for (size_t k = 0; k < kindPairs_.size(); ++k)
    WithKindResults(k, [&](const auto& r) { ReducePair(q, r, false, -1, false, -1, energy, st); });
}

void ContactPipeline::CollectSamples(const std::vector<RigidPose>& poses,
                                     std::vector<ContactSampleRecord>* records,
                                     const SoftView* soft, const KindView* kinds,
                                     const DissipationContext* dissipation,
                                     const std::vector<RigidStageStart>* stageStart) {
  const std::vector<RigidBodyModel>& models = *models_;
  if (!stageStart && !models.empty()) dissipation = nullptr;  // built-in rigid pairs need x⁰, x_n
  FindPairs(poses, dissipation, stageStart, soft, kinds);
  records->clear();
  auto setupOf = [&](const PairContactParams& params) {
    return dissipation ? MakeSetup(params, *dissipation, false) : DissipationSetup();
  };
  auto startOf = [&](int i) { return stageStart ? &(*stageStart)[i] : nullptr; };
  PairStencils scratch;
  for (const ContactPair& cp : pairs_) {
    const PenaltyParams pp = PenaltyOf(cp.params);
    const DissipationSetup setup = setupOf(cp.params);
    const size_t first = records->size();
    const FrameSide B = RigidFrameSide(models[cp.collider], poses[cp.collider], startOf(cp.collider), -1);
    FrameEvaluation evaluation(B, pp, cp.params.maxAlignmentNormals, dissipation ? &setup : nullptr,
                               0, &scratch, records);
    GatherRigidSamples(models[cp.colliding], poses[cp.colliding], startOf(cp.colliding), -1, B,
                       pp.delta, dissipation ? &setup : nullptr, &evaluation);
    evaluation.Finish();
    for (size_t k = first; k < records->size(); ++k) {
      (*records)[k].colliding = RigidActor(cp.colliding);
      (*records)[k].collider = RigidActor(cp.collider);
    }
  }
  if (!softColliderPairs_.empty()) {
    locators_.resize(softModels_->size());
    for (const SoftColliderPair& p : softColliderPairs_)
      locators_[p.collider].Build((*soft->x)[p.collider], (*softModels_)[p.collider].rest.tets);
  }
  PairStencils scratchOnSoft;
  for (const SoftColliderPair& sp : softColliderPairs_) {
    const PenaltyParams pp = PenaltyOf(sp.params);
    CollidingInput a;
    SoftColliderInput b;
    RigidPose pose;
    RigidStageStart start;
    SoftColliderInputs(sp, poses, nullptr, *soft, kinds, false, &pose, &start, &a, &b);
    const size_t first = records->size();
    EvaluatePairOnSoftCollider(a, b, pp, sp.params.maxAlignmentNormals, nullptr, 0, &scratchOnSoft,
                               records);
    for (size_t k = first; k < records->size(); ++k) {
      (*records)[k].colliding = sp.collidingSoft   ? softActor_[sp.colliding]
                                : sp.collidingKind ? kindActor_[sp.colliding]
                                                   : RigidActor(sp.colliding);
      (*records)[k].collider = softActor_[sp.collider];
    }
  }
  Request q;
  q.poses = &poses;
  q.kinds = kinds;
  q.soft = soft;
  q.dissipation = dissipation;
  q.stageStart = stageStart;
  PairStencils scratchKind;
  const std::vector<int> noDofs(models.size(), -1);
  q.dofOffset = &noDofs;
  FormKindSides(q);
  for (const KindPair& kp : kindPairs_) {
    FrameSide rigidB;
    const FrameSide& B = KindPairCollider(q, kp, &rigidB);
    const DissipationSetup setup = setupOf(kp.params);
    const size_t first = records->size();
    FrameEvaluation evaluation(B, PenaltyOf(kp.params), kp.params.maxAlignmentNormals,
                               dissipation ? &setup : nullptr, 0, &scratchKind, records);
    GatherKindPairSamples(q, kp, B, dissipation ? &setup : nullptr, &evaluation);
    evaluation.Finish();
    for (size_t k = first; k < records->size(); ++k) {
      (*records)[k].colliding =
          kp.aSoft ? softActor_[kp.a] : kp.aKind ? kindActor_[kp.a] : RigidActor(kp.a);
      (*records)[k].collider = kp.bKind ? kindActor_[kp.b] : RigidActor(kp.b);
    }
  }
}

}  // namespace superdex
