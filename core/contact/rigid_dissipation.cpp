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


}  // namespace

void PairForceJacobianSums::Add(const Eigen::Vector3d& rB, const Eigen::Vector3d& nB,
                                const Eigen::Vector3d& g, const Eigen::Matrix3d& GY,
                                const Eigen::Matrix3d& GN, double w) {
  const Eigen::Matrix3d S = Skew(rB);
  const Eigen::Matrix3d M = w * GY;
  const Eigen::Matrix3d Q = SkewTimes<3>(Skew(nB).transpose(), (w * GN).transpose()).transpose();
  const Eigen::Vector3d wg = w * g;
  const Eigen::Matrix3d MS = SkewTimes<3>(S.transpose(), M.transpose()).transpose();  // M S
  if (empty_) {
    for (Eigen::Matrix3d* X : {&M_, &MS_, &SM_, &SMS_, &Q_, &SQ_, &F_, &FS_, &SF_}) X->setZero();
    empty_ = false;
  }
  M_ += M;
  MS_ += MS;
  SM_ += SkewTimes<3>(S, M);
  SMS_ += SkewTimes<3>(S, MS);
  Q_ += Q;
  SQ_ += SkewTimes<3>(S, Q);
  // [a]×[b]× = b aᵀ − (a·b) I.
  const double ab = wg.dot(rB);
  FS_ += rB * wg.transpose() - ab * Eigen::Matrix3d::Identity();
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

}  // namespace superdex
