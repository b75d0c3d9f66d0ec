#include "core/contact_pipeline.h"

#include <tbb/parallel_for.h>

#include "core/broad_phase.h"
#include "energies/psd_projection.h"

namespace superdex {
namespace {

bool IsColliding(const RigidBodyModel& m) { return !m.samples.empty(); }
bool IsCollider(const RigidBodyModel& m) { return m.collider.type != ColliderType::None; }

// Below this many tested samples a pair list is evaluated serially.
constexpr size_t kParallelSampleWork = 20000;

void AppendBlocks(const StencilMatrix& M, const int offs[2], int blocks,
                  std::vector<Eigen::Triplet<double>>* triplets) {
  for (int bi = 0; bi < blocks; ++bi) {
    if (offs[bi] < 0) continue;
    for (int bj = 0; bj < blocks; ++bj) {
      if (offs[bj] < 0) continue;
      for (int c = 0; c < 6; ++c)
        for (int r = 0; r < 6; ++r)
          triplets->emplace_back(offs[bi] + r, offs[bj] + c, M(6 * bi + r, 6 * bj + c));
    }
  }
}

void AddBlocks(const StencilVector& g, const int offs[2], int blocks, Eigen::VectorXd* out) {
  for (int bi = 0; bi < blocks; ++bi)
    if (offs[bi] >= 0) out->segment<6>(offs[bi]) += g.segment<6>(6 * bi);
}

}  // namespace

void ContactPipeline::Configure(const std::vector<RigidBodyModel>* models,
                                const ContactFilter* filter) {
  models_ = models;
  filter_ = filter;
  const size_t n = models->size();
  inflation_.assign(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    const ContactParams& c = (*models)[i].contact;
    // A pair is possible when A's samples come within δ of B's shape; δ comes from the collider.
    inflation_[i] = std::max(0.0, c.penaltyThresholdDefault + c.penaltyThresholdExtraPadding) +
                    c.distanceErrorBound;
  }
}

void ContactPipeline::FindPairs(const std::vector<RigidPose>& poses,
                                const DissipationContext* dissipation,
                                const std::vector<RigidStageStart>* stageStart) {
  const std::vector<RigidBodyModel>& models = *models_;
  const size_t n = models.size();
  boxes_.resize(n);
  // Explicit normals retain the stage-start contacts: the boxes sweep from x⁰ to x.
  const bool sweep = dissipation && dissipation->mode == DissipationMode::ExplicitNormals;
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
  FindOverlappingPairs(boxes_, &overlaps_);
  pairs_.clear();
  auto consider = [&](int a, int b) {
    const RigidBodyModel& A = models[a];
    const RigidBodyModel& B = models[b];
    if (!IsColliding(A) || !IsCollider(B)) return;
    if (!A.dynamic && !B.dynamic) return;
    if (filter_ && !filter_->Allowed(a, b)) return;
    ContactPair p;
    p.colliding = a;
    p.collider = b;
    const bool noCollider = A.collider.type == ColliderType::None ||
                            A.collider.type == ColliderType::PointCloud;
    p.params = CombineContactParams(A.contact, B.contact, !B.dynamic, noCollider);
    pairs_.push_back(p);
  };
  for (const auto& [i, j] : overlaps_) {
    consider(i, j);
    consider(j, i);
  }
}

double ContactPipeline::Evaluate(const std::vector<RigidPose>& poses,
                                 const std::vector<int>& dofOffset, int order,
                                 PsdProjection projection, Eigen::VectorXd* gradient,
                                 std::vector<Eigen::Triplet<double>>* triplets,
                                 ContactStats* stats, const DissipationContext* dissipation,
                                 Eigen::VectorXd* dissipationResidual,
                                 const std::vector<RigidStageStart>* stageStart) {
  const std::vector<RigidBodyModel>& models = *models_;
  FindPairs(poses, dissipation, stageStart);
  results_.resize(pairs_.size());
  dissipationResults_.resize(dissipation ? pairs_.size() : 0);
  const bool potential = !dissipation || dissipation->mode == DissipationMode::ExplicitNormals;
  const std::vector<RigidStageStart>* reference = stageStart;
  size_t work = 0;
  for (const ContactPair& p : pairs_) work += models[p.colliding].samples.size();

  auto evaluate = [&](size_t k) {
    const ContactPair& cp = pairs_[k];
    PenaltyParams pp;
    pp.k = cp.params.penaltyCoefficient;
    pp.eps = cp.params.smoothingHalfDistance;
    pp.delta = cp.params.threshold;
    const RigidBodyModel& A = models[cp.colliding];
    const RigidBodyModel& B = models[cp.collider];
    RigidPairPenalty& r = results_[k];
    const RigidPose* aRef = reference ? &(*reference)[cp.colliding].last : nullptr;
    const RigidPose* bRef = reference ? &(*reference)[cp.collider].last : nullptr;
    EvaluateRigidPairPenalty(A, poses[cp.colliding], B, poses[cp.collider], B.dynamic, pp, order,
                             &r, cp.params.maxAlignmentNormals, aRef, bRef);
    if (dissipation) {
      DissipationSetup setup;
      setup.mode = dissipation->mode;
      setup.fadeFriction = dissipation->fadeFriction;
      setup.dt = dissipation->dt;
      setup.penalty = pp;
      setup.coefficients.mu = cp.params.coulombFrictionCoefficient;
      setup.coefficients.ct = cp.params.viscousFrictionCoefficient;
      setup.coefficients.cn = cp.params.normalViscousDampingCoefficient;
      setup.coefficients.vf = cp.params.frictionFalloffVel;
      setup.maxAlignment = cp.params.maxAlignmentNormals;
      setup.frictionWithColliderNormal = cp.params.frictionWithColliderNormal;
      RigidPairDissipation& d = dissipationResults_[k];
      const std::vector<RigidStageStart>& start = *stageStart;
      EvaluateRigidPairDissipation(A, poses[cp.colliding], start[cp.colliding], B,
                                   poses[cp.collider], start[cp.collider], B.dynamic, setup, order,
                                   &d);
      if (order >= 2 && potential && d.activeSamples > 0) {
        r.hessian += d.jacobian;
      }
    }
    const bool any = r.activeSamples > 0 ||
                     (dissipation && potential && dissipationResults_[k].activeSamples > 0);
    if (order >= 2 && any && projection != PsdProjection::None)
      ProjectToPsd(&r.hessian, projection == PsdProjection::Abs);
  };
  if (work >= kParallelSampleWork && pairs_.size() > 1) {
    tbb::parallel_for(size_t(0), pairs_.size(), evaluate);
  } else {
    for (size_t k = 0; k < pairs_.size(); ++k) evaluate(k);
  }

  // Fixed-order reduction.
  double energy = 0.0;
  ContactStats st;
  st.candidatePairs = static_cast<int>(pairs_.size());
  for (size_t k = 0; k < pairs_.size(); ++k) {
    const RigidPairPenalty& r = results_[k];
    const int offs[2] = {dofOffset[pairs_[k].colliding], dofOffset[pairs_[k].collider]};
    const int blocks = models[pairs_[k].collider].dynamic ? 2 : 1;
    st.minSignedDistance = std::min(st.minSignedDistance, r.minPhi);
    const RigidPairDissipation* d =
        dissipation && dissipationResults_[k].activeSamples > 0 ? &dissipationResults_[k] : nullptr;
    if (r.activeSamples > 0) {
      ++st.activePairs;
      st.activeSamples += r.activeSamples;
      st.energy += r.value;
      energy += r.value;
      if (order >= 1) AddBlocks(r.gradient, offs, blocks, gradient);
    }
    if (d) {
      st.dissipativeSamples += d->activeSamples;
      st.dissipation += d->value;
      st.maxCoulombRatio = std::max(st.maxCoulombRatio, d->maxCoulombRatio);
      energy += d->value;
      if (order >= 1)
        AddBlocks(d->residual, offs, blocks, dissipationResidual ? dissipationResidual : gradient);
      if (order >= 2 && !potential) AppendBlocks(d->jacobian, offs, blocks, triplets);
    }
    if (order >= 2 && (r.activeSamples > 0 || (d && potential)))
      AppendBlocks(r.hessian, offs, blocks, triplets);
  }
  if (stats) *stats = st;
  return energy;
}

void ContactPipeline::CollectSamples(const std::vector<RigidPose>& poses,
                                     std::vector<ContactSampleRecord>* records) {
  const std::vector<RigidBodyModel>& models = *models_;
  FindPairs(poses, nullptr, nullptr);
  records->clear();
  RigidPairPenalty scratch;
  for (const ContactPair& cp : pairs_) {
    PenaltyParams pp;
    pp.k = cp.params.penaltyCoefficient;
    pp.eps = cp.params.smoothingHalfDistance;
    pp.delta = cp.params.threshold;
    const size_t first = records->size();
    EvaluateRigidPairPenalty(models[cp.colliding], poses[cp.colliding], models[cp.collider],
                             poses[cp.collider], models[cp.collider].dynamic, pp, 0, &scratch,
                             cp.params.maxAlignmentNormals, nullptr, nullptr, records);
    for (size_t k = first; k < records->size(); ++k) {
      (*records)[k].colliding = cp.colliding;
      (*records)[k].collider = cp.collider;
    }
  }
}

}  // namespace superdex
