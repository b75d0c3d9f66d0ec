#include "energies/rigid_inertia.h"

#include <Eigen/LU>
#include <Eigen/SVD>

namespace superdex {

RigidInertiaTerm RigidInertia(double mass, const Eigen::Matrix3d& J, const Eigen::Vector3d& p,
                              const Eigen::Matrix3d& R, const Eigen::Vector3d& pHat,
                              const Eigen::Matrix3d& RHat, bool withDerivatives) {
  RigidInertiaTerm t;
  const Eigen::Vector3d dp = p - pHat;
  const Eigen::Matrix3d D = R - RHat;
  t.value = 0.5 * mass * dp.squaredNorm() + 0.5 * (D * J * D.transpose()).trace();
  if (!withDerivatives) return t;
  const Eigen::Matrix3d M = R * J * RHat.transpose();
  t.gradient.head<3>() = mass * dp;
  t.gradient.tail<3>() =
      -Eigen::Vector3d(M(1, 2) - M(2, 1), M(2, 0) - M(0, 2), M(0, 1) - M(1, 0));
  t.hessian.topLeftCorner<3, 3>() = mass * Eigen::Matrix3d::Identity();
  t.hessian.bottomRightCorner<3, 3>() =
      M.trace() * Eigen::Matrix3d::Identity() - 0.5 * (M + M.transpose());
  return t;
}

RigidInertiaMinimum MinimizeRigidInertia(const Eigen::Matrix3d& J, const Eigen::Vector3d& pHat,
                                         const Eigen::Matrix3d& RHat, double dt,
                                         const Eigen::Vector3d& gravity) {
  RigidInertiaMinimum out;
  out.p = pHat + dt * dt * gravity;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(RHat * J, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d& U = svd.matrixU();
  const Eigen::Matrix3d& V = svd.matrixV();
  Eigen::Vector3d sign(1.0, 1.0, (U * V.transpose()).determinant() < 0.0 ? -1.0 : 1.0);
  out.R = U * sign.asDiagonal() * V.transpose();
  return out;
}

}  // namespace superdex
