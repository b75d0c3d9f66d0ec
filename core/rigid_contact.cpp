#include "core/rigid_contact.h"

#include <cmath>

#include "core/rigid_math.h"

namespace superdex {

void EvaluateRigidPairPenalty(const RigidBodyModel& A, const RigidPose& a, const RigidBodyModel& B,
                              const RigidPose& b, bool bDynamic, const PenaltyParams& params,
                              int order, RigidPairPenalty* out) {
  const int n = bDynamic ? 12 : 6;
  out->value = 0.0;
  out->activeSamples = 0;
  out->minPhi = INFINITY;
  out->gradient.setZero(n);
  if (order >= 2) out->hessian.setZero(n, n);
  const double delta = params.delta;
  const double reach = B.collider.boundingRadius + delta;  // |Y| beyond this: φ >= δ
  const Eigen::Matrix3d RBt = b.R.transpose();
  const Eigen::Matrix3d RBtRA = RBt * a.R;
  const Eigen::Vector3d YA = RBt * (a.p - b.p);  // A's centre in B's frame

  // Whole-pair rejection: analytic fields are exact SDFs (1-Lipschitz), so every sample, lying
  // within samplesRadius of A's centre, has φ >= Φ_B(Y_A) − samplesRadius.
  if (B.collider.Evaluate(YA).value - A.samplesRadius >= delta) return;

  StencilVector gradPhi(n);
  StencilMatrix hessPhi;
  if (order >= 2) hessPhi.resize(n, n);
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 12> Jx(3, n);

  for (const SurfaceSample& s : A.samples) {
    const Eigen::Vector3d Y = YA + RBtRA * s.X;
    if (std::isfinite(reach) && Y.squaredNorm() >= reach * reach) continue;
    const SdfSample f = B.collider.Evaluate(Y);
    out->minPhi = std::min(out->minPhi, f.value);
    if (f.value >= delta) continue;
    ++out->activeSamples;
    const PenaltyDensity W = NormalPenaltyDensity(f.value, params);
    if (order == 0) {
      out->value += s.weight * W.W;
      continue;
    }
    const Eigen::Vector3d r = a.R * s.X;
    const Eigen::Vector3d d = a.p + r - b.p;
    const Eigen::Vector3d nw = b.R * f.gradient;
    gradPhi.segment<3>(0) = nw;
    gradPhi.segment<3>(3) = r.cross(nw);
    if (bDynamic) {
      gradPhi.segment<3>(6) = -nw;
      gradPhi.segment<3>(9) = -d.cross(nw);
    }
    if (order >= 2) {
      Jx.leftCols<3>().setIdentity();
      Jx.middleCols<3>(3) = -Skew(r);
      if (bDynamic) {
        Jx.middleCols<3>(6) = -Eigen::Matrix3d::Identity();
        Jx.middleCols<3>(9) = Skew(d);
      }
      const Eigen::Matrix3d Hw = b.R * f.hessian * RBt;
      hessPhi.noalias() = Jx.transpose() * Hw * Jx;
      const double nr = nw.dot(r);
      hessPhi.block<3, 3>(3, 3) +=
          0.5 * (nw * r.transpose() + r * nw.transpose()) - nr * Eigen::Matrix3d::Identity();
      if (bDynamic) {
        const double nd = nw.dot(d);
        const Eigen::Matrix3d Nx = Skew(nw);
        hessPhi.block<3, 3>(9, 9) +=
            0.5 * (nw * d.transpose() + d * nw.transpose()) - nd * Eigen::Matrix3d::Identity();
        hessPhi.block<3, 3>(9, 0) += Nx;
        hessPhi.block<3, 3>(0, 9) += Nx.transpose();
        hessPhi.block<3, 3>(9, 6) -= Nx;
        hessPhi.block<3, 3>(6, 9) -= Nx.transpose();
        const Eigen::Matrix3d C = nr * Eigen::Matrix3d::Identity() - r * nw.transpose();
        hessPhi.block<3, 3>(9, 3) += C;
        hessPhi.block<3, 3>(3, 9) += C.transpose();
      }
    }
    AddNormalPenalty(W, s.weight, gradPhi, hessPhi, &out->value, &out->gradient,
                     order >= 2 ? &out->hessian : nullptr);
  }
}

}  // namespace superdex
