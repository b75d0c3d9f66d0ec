// One rigid pair (a colliding body A on a rigid collider B) evaluated by the contact assembler
// (core/contact/kind_contact.h) as the contact pipeline evaluates it: both bodies as RigidKinds,
// A's samples gathered and culled on B's frame (GatherKindSamples, KindFrameSide), then
// EvaluateSamplesOnFrame. The penalty and the dissipation parts are returned separately, on the
// stencil [δp_A, δθ_A] (B static) or [δp_A, δθ_A, δp_B, δθ_B].
#pragma once

#include <stdexcept>
#include <vector>

#include "core/contact/kind_contact.h"
#include "core/model/rigid_kind.h"
#include "core/model/rigid_math.h"

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

/// The model of rigid body `d` (throws on a description BuildRigidBody refuses).
inline RigidBodyModel BodyModel(const RigidActorDesc& d) {
  RigidBodyModel m;
  RigidBodyState s;
  Error e;
  if (!BuildRigidBody(d, "", &m, &s, &e)) throw std::runtime_error(e.message);
  return m;
}

/// A sphere "a" of radius r [m] at surface resolution `resolution`, its penalty's surface
/// integral `integral`.
inline RigidBodyModel SphereModel(double r, bool dynamic, SurfaceIntegral integral,
                                  int resolution) {
  RigidActorDesc d;
  d.name = "a";
  d.dynamic = dynamic;
  d.shape.kind = RigidShapeKind::Sphere;
  d.shape.radius = r;
  d.shape.surfaceResolution = resolution;
  d.surfaceIntegral = integral;
  return BodyModel(d);
}

/// Both poses retracted by a pair stencil's step d = [δp_A, δθ_A (, δp_B, δθ_B)]: p += δp,
/// R ← Exp(δθ) R (B's part only when B is dynamic).
inline void RetractPair(const Eigen::VectorXd& d, bool bDynamic, RigidPose* a, RigidPose* b) {
  a->p += d.segment<3>(0);
  a->R = ExpSo3(d.segment<3>(3)) * a->R;
  if (!bDynamic) return;
  b->p += d.segment<3>(6);
  b->R = ExpSo3(d.segment<3>(9)) * b->R;
}

/// A rigid configuration q = [p, R column-major] (RigidKind::Pack).
inline Eigen::VectorXd PoseQ(const RigidPose& pose) {
  return RigidKind::Pack(RigidBodyState{pose.p, pose.R}).x;
}

/// A body's side of a pair as its RigidKind sees it: q, x_n (qLast) and x⁰ (q0) from its pose
/// and stage start (null start: neither), and its stage dofs from `first` (−1: none).
struct RigidSide {
  RigidKind kind;
  Eigen::VectorXd q, qLast, q0;
  bool hasStart = false;
  std::vector<int> stageDof;
  RigidSide(const RigidBodyModel& m, const RigidPose& pose, const RigidStageStart* start,
            int first)
      : kind(m, RigidBodyState()), q(PoseQ(pose)), hasStart(start != nullptr),
        stageDof(6, -1) {
    if (start) {
      qLast = PoseQ(start->last);
      q0 = PoseQ({start->p, start->R});
    }
    if (first >= 0)
      for (int i = 0; i < 6; ++i) stageDof[i] = first + i;
  }
  const Eigen::VectorXd* Last() const { return hasStart ? &qLast : nullptr; }
  const Eigen::VectorXd* Start() const { return hasStart ? &q0 : nullptr; }
};

/// The pair's stencils at the poses (aStart, bStart: x⁰ and x_n, x_n the alignment test's
/// reference; null: the current poses) with `setup` (null: penalty only; then aStart/bStart may
/// be null). `streamed`: A's samples fed straight into a FrameEvaluation, as the pipeline does
/// (there an exact sphere's closed form and cap quadrature replace its samples); else listed
/// first, then EvaluateSamplesOnFrame.
inline PairStencils EvaluateRigidPair(const RigidBodyModel& A, const RigidPose& a,
                                      const RigidStageStart* aStart, const RigidBodyModel& B,
                                      const RigidPose& b, const RigidStageStart* bStart,
                                      bool bDynamic, const PenaltyParams& penalty,
                                      double maxAlignment, const DissipationSetup* setup,
                                      int order,
                                      std::vector<ContactSampleRecord>* records = nullptr,
                                      bool streamed = false) {
  const RigidSide sa(A, a, aStart, 0), sb(B, b, bStart, bDynamic ? 6 : -1);
  const FrameSide side =
      KindFrameSide(sb.kind, sb.q, sb.Last(), setup ? sb.Start() : nullptr, sb.stageDof);
  const Eigen::VectorXd* aStartQ = setup ? sa.Start() : nullptr;
  PairStencils out;
  if (streamed) {
    FrameEvaluation evaluation(side, penalty, maxAlignment, setup, order, &out, records);
    GatherKindSamples(sa.kind, sa.q, sa.Last(), aStartQ, sa.stageDof, side, penalty.delta, setup,
                      &evaluation);
    evaluation.Finish();
    return out;
  }
  std::vector<PairSample> samples;
  SampleList list(&samples);
  GatherKindSamples(sa.kind, sa.q, sa.Last(), aStartQ, sa.stageDof, side, penalty.delta, setup,
                    &list);
  EvaluateSamplesOnFrame(samples, side, penalty, maxAlignment, setup, order, &out, records);
  return out;
}

/// StepLimitSink's α for rigid body A's move a0 → a1 on rigid body B's field, B moving b0 → b1,
/// as the contact pipeline's StepLimits forms it (each side at the trial configuration with the
/// current one as its x_n).
inline double RigidPairStepLimit(const RigidBodyModel& A, const RigidPose& a0, const RigidPose& a1,
                                 const RigidBodyModel& B, const RigidPose& b0, const RigidPose& b1,
                                 const PenaltyParams& params) {
  RigidStageStart aNow, bNow;
  aNow.last = a0;
  bNow.last = b0;
  const RigidSide sa(A, a1, &aNow, -1), sb(B, b1, &bNow, -1);
  const FrameSide side = KindFrameSide(sb.kind, sb.q, sb.Last(), nullptr, sb.stageDof);
  StepLimitSink sink(side, params);
  GatherKindSamples(sa.kind, sa.q, sa.Last(), nullptr, sa.stageDof, side,
                    params.delta - 0.5 * params.eps, nullptr, &sink);
  return sink.Alpha();
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

/// The dissipative parts of a pair's stencils (on n = 6 or 12 dofs) summed into *out.
inline void SumDissipation(const PairStencils& r, int n, int order, RigidPairDissipation* out) {
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

/// The stage-discrete dissipation of A's samples on B with the stage starts a0, b0.
inline void EvaluateRigidPairDissipation(const RigidBodyModel& A, const RigidPose& a,
                                         const RigidStageStart& a0, const RigidBodyModel& B,
                                         const RigidPose& b, const RigidStageStart& b0,
                                         bool bDynamic, const DissipationSetup& setup, int order,
                                         RigidPairDissipation* out) {
  const PairStencils r = EvaluateRigidPair(A, a, &a0, B, b, &b0, bDynamic, setup.penalty,
                                           setup.maxAlignment, &setup, order);
  SumDissipation(r, bDynamic ? 12 : 6, order, out);
}

}  // namespace superdex::test
