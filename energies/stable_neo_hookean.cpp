#include "energies/stable_neo_hookean.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

#include "geometry/skew.h"

namespace superdex {
namespace {

using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Vector9d = Eigen::Matrix<double, 9, 1>;

/// λ' = λ + 5/6 μ (paper §3.5); μ' = 4/3 μ is written out where it appears.
double LambdaPrime(const LameParameters& p) { return p.lambda + (5.0 / 6.0) * p.mu; }

/// cof F = det(F) F⁻ᵀ = ∂J/∂F, column by column: (f1 × f2, f2 × f0, f0 × f1).
Eigen::Matrix3d Cofactor(const Eigen::Matrix3d& F) {
  Eigen::Matrix3d C;
  C.col(0) = F.col(1).cross(F.col(2));
  C.col(1) = F.col(2).cross(F.col(0));
  C.col(2) = F.col(0).cross(F.col(1));
  return C;
}


/// Ψ from the invariants (expanded form of the header; no α, no cancellation through α − 1).
double Density(double Ic, double J, const LameParameters& p) {
  const double dI = Ic - 3.0, dJ = J - 1.0;
  return (2.0 / 3.0) * p.mu * (dI - std::log1p(0.25 * dI)) + 0.5 * LambdaPrime(p) * dJ * dJ -
         p.mu * dJ;
}

/// μ'(1 − 1/(I_C + 1)) = μ' I_C/(I_C + 1): the coefficient of F in P and of I₉ in ∂²Ψ/∂F².
double ShearCoefficient(double Ic, const LameParameters& p) {
  return (4.0 / 3.0) * p.mu * Ic / (Ic + 1.0);
}

/// κ = λ'(J − α) = λ'(J − 1) − μ: the coefficient of cof F in P and of H_J in ∂²Ψ/∂F².
double VolumeCoefficient(double J, const LameParameters& p) {
  return LambdaPrime(p) * (J - 1.0) - p.mu;
}

Eigen::Matrix3d Stress(const Eigen::Matrix3d& F, const Eigen::Matrix3d& cof, double Ic, double J,
                       const LameParameters& p) {
  return ShearCoefficient(Ic, p) * F + VolumeCoefficient(J, p) * cof;
}

Vector9d Vec(const Eigen::Matrix3d& M) { return Eigen::Map<const Vector9d>(M.data()); }

/// PSD projection of ∂²Ψ/∂F² by the analytic eigensystem (header comment). A is the unprojected
/// matrix; it is returned as is when no eigenvalue is negative.
void ProjectStressDerivative(const Eigen::Matrix3d& F, double Ic, double J,
                             const LameParameters& p, Matrix9d* A) {
  // Positive definite already (the common case away from inversion): no SVD needed.
  Eigen::LLT<Matrix9d> llt(*A);
  if (llt.info() == Eigen::Success) return;

  // Rotation-variant SVD: U, V proper rotations, the sign of J carried by the smallest σ.
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU(), V = svd.matrixV();
  Eigen::Vector3d s = svd.singularValues();
  if (U.determinant() < 0.0) {
    U.col(2) *= -1.0;
    s[2] = -s[2];
  }
  if (V.determinant() < 0.0) {
    V.col(2) *= -1.0;
    s[2] = -s[2];
  }

  const double a = ShearCoefficient(Ic, p);
  const double b = 2.0 * (4.0 / 3.0) * p.mu / ((Ic + 1.0) * (Ic + 1.0));
  const double lp = LambdaPrime(p);
  const double kappa = VolumeCoefficient(J, p);
  const Eigen::Vector3d g(s[1] * s[2], s[2] * s[0], s[0] * s[1]);  // ∂J/∂σ

  double lambda[9];
  Eigen::Matrix3d Q[9];
  // Scaling modes: the 3×3 block on diagonal directions U diag(z) Vᵀ.
  Eigen::Matrix3d As;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      As(i, j) = b * s[i] * s[j] + lp * g[i] * g[j] + (i == j ? a : kappa * s[3 - i - j]);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(As);
  for (int m = 0; m < 3; ++m) {
    lambda[m] = es.eigenvalues()[m];
    Q[m] = U * es.eigenvectors().col(m).asDiagonal() * V.transpose();
  }
  // Twist and flip modes in the (i, j) plane, k the third axis: H_J eigenvalues ±σ_k.
  const double r = std::sqrt(0.5);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const Eigen::Matrix3d UiVj = U.col(i) * V.col(j).transpose();
    const Eigen::Matrix3d UjVi = U.col(j) * V.col(i).transpose();
    lambda[3 + k] = a + kappa * s[k];
    Q[3 + k] = r * (UiVj - UjVi);
    lambda[6 + k] = a - kappa * s[k];
    Q[6 + k] = r * (UiVj + UjVi);
  }

  bool negative = false;
  for (double l : lambda) negative = negative || l < 0.0;
  if (!negative) return;
  A->setZero();
  for (int m = 0; m < 9; ++m) {
    if (lambda[m] <= 0.0) continue;
    const Vector9d q = Vec(Q[m]);
    A->noalias() += lambda[m] * q * q.transpose();
  }
}

Matrix9d StressDerivative(const Eigen::Matrix3d& F, const Eigen::Matrix3d& cof, double Ic,
                          double J, const LameParameters& p, bool projectPsd) {
  const double a = ShearCoefficient(Ic, p);
  const double b = 2.0 * (4.0 / 3.0) * p.mu / ((Ic + 1.0) * (Ic + 1.0));
  const double lp = LambdaPrime(p);
  const double kappa = VolumeCoefficient(J, p);
  const Vector9d f = Vec(F), g = Vec(cof);
  Matrix9d A = b * f * f.transpose();
  A.noalias() += lp * g * g.transpose();
  A.diagonal().array() += a;
  // κ H_J, H_J = ∂²J/∂F² in 3×3 blocks over the columns of F:
  //   [[0, −[f2]×, [f1]×], [[f2]×, 0, −[f0]×], [−[f1]×, [f0]×, 0]].
  const Eigen::Matrix3d X0 = kappa * Skew(F.col(0));
  const Eigen::Matrix3d X1 = kappa * Skew(F.col(1));
  const Eigen::Matrix3d X2 = kappa * Skew(F.col(2));
  A.block<3, 3>(0, 3) -= X2;
  A.block<3, 3>(3, 0) += X2;
  A.block<3, 3>(0, 6) += X1;
  A.block<3, 3>(6, 0) -= X1;
  A.block<3, 3>(3, 6) -= X0;
  A.block<3, 3>(6, 3) += X0;
  if (projectPsd) ProjectStressDerivative(F, Ic, J, p, &A);
  return A;
}

}  // namespace

LameParameters LameFromYoungPoisson(double youngsModulus, double poissonRatio) {
  const double E = youngsModulus, nu = poissonRatio;
  LameParameters p;
  p.mu = E / (2.0 * (1.0 + nu));
  p.lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  return p;
}

double StableNeoHookeanEnergyDensity(const Eigen::Matrix3d& F, const LameParameters& p) {
  return Density(F.squaredNorm(), F.determinant(), p);
}

Eigen::Matrix3d StableNeoHookeanStress(const Eigen::Matrix3d& F, const LameParameters& p) {
  return Stress(F, Cofactor(F), F.squaredNorm(), F.determinant(), p);
}

Eigen::Matrix<double, 9, 9> StableNeoHookeanStressDerivative(const Eigen::Matrix3d& F,
                                                            const LameParameters& p,
                                                            bool projectPsd) {
  return StressDerivative(F, Cofactor(F), F.squaredNorm(), F.determinant(), p, projectPsd);
}

bool MakeTetElement(const Eigen::Vector3d X[4], TetElement* out) {
  Eigen::Matrix3d Dm;
  for (int i = 0; i < 3; ++i) Dm.col(i) = X[i + 1] - X[0];
  if (!Dm.allFinite()) return false;
  const double det = Dm.determinant();
  const double scale = Dm.col(0).norm() * Dm.col(1).norm() * Dm.col(2).norm();
  if (!(det > 1e-10 * scale) || !std::isfinite(det)) return false;
  out->DmInv = Dm.inverse();
  out->restVolume = det / 6.0;
  return true;
}

void EvaluateStableNeoHookean(const TetElement& e, const LameParameters& p,
                              const Eigen::Vector3d x[4], int order, bool projectPsd,
                              TetElasticTerm* out) {
  Eigen::Matrix3d Ds;
  for (int i = 0; i < 3; ++i) Ds.col(i) = x[i + 1] - x[0];
  const Eigen::Matrix3d F = Ds * e.DmInv;
  const double Ic = F.squaredNorm();
  const double J = F.determinant();
  const double V = e.restVolume;
  out->value = V * Density(Ic, J, p);
  out->detF = J;
  if (order < 1) {
    out->gradient.setZero();
    out->hessian.setZero();
    return;
  }

  const Eigen::Matrix3d cof = Cofactor(F);
  // Nodes 1..3: V P Dm⁻ᵀ, column by column; node 0: minus their sum.
  const Eigen::Matrix3d G = V * Stress(F, cof, Ic, J, p) * e.DmInv.transpose();
  for (int i = 0; i < 3; ++i) out->gradient.segment<3>(3 * (i + 1)) = G.col(i);
  out->gradient.segment<3>(0) = -(G.col(0) + G.col(1) + G.col(2));
  if (order < 2) {
    out->hessian.setZero();
    return;
  }

  // hessian = V Bᵀ A B with B = ∂vec F/∂x: ∂F_ab/∂x_{n,c} = δ_ac W(n, b), W(n, b) = DmInv(n−1, b)
  // (n >= 1), W(0, b) = −Σ_j DmInv(j, b). Block by block over (c, d):
  //   hessian(3n + c, 3m + d) = V (W A_cd Wᵀ)(n, m),  A_cd(b, e) = A(c + 3b, d + 3e).
  Eigen::Matrix<double, 4, 3> W;
  W.row(0) = -e.DmInv.colwise().sum();
  W.bottomRows<3>() = e.DmInv;
  const Matrix9d A = StressDerivative(F, cof, Ic, J, p, projectPsd);
  for (int c = 0; c < 3; ++c)
    for (int d = 0; d < 3; ++d) {
      const Eigen::Map<const Eigen::Matrix3d, 0, Eigen::Stride<27, 3>> Acd(A.data() + c + 9 * d);
      const Eigen::Matrix<double, 4, 3> WA = V * (W * Acd);
      const Eigen::Matrix4d M = WA * W.transpose();
      for (int n = 0; n < 4; ++n)
        for (int m = 0; m < 4; ++m) out->hessian(3 * n + c, 3 * m + d) = M(n, m);
    }
  // Exactly symmetric (the product's rounding is not).
  out->hessian = (0.5 * (out->hessian + out->hessian.transpose())).eval();
}

}  // namespace superdex
