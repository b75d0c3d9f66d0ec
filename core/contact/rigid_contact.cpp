#include "core/contact/rigid_contact.h"

#include <algorithm>
#include <cmath>

#include "core/contact/sample_chain.h"
#include "core/model/rigid_math.h"

namespace superdex {
namespace {

/// X K for a skew K (zero diagonal): each entry sums the two products with K's nonzero entries.
Eigen::Matrix3d TimesSkew(const Eigen::Matrix3d& X, const Eigen::Matrix3d& K) {
  Eigen::Matrix3d out;
  for (int i = 0; i < 3; ++i) {
    out(i, 0) = X(i, 1) * K(1, 0) + X(i, 2) * K(2, 0);
    out(i, 1) = X(i, 2) * K(2, 1) + X(i, 0) * K(0, 1);
    out(i, 2) = X(i, 0) * K(0, 2) + X(i, 1) * K(1, 2);
  }
  return out;
}

/// Kᵀ X for a skew K: (Kᵀ X)(m, b) = Σ_{k ≠ m} K(k, m) X(k, b).
Eigen::Matrix3d SkewTransposeTimes(const Eigen::Matrix3d& K, const Eigen::Matrix3d& X) {
  Eigen::Matrix3d out;
  for (int b = 0; b < 3; ++b) {
    out(0, b) = K(1, 0) * X(1, b) + K(2, 0) * X(2, b);
    out(1, b) = K(2, 1) * X(2, b) + K(0, 1) * X(0, b);
    out(2, b) = K(0, 2) * X(0, b) + K(1, 2) * X(1, b);
  }
  return out;
}

template <typename Vector, typename Matrix>
void AddFunctionOfPullbackTo(const Eigen::Vector3d& r, const Eigen::Vector3d& d,
                             const Eigen::Matrix3d& RB, const Eigen::Vector3d& gY,
                             const Eigen::Matrix3d* HY, bool bDynamic, double w, Vector* grad,
                             Matrix* hess) {
  const Eigen::Vector3d n = RB * gY;
  grad->template segment<3>(0) += w * n;
  grad->template segment<3>(3) += w * r.cross(n);
  if (bDynamic) {
    grad->template segment<3>(6) -= w * n;
    grad->template segment<3>(9) -= w * d.cross(n);
  }
  if (!hess) return;
  // Jx = ∂x_w/∂δ = [I, K_r, −I, K_d] with the skew blocks K_r = −[r]×, K_d = [d]×, so that
  // Jxᵀ Hw Jx is assembled from 3×3 blocks: Hw, Hw K, Kᵀ Hw, Kᵀ Hw K. Each entry is the sum of
  // the same nonzero products as the full 3×12 matrix products (whose other terms are products
  // with the identity's and the skews' zeros, ±0, and with 1 or −1, exact), so the result is the
  // same to the bit, at a quarter of the multiplications.
  const Eigen::Matrix3d Hw = w * (RB * (*HY) * RB.transpose());
  const Eigen::Matrix3d Kr = -Skew(r);
  const Eigen::Matrix3d HK = TimesSkew(Hw, Kr);
  hess->template block<3, 3>(0, 0) += Hw;
  hess->template block<3, 3>(0, 3) += HK;
  hess->template block<3, 3>(3, 0) += SkewTransposeTimes(Kr, Hw);
  hess->template block<3, 3>(3, 3) += SkewTransposeTimes(Kr, HK);
  if (bDynamic) {
    const Eigen::Matrix3d Kd = Skew(d);
    const Eigen::Matrix3d HKd = TimesSkew(Hw, Kd);
    const Eigen::Matrix3d KrH = SkewTransposeTimes(Kr, Hw);
    const Eigen::Matrix3d KdH = SkewTransposeTimes(Kd, Hw);
    hess->template block<3, 3>(0, 6) -= Hw;
    hess->template block<3, 3>(0, 9) += HKd;
    hess->template block<3, 3>(3, 6) -= KrH;
    hess->template block<3, 3>(3, 9) += SkewTransposeTimes(Kr, HKd);
    hess->template block<3, 3>(6, 0) -= Hw;
    hess->template block<3, 3>(6, 3) -= HK;
    hess->template block<3, 3>(6, 6) += Hw;
    hess->template block<3, 3>(6, 9) -= HKd;
    hess->template block<3, 3>(9, 0) += KdH;
    hess->template block<3, 3>(9, 3) += SkewTransposeTimes(Kd, HK);
    hess->template block<3, 3>(9, 6) -= KdH;
    hess->template block<3, 3>(9, 9) += SkewTransposeTimes(Kd, HKd);
  }
  const Eigen::Vector3d nw = w * n;
  const double nr = nw.dot(r);
  hess->template block<3, 3>(3, 3) +=
      0.5 * (nw * r.transpose() + r * nw.transpose()) - nr * Eigen::Matrix3d::Identity();
  if (bDynamic) {
    const double nd = nw.dot(d);
    const Eigen::Matrix3d Nx = Skew(nw);
    hess->template block<3, 3>(9, 9) +=
        0.5 * (nw * d.transpose() + d * nw.transpose()) - nd * Eigen::Matrix3d::Identity();
    hess->template block<3, 3>(9, 0) += Nx;
    hess->template block<3, 3>(0, 9) += Nx.transpose();
    hess->template block<3, 3>(9, 6) -= Nx;
    hess->template block<3, 3>(6, 9) -= Nx.transpose();
    const Eigen::Matrix3d C = nr * Eigen::Matrix3d::Identity() - r * nw.transpose();
    hess->template block<3, 3>(9, 3) += C;
    hess->template block<3, 3>(3, 9) += C.transpose();
  }
}

}  // namespace

void AddFunctionOfPullback(const Eigen::Vector3d& r, const Eigen::Vector3d& d,
                           const Eigen::Matrix3d& RB, const Eigen::Vector3d& gY,
                           const Eigen::Matrix3d* HY, bool bDynamic, double w,
                           StencilVector* grad, StencilMatrix* hess) {
  AddFunctionOfPullbackTo(r, d, RB, gY, HY, bDynamic, w, grad, hess);
}

void AddFunctionOfPullback(const Eigen::Vector3d& r, const Eigen::Vector3d& d,
                           const Eigen::Matrix3d& RB, const Eigen::Vector3d& gY,
                           const Eigen::Matrix3d* HY, bool bDynamic, double w, PairVector* grad,
                           PairMatrix* hess) {
  AddFunctionOfPullbackTo(r, d, RB, gY, HY, bDynamic, w, grad, hess);
}

void PairHessianSums::Add(const Eigen::Vector3d& rB, const Eigen::Vector3d& gY,
                          const Eigen::Matrix3d& HY, double w) {
  const Eigen::Matrix3d K = -Skew(rB);
  const Eigen::Matrix3d H = w * HY;
  const Eigen::Matrix3d HK = TimesSkew(H, K);
  if (empty_) {
    H0_.setZero();
    H1_.setZero();
    H2_.setZero();
    P_.setZero();
    N_.setZero();
    empty_ = false;
  }
  H0_ += H;
  H1_ += HK;
  H2_ += SkewTransposeTimes(K, HK);
  const Eigen::Vector3d g = w * gY;
  P_ += g * rB.transpose();
  N_ += g;
}

void PairHessianSums::AddTo(const Eigen::Matrix3d& RB, const Eigen::Vector3d& c, bool bDynamic,
                            PairMatrix* hess) const {
  if (empty_) return;
  const Eigen::Matrix3d RBt = RB.transpose();
  const Eigen::Matrix3d A0 = RB * H0_ * RBt, A1 = RB * H1_ * RBt, A2 = RB * H2_ * RBt;
  const Eigen::Matrix3d P = RB * P_ * RBt;  // Σ w n rᵀ (world)
  const Eigen::Vector3d N = RB * N_;         // Σ w n
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  // The retraction curvature Σ (sym(n rᵀ) − (n·r) I) of the rotation block.
  const double pr = P.trace();
  hess->block<3, 3>(0, 0) += A0;
  hess->block<3, 3>(0, 3) += A1;
  hess->block<3, 3>(3, 0) += A1.transpose();
  hess->block<3, 3>(3, 3) += A2 + 0.5 * (P + P.transpose()) - pr * I;
  if (!bDynamic) return;
  const Eigen::Matrix3d Kc = Skew(c);
  const Eigen::Matrix3d A0Kc = A0 * Kc;                 // Σ Hw [c]×
  const Eigen::Matrix3d HKd = A0Kc - A1;               // Σ Hw K_d, K_d = [d]× = [c]× − K_r
  const Eigen::Matrix3d KrHKd = A1.transpose() * Kc - A2;  // Σ K_rᵀ Hw K_d
  const Eigen::Matrix3d KdHKd =
      Kc.transpose() * A0Kc - Kc.transpose() * A1 - A1.transpose() * Kc + A2;
  hess->block<3, 3>(0, 6) -= A0;
  hess->block<3, 3>(0, 9) += HKd;
  hess->block<3, 3>(3, 6) -= A1.transpose();
  hess->block<3, 3>(3, 9) += KrHKd;
  hess->block<3, 3>(6, 0) -= A0;
  hess->block<3, 3>(6, 3) -= A1;
  hess->block<3, 3>(6, 6) += A0;
  hess->block<3, 3>(6, 9) -= HKd;
  hess->block<3, 3>(9, 0) += HKd.transpose();
  hess->block<3, 3>(9, 3) += KrHKd.transpose();
  hess->block<3, 3>(9, 6) -= HKd.transpose();
  hess->block<3, 3>(9, 9) += KdHKd;
  // Retraction curvature: Σ n dᵀ = N cᵀ + P; the [n]× couplings of B's rotation with the
  // translations; C = Σ ((n·r) I − r nᵀ) = tr(P) I − Pᵀ.
  const Eigen::Matrix3d Pd = N * c.transpose() + P;
  hess->block<3, 3>(9, 9) += 0.5 * (Pd + Pd.transpose()) - Pd.trace() * I;
  const Eigen::Matrix3d Nx = Skew(N);
  hess->block<3, 3>(9, 0) += Nx;
  hess->block<3, 3>(0, 9) += Nx.transpose();
  hess->block<3, 3>(9, 6) -= Nx;
  hess->block<3, 3>(6, 9) -= Nx.transpose();
  const Eigen::Matrix3d C = pr * I - P.transpose();
  hess->block<3, 3>(9, 3) += C;
  hess->block<3, 3>(3, 9) += C.transpose();
}


}  // namespace superdex
