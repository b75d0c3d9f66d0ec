#include "core/rigid_dissipation.h"

#include <cmath>

#include "core/dissipation_kernels.h"

namespace superdex {
namespace {
using namespace dissipation_kernels;

/// One sample of a current-geometry mode, as a function of the stencil's tangent step δ (first
/// order retractions p + δp, (1 + [δθ]×) R, exact for first derivatives at δ = 0).
struct CurrentModeSample {
  const RigidPose* a = nullptr;
  const RigidPose* b = nullptr;
  Eigen::Vector3d X, normal;  // body frame of A
  Eigen::Vector3d Y;          // current pullback at δ = 0
  Eigen::Vector3d Y0;         // stage-start pullback (velocity reference)
  Eigen::Vector3d Yn;         // pullback at the last actual configuration (geometry reference)
  SdfSample field;            // Φ_B, G, ∇²Φ_B at Y
  const DissipationSetup* setup = nullptr;
  bool bDynamic = false;

  /// World residual [f_A, r × f_A, −f_A, −d × f_A] with f_A = R_B ∂R/∂V (n = 6 or 12 entries).
  template <typename T>
  void Residual(const T* delta, T* out) const {
    const DissipationSetup& s = *setup;
    const Vec3<T> dpA(delta[0], delta[1], delta[2]);
    const Vec3<T> dthA(delta[3], delta[4], delta[5]);
    const Mat3<T> RA0 = a->R.cast<T>();
    const Mat3<T> RA = RA0 + SkewT<T>(dthA) * RA0;
    const Vec3<T> pA = a->p.cast<T>() + dpA;
    Mat3<T> RB = b->R.cast<T>();
    Vec3<T> pB = b->p.cast<T>();
    if (bDynamic) {
      const Vec3<T> dpB(delta[6], delta[7], delta[8]);
      const Vec3<T> dthB(delta[9], delta[10], delta[11]);
      RB = RB + SkewT<T>(dthB) * RB;
      pB = pB + dpB;
    }
    const Vec3<T> r = RA * X.cast<T>();
    const Vec3<T> d = pA + r - pB;
    const Vec3<T> Yt = RB.transpose() * d;
    // Alignment s = G·N_A with N_A = R_Bᵀ R_A n_A (raw vectors).
    const Vec3<T> NA = RB.transpose() * (RA * normal.cast<T>());
    const Vec3<T> g = CurrentModeDissipationGradient<T>(Yt, NA, Y, field, Yn, Y0, s);
    const Vec3<T> f = RB * g;
    const Vec3<T> tau = r.cross(f);
    for (int k = 0; k < 3; ++k) {
      out[k] = f[k];
      out[3 + k] = tau[k];
    }
    if (bDynamic) {
      const Vec3<T> tauB = d.cross(f);
      for (int k = 0; k < 3; ++k) {
        out[6 + k] = -f[k];
        out[9 + k] = -tauB[k];
      }
    }
  }
};

}  // namespace

const char* ToString(DissipationMode mode) {
  switch (mode) {
    case DissipationMode::ExplicitNormals: return "ExplicitNormals";
    case DissipationMode::ReconstructedLoad: return "ReconstructedLoad";
    case DissipationMode::ImplicitLoad: return "ImplicitLoad";
  }
  return "Unknown";
}

void EvaluateRigidPairDissipation(const RigidBodyModel& A, const RigidPose& a,
                                  const RigidStageStart& a0, const RigidBodyModel& B,
                                  const RigidPose& b, const RigidStageStart& b0, bool bDynamic,
                                  const DissipationSetup& setup, int order,
                                  RigidPairDissipation* out) {
  const int n = bDynamic ? 12 : 6;
  out->value = 0.0;
  out->activeSamples = 0;
  out->maxCoulombRatio = 0.0;
  out->residual.setZero(n);
  if (order >= 2) out->jacobian.setZero(n, n);
  if (!setup.coefficients.Any()) return;
  const double delta = setup.penalty.delta;
  const double dt = setup.dt;
  const double m = setup.maxAlignment;
  const double reach = B.collider.boundingRadius + delta;
  const bool finiteReach = std::isfinite(reach);
  const Eigen::Matrix3d RBt = b.R.transpose();
  const Eigen::Matrix3d RBtRA = RBt * a.R;
  const Eigen::Vector3d YA = RBt * (a.p - b.p);
  const Eigen::Matrix3d R0BinvRA = b0.Rinv * a0.R;
  const Eigen::Vector3d Y0A = b0.Rinv * (a0.p - b0.p);
  const Eigen::Matrix3d RnBtRA = b0.last.R.transpose() * a0.last.R;
  const Eigen::Vector3d YnA = b0.last.R.transpose() * (a0.last.p - b0.last.p);
  const bool explicitNormals = setup.mode == DissipationMode::ExplicitNormals;

  // Whole-pair rejection (exact SDFs are 1-Lipschitz): no sample of A can carry a load when both
  // A's current and last actual sample clouds stay farther than δ from B.
  const double L = B.collider.lipschitz;
  const bool nearNow = B.collider.Evaluate(YA).value - L * A.samplesRadius < delta;
  const bool nearThen = B.collider.Evaluate(YnA).value - L * A.samplesRadius < delta;
  if (explicitNormals ? !nearThen : !(nearNow || nearThen)) return;

  CurrentModeSample sample;
  sample.a = &a;
  sample.b = &b;
  sample.setup = &setup;
  sample.bDynamic = bDynamic;

  // Cluster culling bounds (1-Lipschitz fields): the reconstructed distance φ + G·(Y_n − Y) is at
  // least φ − |Y_n − Y|, and |Y_n − Y| <= |Y_n,A − Y_A| + ‖R_n,BᵀR_n,A − R_BᵀR_A‖_F |X|.
  const double shift = (YnA - YA).norm() + (RnBtRA - RBtRA).norm() * A.samplesRadius;
  for (const SampleCluster& c : A.sampleClusters) {
    if (explicitNormals) {
      if (B.collider.Evaluate(YnA + RnBtRA * c.center).value - L * c.radius >= delta) continue;
    } else {
      const double slack = setup.mode == DissipationMode::ImplicitLoad ? 0.0 : L * shift;
      if (B.collider.Evaluate(YA + RBtRA * c.center).value - L * c.radius - slack >= delta)
        continue;
    }
    for (int k = c.begin; k < c.end; ++k) {
      const SurfaceSample& q = A.samples[k];
      const Eigen::Vector3d Y = YA + RBtRA * q.X;
      const Eigen::Vector3d Y0 = Y0A + R0BinvRA * q.X;
      const Eigen::Vector3d Yn = YnA + RnBtRA * q.X;
      double lambdaHat = 0.0;
      Eigen::Vector3d N;
      if (explicitNormals) {
        if (finiteReach && Yn.squaredNorm() >= reach * reach) continue;
        const SdfSample f0 = B.collider.Evaluate(Yn);
        if (f0.value >= delta) continue;
        const Eigen::Vector3d NA0 = RnBtRA * q.normal;
        const double s = f0.gradient.dot(NA0);
        if (s > m + kAlignmentRoundoff) continue;  // rejected
        lambdaHat =
            AlignmentFactor(s, setup) * NormalPenaltyDensity(f0.value, setup.penalty).lambdaN;
        N = SplitDirection(f0.gradient, NA0, setup);
      } else {
        if (finiteReach && Y.squaredNorm() >= reach * reach && Yn.squaredNorm() >= reach * reach)
          continue;
        const SdfSample f = B.collider.Evaluate(Y);
        const double phiLoad = setup.mode == DissipationMode::ImplicitLoad
                                   ? f.value
                                   : f.value + f.gradient.dot(Yn - Y);
        if (phiLoad >= delta) continue;
        const Eigen::Vector3d NA = RBtRA * q.normal;
        const double s = f.gradient.dot(NA);
        if (s > m + kAlignmentRoundoff) continue;
        lambdaHat =
            AlignmentFactor(s, setup) * NormalPenaltyDensity(phiLoad, setup.penalty).lambdaN;
        N = SplitDirection(f.gradient, NA, setup);
        sample.X = q.X;
        sample.normal = q.normal;
        sample.Y = Y;
        sample.Y0 = Y0;
        sample.Yn = Yn;
        sample.field = f;
      }
      if (lambdaHat == 0.0) continue;
      ++out->activeSamples;
      const Eigen::Vector3d V = (Y - Y0) / dt;
      const DissipationDensity D =
          EvaluateDissipation(lambdaHat, N, V, setup.coefficients, explicitNormals && order >= 2);
      out->value += q.weight * dt * D.R;
      if (setup.coefficients.mu > 0.0 && lambdaHat > 0.0)
        out->maxCoulombRatio = std::max(
            out->maxCoulombRatio, D.coulomb.norm() / (setup.coefficients.mu * lambdaHat));
      if (order == 0) continue;
      const Eigen::Vector3d r = a.R * q.X;
      const Eigen::Vector3d d = a.p + r - b.p;
      if (explicitNormals) {
        // ∂(Δt R)/∂Y = ∂R/∂V;  ∂²(Δt R)/∂Y² = ∂²R/∂V² / Δt.
        const Eigen::Matrix3d HY = D.hessian / dt;
        AddFunctionOfPullback(r, d, b.R, D.gradient, order >= 2 ? &HY : nullptr, bDynamic,
                              q.weight, &out->residual, order >= 2 ? &out->jacobian : nullptr);
      } else {
        AddFunctionOfPullback(r, d, b.R, D.gradient, nullptr, bDynamic, q.weight, &out->residual,
                              nullptr);
        if (order >= 2) {
          if (bDynamic) {
            AddResidualJacobian<12>(sample, q.weight, &out->jacobian);
          } else {
            AddResidualJacobian<6>(sample, q.weight, &out->jacobian);
          }
        }
      }
    }
  }
}

}  // namespace superdex
