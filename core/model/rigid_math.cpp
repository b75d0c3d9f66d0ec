#include "core/model/rigid_math.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

namespace superdex {

Eigen::Vector3d Axial(const Eigen::Matrix3d& A) {
  return 0.5 * Eigen::Vector3d(A(2, 1) - A(1, 2), A(0, 2) - A(2, 0), A(1, 0) - A(0, 1));
}

Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& theta) {
  const double t2 = theta.squaredNorm();
  const Eigen::Matrix3d K = Skew(theta);
  double a, b;  // sin t / t, (1 - cos t) / t²
  if (t2 < 1e-8) {
    a = 1.0 - t2 / 6.0 + t2 * t2 / 120.0;
    b = 0.5 - t2 / 24.0 + t2 * t2 / 720.0;
  } else {
    const double t = std::sqrt(t2);
    a = std::sin(t) / t;
    b = (1.0 - std::cos(t)) / t2;
  }
  return Eigen::Matrix3d::Identity() + a * K + b * K * K;
}

Eigen::Vector3d LogSo3(const Eigen::Matrix3d& R) {
  const double c = std::max(-1.0, std::min(1.0, 0.5 * (R.trace() - 1.0)));
  const double t = std::acos(c);
  const Eigen::Vector3d w = Axial(R);  // = sin(t) * axis
  if (t < 1e-6) return w * (1.0 + t * t / 6.0);
  if (M_PI - t > 1e-6) return w * (t / std::sin(t));
  // Near π: axis from the symmetric part, R + I = 2 a aᵀ (1 - cos t) ≈ 2 a aᵀ·2/... sign from w.
  const Eigen::Matrix3d B = 0.5 * (R + Eigen::Matrix3d::Identity());
  int k;
  B.diagonal().maxCoeff(&k);
  Eigen::Vector3d axis = B.col(k) / std::sqrt(std::max(B(k, k), 1e-300));
  axis.normalize();
  if (axis.dot(w) < 0.0) axis = -axis;
  return t * axis;
}

Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& A) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0.0) U.col(2) *= -1.0;
  return U * V.transpose();
}

Eigen::Matrix3d LeftJacobianSo3(const Eigen::Vector3d& theta) {
  const double t2 = theta.squaredNorm();
  const Eigen::Matrix3d K = Skew(theta);
  double a, b;  // (1 − cos t)/t², (t − sin t)/t³
  if (t2 < 1e-8) {
    a = 0.5 - t2 / 24.0;
    b = 1.0 / 6.0 - t2 / 120.0;
  } else {
    const double t = std::sqrt(t2);
    a = (1.0 - std::cos(t)) / t2;
    b = (t - std::sin(t)) / (t2 * t);
  }
  return Eigen::Matrix3d::Identity() + a * K + b * K * K;
}

}  // namespace superdex
