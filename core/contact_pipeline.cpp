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

}  // namespace

void ContactPipeline::Configure(const std::vector<RigidBodyModel>* models) {
  models_ = models;
  const size_t n = models->size();
  inflation_.assign(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    const ContactParams& c = (*models)[i].contact;
    // A pair is possible when A's samples come within δ of B's shape; δ comes from the collider.
    inflation_[i] = std::max(0.0, c.penaltyThresholdDefault + c.penaltyThresholdExtraPadding) +
                    c.distanceErrorBound;
  }
}

void ContactPipeline::FindPairs(const std::vector<RigidPose>& poses) {
  const std::vector<RigidBodyModel>& models = *models_;
  const size_t n = models.size();
  boxes_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    boxes_[i] = WorldBounds(models[i], poses[i].p, poses[i].R);
    boxes_[i].Inflate(inflation_[i]);
  }
  FindOverlappingPairs(boxes_, &overlaps_);
  pairs_.clear();
  auto consider = [&](int a, int b) {
    const RigidBodyModel& A = models[a];
    const RigidBodyModel& B = models[b];
    if (!IsColliding(A) || !IsCollider(B)) return;
    if (!A.dynamic && !B.dynamic) return;
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
                                 ContactStats* stats) {
  const std::vector<RigidBodyModel>& models = *models_;
  FindPairs(poses);
  results_.resize(pairs_.size());
  size_t work = 0;
  for (const ContactPair& p : pairs_) work += models[p.colliding].samples.size();

  auto evaluate = [&](size_t k) {
    const ContactPair& cp = pairs_[k];
    PenaltyParams pp;
    pp.k = cp.params.penaltyCoefficient;
    pp.eps = cp.params.smoothingHalfDistance;
    pp.delta = cp.params.threshold;
    const RigidBodyModel& B = models[cp.collider];
    RigidPairPenalty& r = results_[k];
    EvaluateRigidPairPenalty(models[cp.colliding], poses[cp.colliding], B, poses[cp.collider],
                             B.dynamic, pp, order, &r);
    if (order >= 2 && r.activeSamples > 0 && projection != PsdProjection::None)
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
    st.minSignedDistance = std::min(st.minSignedDistance, r.minPhi);
    if (r.activeSamples == 0) continue;
    ++st.activePairs;
    st.activeSamples += r.activeSamples;
    energy += r.value;
    if (order == 0) continue;
    const int offs[2] = {dofOffset[pairs_[k].colliding], dofOffset[pairs_[k].collider]};
    const int blocks = static_cast<int>(r.gradient.size()) / 6;
    for (int bi = 0; bi < blocks; ++bi) {
      if (offs[bi] < 0) continue;
      gradient->segment<6>(offs[bi]) += r.gradient.segment<6>(6 * bi);
      if (order < 2) continue;
      for (int bj = 0; bj < blocks; ++bj) {
        if (offs[bj] < 0) continue;
        for (int c = 0; c < 6; ++c)
          for (int rr = 0; rr < 6; ++rr)
            triplets->emplace_back(offs[bi] + rr, offs[bj] + c, r.hessian(6 * bi + rr, 6 * bj + c));
      }
    }
  }
  st.energy = energy;
  if (stats) *stats = st;
  return energy;
}

}  // namespace superdex
