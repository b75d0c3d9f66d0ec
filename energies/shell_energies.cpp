#include "energies/shell_energies.h"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "energies/psd_projection.h"
#include "geometry/skew.h"

namespace superdex {
namespace {

using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat9 = Eigen::Matrix<double, 9, 9>;
using Mat6 = Eigen::Matrix<double, 6, 6>;


// P = ∂ψ/∂F of StVK for F (3 × 2) and ψ itself.
double StvkStress(const Eigen::Matrix<double, 3, 2>& F, const LameParameters& p,
                  Eigen::Matrix<double, 3, 2>* P) {
  const Eigen::Matrix2d E = 0.5 * (F.transpose() * F - Eigen::Matrix2d::Identity());
  const double trE = E.trace();
  const Eigen::Matrix2d S = 2.0 * p.mu * E + p.lambda * trE * Eigen::Matrix2d::Identity();
  if (P) *P = F * S;
  return p.mu * E.squaredNorm() + 0.5 * p.lambda * trE * trE;
}

// ∂²ψ/∂F² of StVK (6 × 6 over column-major vec F: F_ij at i + 3j).
Mat6 StvkStressDerivative(const Eigen::Matrix<double, 3, 2>& F, const LameParameters& p) {
  const Eigen::Matrix2d E = 0.5 * (F.transpose() * F - Eigen::Matrix2d::Identity());
  const Eigen::Matrix2d S = 2.0 * p.mu * E + p.lambda * E.trace() * Eigen::Matrix2d::Identity();
  Mat6 D;
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 3, 2> dF = Eigen::Matrix<double, 3, 2>::Zero();
    dF(k % 3, k / 3) = 1.0;
    const Eigen::Matrix2d dE = 0.5 * (dF.transpose() * F + F.transpose() * dF);
    const Eigen::Matrix2d dS = 2.0 * p.mu * dE + p.lambda * dE.trace() * Eigen::Matrix2d::Identity();
    const Eigen::Matrix<double, 3, 2> dP = dF * S + F * dS;
    for (int j = 0; j < 6; ++j) D(j, k) = dP(j % 3, j / 3);
  }
  return 0.5 * (D + D.transpose());
}

}  // namespace

ShellTriangle MakeShellTriangle(const Eigen::Vector3d& X0, const Eigen::Vector3d& X1,
                                const Eigen::Vector3d& X2) {
  ShellTriangle t;
  const Eigen::Vector3d e1 = X1 - X0, e2 = X2 - X0, n = e1.cross(e2);
  const double twice = n.norm();
  if (!(twice > 0.0) || !(e1.norm() > 0.0)) return t;
  const Eigen::Vector3d t1 = e1.normalized(), t2 = (n / twice).cross(t1);
  Eigen::Matrix2d Dm;
  Dm << e1.dot(t1), e2.dot(t1), e1.dot(t2), e2.dot(t2);
  t.DmInv = Dm.inverse();
  t.restArea = 0.5 * twice;
  return t;
}

LameParameters PlaneStressLame(double youngsModulus, double poissonRatio) {
  LameParameters p;
  p.mu = youngsModulus / (2.0 * (1.0 + poissonRatio));
  p.lambda = youngsModulus * poissonRatio / (1.0 - poissonRatio * poissonRatio);
  return p;
}

double MembraneEnergy(const Vec9& x, const ShellTriangle& t, const LameParameters& lame,
                      double thickness, int order, bool project, Vec9* g, Mat9* H) {
  Eigen::Matrix<double, 3, 2> Ds;
  Ds.col(0) = x.segment<3>(3) - x.segment<3>(0);
  Ds.col(1) = x.segment<3>(6) - x.segment<3>(0);
  const Eigen::Matrix<double, 3, 2> F = Ds * t.DmInv;
  const double scale = thickness * t.restArea;
  Eigen::Matrix<double, 3, 2> P;
  const double W = scale * StvkStress(F, lame, order >= 1 ? &P : nullptr);
  if (order < 1) return W;
  // B = ∂ vec F / ∂x (6 × 9): F_ij = Σ_k Ds_ik DmInv_kj.
  Eigen::Matrix<double, 6, 9> B = Eigen::Matrix<double, 6, 9>::Zero();
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      B(i + 3 * j, 3 + i) = t.DmInv(0, j);
      B(i + 3 * j, 6 + i) = t.DmInv(1, j);
      B(i + 3 * j, i) = -(t.DmInv(0, j) + t.DmInv(1, j));
    }
  const Eigen::Map<const Eigen::Matrix<double, 6, 1>> vecP(P.data());
  *g += scale * B.transpose() * vecP;
  if (order < 2) return W;
  Mat6 D = StvkStressDerivative(F, lame);
  if (project) {
    Eigen::SelfAdjointEigenSolver<Mat6> eig(D);
    if (eig.eigenvalues().minCoeff() < 0.0)
      D = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() *
          eig.eigenvectors().transpose();
  }
  *H += scale * B.transpose() * D * B;
  return W;
}

double HingeAngle(const Eigen::Matrix<double, 12, 1>& x, int order,
                  Eigen::Matrix<double, 12, 1>* g, Eigen::Matrix<double, 12, 12>* H) {
  // y = [e, a, b] = [x1 − x0, x2 − x0, x3 − x0]; derivatives in y, then mapped to x.
  const Eigen::Vector3d e = x.segment<3>(3) - x.segment<3>(0);
  const Eigen::Vector3d a = x.segment<3>(6) - x.segment<3>(0);
  const Eigen::Vector3d b = x.segment<3>(9) - x.segment<3>(0);
  const double len = e.norm();
  const double T = e.dot(a.cross(b));
  const double s = -len * T;
  const double c = e.dot(b) * a.dot(e) - e.dot(e) * a.dot(b);
  const double theta = std::atan2(s, c);
  if (order < 1) return theta;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  // First derivatives in y of |e|, T, and the dot products p = e·b, q = a·e, r = e·e, w = a·b.
  Vec9 dLen = Vec9::Zero(), dT, dp = Vec9::Zero(), dq = Vec9::Zero(), dr = Vec9::Zero(),
       dw = Vec9::Zero();
  dLen.head<3>() = e / len;
  dT << a.cross(b), b.cross(e), e.cross(a);
  dp.segment<3>(0) = b;
  dp.segment<3>(6) = e;
  dq.segment<3>(0) = a;
  dq.segment<3>(3) = e;
  dr.segment<3>(0) = 2.0 * e;
  dw.segment<3>(3) = b;
  dw.segment<3>(6) = a;
  const double p = e.dot(b), q = a.dot(e), r = e.dot(e), w = a.dot(b);
  const Vec9 ds = -(T * dLen + len * dT);
  const Vec9 dc = q * dp + p * dq - w * dr - r * dw;
  const double rho = s * s + c * c;
  const Vec9 dTheta = (c * ds - s * dc) / rho;
  // ∂y/∂x (9 × 12).
  Eigen::Matrix<double, 9, 12> M = Eigen::Matrix<double, 9, 12>::Zero();
  for (int k = 0; k < 3; ++k) {
    M.block<3, 3>(3 * k, 0) = -I;
    M.block<3, 3>(3 * k, 3 * (k + 1)) = I;
  }
  *g = M.transpose() * dTheta;
  if (order < 2) return theta;
  // Second derivatives in y.
  Mat9 d2Len = Mat9::Zero(), d2T = Mat9::Zero(), d2p = Mat9::Zero(), d2q = Mat9::Zero(),
       d2r = Mat9::Zero(), d2w = Mat9::Zero();
  const Eigen::Vector3d eh = e / len;
  d2Len.block<3, 3>(0, 0) = (I - eh * eh.transpose()) / len;
  d2T.block<3, 3>(0, 3) = -Skew(b);
  d2T.block<3, 3>(3, 0) = Skew(b);
  d2T.block<3, 3>(0, 6) = Skew(a);
  d2T.block<3, 3>(6, 0) = -Skew(a);
  d2T.block<3, 3>(3, 6) = -Skew(e);
  d2T.block<3, 3>(6, 3) = Skew(e);
  d2p.block<3, 3>(0, 6) = d2p.block<3, 3>(6, 0) = I;
  d2q.block<3, 3>(0, 3) = d2q.block<3, 3>(3, 0) = I;
  d2r.block<3, 3>(0, 0) = 2.0 * I;
  d2w.block<3, 3>(3, 6) = d2w.block<3, 3>(6, 3) = I;
  const Mat9 d2s = -(T * d2Len + dLen * dT.transpose() + dT * dLen.transpose() + len * d2T);
  const Mat9 d2c = dp * dq.transpose() + dq * dp.transpose() + q * d2p + p * d2q -
                   dr * dw.transpose() - dw * dr.transpose() - w * d2r - r * d2w;
  Mat9 d2Theta = (c * d2s - s * d2c + ds * dc.transpose() - dc * ds.transpose()) / rho -
                 (c * ds - s * dc) * (2.0 * s * ds + 2.0 * c * dc).transpose() / (rho * rho);
  d2Theta = 0.5 * (d2Theta + d2Theta.transpose()).eval();
  *H = M.transpose() * d2Theta * M;
  return theta;
}

double HingeStiffness(double restEdgeLength, double restAreaSum, double plateStiffness) {
  return plateStiffness * restEdgeLength * restEdgeLength / (2.0 * restAreaSum);
}

double HingeBendingEnergy(const Eigen::Matrix<double, 12, 1>& x, double stiffness,
                          double restAngle, int order, bool project,
                          Eigen::Matrix<double, 12, 1>* g, Eigen::Matrix<double, 12, 12>* H) {
  Eigen::Matrix<double, 12, 1> dTheta;
  Eigen::Matrix<double, 12, 12> d2Theta;
  const double theta = HingeAngle(x, order, &dTheta, &d2Theta);
  const double u = theta - restAngle;
  const double W = stiffness * u * u;
  if (order < 1) return W;
  *g += 2.0 * stiffness * u * dTheta;
  if (order < 2) return W;
  StencilMatrix h = 2.0 * stiffness * (dTheta * dTheta.transpose() + u * d2Theta);
  if (project) ProjectToPsd(&h, false);
  *H += h;
  return W;
}

}  // namespace superdex
