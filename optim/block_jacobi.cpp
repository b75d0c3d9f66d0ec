#include "optim/block_jacobi.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace superdex {

void BlockJacobi3::Invert() {
  positiveDefinite_ = true;
  for (Eigen::Matrix3d& B : blocks_) {
    if (block_ == 1) {
      positiveDefinite_ = positiveDefinite_ && B(0, 0) > 0.0;
      B(0, 0) = B(0, 0) != 0.0 ? 1.0 / B(0, 0) : 1.0;
      continue;
    }
    const bool symmetric = (B - B.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * B.cwiseAbs().maxCoeff();
    Eigen::LLT<Eigen::Matrix3d> llt(B);
    positiveDefinite_ = positiveDefinite_ && symmetric && llt.info() == Eigen::Success;
    Eigen::Matrix3d inverse;
    bool invertible = false;
    B.computeInverseWithCheck(inverse, invertible, 1e-14 * B.cwiseAbs().maxCoeff());
    if (invertible && inverse.allFinite()) {
      B = inverse;
    } else {
      const Eigen::Vector3d d = B.diagonal();
      B.setZero();
      for (int k = 0; k < 3; ++k) B(k, k) = d[k] != 0.0 ? 1.0 / d[k] : 1.0;
    }
  }
}

void BlockJacobi3::Apply(const Eigen::VectorXd& r, Eigen::VectorXd* z) const {
  z->resize(r.size());
  if (block_ == 1) {
    for (size_t i = 0; i < blocks_.size(); ++i) (*z)[i] = blocks_[i](0, 0) * r[i];
    return;
  }
  for (size_t i = 0; i < blocks_.size(); ++i)
    z->segment<3>(3 * i).noalias() = blocks_[i] * r.segment<3>(3 * i);
}

}  // namespace superdex
