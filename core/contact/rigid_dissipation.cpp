#include "core/contact/rigid_dissipation.h"

#include <cmath>

#include "core/contact/dissipation_kernels.h"
#include "core/model/rigid_math.h"

namespace superdex {
namespace {
using namespace dissipation_kernels;

/// One sample of a current-geometry mode. Its world residual is
///   [f_A, r × f_A, −f_A, −d × f_A],   f_A = R_B g(Y, N_A),   g = ∂R/∂V (dissipation_kernels.h),
/// with r = R_A X, d = p_A + r − p_B, Y = R_Bᵀ d and N_A = R_Bᵀ R_A n_A (6 or 12 entries).
/// S M for a skew S (zero diagonal) and a 3×N block M: each entry sums the two products with
/// S's nonzero entries (the third term of a full product is a product with 0).
template <int N>
Eigen::Matrix<double, 3, N> SkewTimes(const Eigen::Matrix3d& S, const Eigen::Matrix<double, 3, N>& M) {
  Eigen::Matrix<double, 3, N> out;
  for (int j = 0; j < N; ++j) {
    out(0, j) = S(0, 1) * M(1, j) + S(0, 2) * M(2, j);
    out(1, j) = S(1, 2) * M(2, j) + S(1, 0) * M(0, j);
    out(2, j) = S(2, 0) * M(0, j) + S(2, 1) * M(1, j);
  }
  return out;
}

struct CurrentModeSample {
  Eigen::Vector3d NA;         // A's normal in B's frame, R_Bᵀ R_A n_A (the kernel's N_A)
  Eigen::Vector3d Y;          // current pullback at δ = 0
  Eigen::Vector3d Y0;         // stage-start pullback (velocity reference)
  Eigen::Vector3d Yn;         // pullback at the last actual configuration (geometry reference)
  SdfSample field;            // Φ_B, G, ∇²Φ_B at Y
  const DissipationSetup* setup = nullptr;

  /// Adds w ∂residual/∂δ (δ = [δp_A, δθ_A, δp_B, δθ_B], retractions p + δp, (1 + [δθ]×) R) into
  /// the pair's sums (PairForceJacobianSums; rB = R_Bᵀ R_A X). The kernel g is differentiated in
  /// its six arguments (Y, N_A) in closed form (LinearizeCurrentModeGradient, tested against
  /// forward-mode AD); the chain to the stencil is analytic:
  ///   dY = R_Bᵀ (δp_A − [r]× δθ_A − δp_B + [d]× δθ_B),   dN_A = R_Bᵀ [n_w]× (δθ_B − δθ_A),
  ///   df = R_B (G_Y dY + G_N dN_A) − [f]× δθ_B,   dr = −[r]× δθ_A,   dd = δp_A − [r]× δθ_A − δp_B,
  ///   d(r × f) = [r]× df − [f]× dr,   d(−d × f) = [f]× dd − [d]× df        (n_w = R_A n_A).
  void AddTo(double w, const Eigen::Vector3d& rB, PairForceJacobianSums* sums) const {
    const CurrentModeLinearization lin =
        LinearizeCurrentModeGradient(Y, NA, field, Yn, Y0, *setup);
    sums->Add(rB, NA, lin.g, lin.GY, lin.GN, w);
  }
};

}  // namespace

void PairForceJacobianSums::Add(const Eigen::Vector3d& rB, const Eigen::Vector3d& nB,
                                const Eigen::Vector3d& g, const Eigen::Matrix3d& GY,
                                const Eigen::Matrix3d& GN, double w) {
  const Eigen::Matrix3d S = Skew(rB);
  const Eigen::Matrix3d M = w * GY;
  const Eigen::Matrix3d Q = SkewTimes<3>(Skew(nB).transpose(), (w * GN).transpose()).transpose();
  const Eigen::Vector3d wg = w * g;
  const Eigen::Matrix3d MS = SkewTimes<3>(S.transpose(), M.transpose()).transpose();  // M S
  M_ += M;
  MS_ += MS;
  SM_ += SkewTimes<3>(S, M);
  SMS_ += SkewTimes<3>(S, MS);
  Q_ += Q;
  SQ_ += SkewTimes<3>(S, Q);
  // [a]×[b]× = b aᵀ − (a·b) I.
  const double ab = wg.dot(rB);
  FS_ += rB * wg.transpose() - ab * Eigen::Matrix3d::Identity();
  empty_ = false;
  if (!bDynamic_) return;
  F_ += Skew(wg);
  SF_ += wg * rB.transpose() - ab * Eigen::Matrix3d::Identity();
}

void PairForceJacobianSums::AddTo(const Eigen::Matrix3d& RB, const Eigen::Vector3d& c,
                                  PairMatrix* J) const {
  if (empty_) return;
  const Eigen::Matrix3d RBt = RB.transpose();
  auto world = [&](const Eigen::Matrix3d& X) -> Eigen::Matrix3d { return RB * X * RBt; };
  const Eigen::Matrix3d M = world(M_), MS = world(MS_), SM = world(SM_), SMS = world(SMS_),
                        Q = world(Q_), SQ = world(SQ_), FS = world(FS_);
  J->block<3, 3>(0, 0) += M;
  J->block<3, 3>(0, 3) -= MS + Q;
  J->block<3, 3>(3, 0) += SM;
  J->block<3, 3>(3, 3) += FS - SMS - SQ;
  if (!bDynamic_) return;
  const Eigen::Matrix3d F = world(F_), SF = world(SF_);
  const Eigen::Matrix3d Sc = Skew(c);
  // The rows [df; [r]× df − [f]× dr; −df; [f]× dd − [d]× df] summed over the samples, with df's
  // last block M [d]× + Q − F = M [c]× + MS + Q − F and [d]× X summed as [c]× ΣX + Σ S X.
  const Eigen::Matrix3d D9 = M * Sc + MS + Q - F;   // Σ w df₉
  const Eigen::Matrix3d SD9 = SM * Sc + SMS + SQ - SF;  // Σ [r]× w df₉
  J->block<3, 3>(0, 6) -= M;
  J->block<3, 3>(0, 9) += D9;
  J->block<3, 3>(3, 6) -= SM;
  J->block<3, 3>(3, 9) += SD9;
  J->block<3, 3>(6, 0) -= M;
  J->block<3, 3>(6, 3) += MS + Q;
  J->block<3, 3>(6, 6) += M;
  J->block<3, 3>(6, 9) -= D9;
  const Eigen::Matrix3d dM = Sc * M + SM;  // Σ [d]× M
  J->block<3, 3>(9, 0) += F - dM;
  J->block<3, 3>(9, 3) += Sc * (MS + Q) + SMS + SQ - FS;
  J->block<3, 3>(9, 6) += dM - F;
  J->block<3, 3>(9, 9) -= Sc * D9 + SD9;
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
  // The load is read at the last actual pullback Y_n: explicit normals by definition, and the
  // reconstructed load φ + G·(Y_n − Y) of an affine field (a plane), which is Φ(Y_n) exactly.
  // Culling by Φ(Y_n) is then exact, where the general bound φ − L|Y_n − Y| lets through every
  // sample within the stage's motion of the collider.
  const bool loadAtLast =
      explicitNormals || (setup.mode == DissipationMode::ReconstructedLoad &&
                          B.collider.type == ColliderType::Plane);

  // Whole-pair rejection (exact SDFs are 1-Lipschitz): no sample of A can carry a load when both
  // A's current and last actual sample clouds stay farther than δ from B.
  const double L = B.collider.lipschitz;
  const bool nearThen = B.collider.Value(YnA) - L * A.samplesRadius < delta;
  if (loadAtLast ? !nearThen
                 : !(nearThen || B.collider.Value(YA) - L * A.samplesRadius < delta))
    return;

  CurrentModeSample sample;
  sample.setup = &setup;

  // Cluster culling bounds (1-Lipschitz fields): the reconstructed distance φ + G·(Y_n − Y) is at
  // least φ − |Y_n − Y|, and |Y_n − Y| <= |Y_n,A − Y_A| + ‖R_n,BᵀR_n,A − R_BᵀR_A‖_F |X|.
  const double shift = (YnA - YA).norm() + (RnBtRA - RBtRA).norm() * A.samplesRadius;
  const double slack = setup.mode == DissipationMode::ImplicitLoad ? 0.0 : L * shift;
  // The per-sample reach test below (no load where both Y and Y_n lie beyond B's bounding
  // sphere + δ) applied to a whole node: its samples lie within `radius` of its centre (the
  // margin keeps the node test from rejecting a sample that the sample test, in its own
  // rounding, would keep). The slack of the current-pose bound is the whole body's motion, so
  // without this the nodes of a ball moving past another all pass (the landing of a pile).
  const double nodeReach = reach * (1.0 + 1e-12);
  auto near = [&](const Eigen::Vector3d& center, double radius) {
    if (loadAtLast)
      return B.collider.Value(YnA + RnBtRA * center) - L * radius < delta;
    const Eigen::Vector3d Yc = YA + RBtRA * center;
    if (finiteReach && Yc.norm() - radius >= nodeReach &&
        (YnA + RnBtRA * center).norm() - radius >= nodeReach)
      return false;
    return B.collider.Value(Yc) - L * radius - slack < delta;
  };
  // Accumulated in fixed-size stencils, copied out at the end.
  PairVector residual = PairVector::Zero();
  PairMatrix jacobian;
  if (order >= 2) jacobian.setZero();
  PairHessianSums sums;  // explicit normals: the Hessian of the potential
  PairForceJacobianSums forceSums(bDynamic);  // current modes: the residual's Jacobian
  ForEachSampleRange(A, near, [&](int begin, int end) {
    for (int k = begin; k < end; ++k) {
      const SurfaceSample& q = A.samples[k];
      const Eigen::Vector3d Y = YA + RBtRA * q.X;
      const Eigen::Vector3d Yn = YnA + RnBtRA * q.X;
      double lambdaHat = 0.0;
      Eigen::Vector3d N;
      if (explicitNormals) {
        if (finiteReach && Yn.squaredNorm() >= reach * reach) continue;
        SdfSample f0;
        if (!B.collider.EvaluateBelow(Yn, delta, &f0)) continue;
        const Eigen::Vector3d NA0 = RnBtRA * q.normal;
        const double s = f0.gradient.dot(NA0);
        if (s > m + kAlignmentRoundoff) continue;  // rejected
        lambdaHat =
            AlignmentFactor(s, setup) * NormalPenaltyDensity(f0.value, setup.penalty).lambdaN;
        N = SplitDirection(f0.gradient, NA0, setup);
      } else {
        if (finiteReach && Y.squaredNorm() >= reach * reach && Yn.squaredNorm() >= reach * reach)
          continue;
        if (loadAtLast && B.collider.Value(Yn) >= delta) continue;  // φ_load = Φ(Y_n) >= δ
        // φ_load >= φ − L |Y_n − Y| (ReconstructedLoad): no load where that bound reaches δ.
        SdfSample f;
        const double reachLoad = setup.mode == DissipationMode::ImplicitLoad
                                     ? delta
                                     : delta + L * (Yn - Y).norm();
        if (!B.collider.EvaluateBelow(Y, reachLoad, &f)) continue;
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
        sample.NA = NA;
        sample.Y = Y;
        sample.Yn = Yn;
        sample.field = f;
      }
      if (lambdaHat == 0.0) continue;
      ++out->activeSamples;
      const Eigen::Vector3d Y0 = Y0A + R0BinvRA * q.X;
      sample.Y0 = Y0;
      const Eigen::Vector3d V = (Y - Y0) / dt;
      const DissipationDensity D = EvaluateSampleDissipation(
          lambdaHat, N, V, setup.coefficients, setup.HessianKind(explicitNormals && order >= 2),
          setup.slips, k);
      out->value += q.weight * dt * D.R;
      if (setup.coefficients.mu > 0.0 && lambdaHat > 0.0)
        out->maxCoulombRatio = std::max(
            out->maxCoulombRatio, D.coulomb.norm() / (setup.coefficients.mu * lambdaHat));
      if (order == 0) continue;
      const Eigen::Vector3d r = a.R * q.X;
      const Eigen::Vector3d d = a.p + r - b.p;
      // ∂(Δt R)/∂Y = ∂R/∂V;  with explicit normals ∂²(Δt R)/∂Y² = ∂²R/∂V² / Δt.
      AddFunctionOfPullback(r, d, b.R, D.gradient, nullptr, bDynamic, q.weight, &residual, nullptr);
      if (order < 2) continue;
      if (explicitNormals)
        sums.Add(Y - YA, D.gradient, D.hessian / dt, q.weight);
      else
        sample.AddTo(q.weight, Y - YA, &forceSums);
    }
  });
  out->residual = residual.head(n);
  if (order >= 2) {
    sums.AddTo(b.R, a.p - b.p, bDynamic, &jacobian);
    forceSums.AddTo(b.R, a.p - b.p, &jacobian);
    out->jacobian = jacobian.topLeftCorner(n, n);
  }
}

}  // namespace superdex
