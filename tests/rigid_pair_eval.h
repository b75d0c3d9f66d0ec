// One rigid pair (a colliding body A on a rigid collider B) evaluated by the contact assembler
// (core/contact/kind_contact.h) as the contact pipeline evaluates it: A's samples gathered and
// culled on B's frame, then EvaluateSamplesOnFrame. The penalty and the dissipation parts are
// returned separately, on the stencil [δp_A, δθ_A] (B static) or [δp_A, δθ_A, δp_B, δθ_B].
#pragma once

#include <vector>

#include "core/contact/kind_contact.h"

namespace superdex::test {

struct RigidPairPenalty {
  double value = 0.0;        ///< Σ w W [J]
  Eigen::VectorXd gradient;  ///< [N, N·m]
  Eigen::MatrixXd hessian;   ///< unprojected
  int activeSamples = 0;
  double minPhi = INFINITY;
};

struct RigidPairDissipation {
  double value = 0.0;        ///< Δt_i Σ w R [J]
  Eigen::VectorXd residual;  ///< w J_Yᵀ ∂R/∂V summed
  Eigen::MatrixXd jacobian;  ///< explicit normals: the Hessian of value; else ∂residual/∂δ
  int activeSamples = 0;
  double maxCoulombRatio = 0.0;
};

/// The pair's stencils at the poses (aRef, bRef: x_n, the alignment test's reference; null: the
/// current poses) with `setup` (null: penalty only; then aStart/bStart may be null).
inline PairStencils EvaluateRigidPair(const RigidBodyModel& A, const RigidPose& a,
                                      const RigidStageStart* aStart, const RigidBodyModel& B,
                                      const RigidPose& b, const RigidStageStart* bStart,
                                      bool bDynamic, const PenaltyParams& penalty,
                                      double maxAlignment, const DissipationSetup* setup,
                                      int order,
                                      std::vector<ContactSampleRecord>* records = nullptr) {
  const FrameSide side = RigidFrameSide(B, b, bStart, bDynamic ? 6 : -1);
  std::vector<PairSample> samples;
  GatherRigidSamples(A, a, aStart, 0, side, penalty.delta, setup, &samples);
  PairStencils out;
  EvaluateSamplesOnFrame(samples, side, penalty, maxAlignment, setup, order, &out, records);
  return out;
}

inline RigidStageStart StartAt(const RigidPose& now, const RigidPose& last) {
  RigidStageStart s;
  s.p = now.p;
  s.R = now.R;
  s.Rinv = now.R.transpose();
  s.last = last;
  return s;
}

/// The penalty of A's samples in B's field (the alignment test at aRef, bRef when given).
inline void EvaluateRigidPairPenalty(const RigidBodyModel& A, const RigidPose& a,
                                     const RigidBodyModel& B, const RigidPose& b, bool bDynamic,
                                     const PenaltyParams& params, int order,
                                     RigidPairPenalty* out, double maxAlignment = INFINITY,
                                     const RigidPose* aRef = nullptr,
                                     const RigidPose* bRef = nullptr,
                                     std::vector<ContactSampleRecord>* records = nullptr) {
  const int n = bDynamic ? 12 : 6;
  const bool reference = aRef || bRef;
  const RigidStageStart as = StartAt(a, aRef ? *aRef : a), bs = StartAt(b, bRef ? *bRef : b);
  const PairStencils r = EvaluateRigidPair(A, a, reference ? &as : nullptr, B, b,
                                           reference ? &bs : nullptr, bDynamic, params,
                                           maxAlignment, nullptr, order, records);
  out->value = r.penaltyValue;
  out->activeSamples = r.activeSamples;
  out->minPhi = r.minPhi;
  out->gradient.setZero(n);
  out->hessian.setZero(n, n);
  for (int e = 0; e < r.count; ++e) {
    const ContactStencil& st = r.stencils[e];
    if (!st.penaltyActive) continue;
    if (order >= 1) out->gradient += st.penaltyGradient;
    if (order >= 2) out->hessian += st.penaltyHessian;
  }
}

/// The stage-discrete dissipation of A's samples on B with the stage starts a0, b0.
inline void EvaluateRigidPairDissipation(const RigidBodyModel& A, const RigidPose& a,
                                         const RigidStageStart& a0, const RigidBodyModel& B,
                                         const RigidPose& b, const RigidStageStart& b0,
                                         bool bDynamic, const DissipationSetup& setup, int order,
                                         RigidPairDissipation* out) {
  const int n = bDynamic ? 12 : 6;
  const PairStencils r = EvaluateRigidPair(A, a, &a0, B, b, &b0, bDynamic, setup.penalty,
                                           setup.maxAlignment, &setup, order);
  out->value = r.dissipationValue;
  out->activeSamples = r.dissipativeSamples;
  out->maxCoulombRatio = r.maxCoulombRatio;
  out->residual.setZero(n);
  out->jacobian.setZero(n, n);
  for (int e = 0; e < r.count; ++e) {
    const ContactStencil& st = r.stencils[e];
    if (!st.dissipationActive) continue;
    if (order >= 1) out->residual += st.dissipationResidual;
    if (order >= 2) out->jacobian += st.dissipationJacobian;
  }
}

}  // namespace superdex::test
