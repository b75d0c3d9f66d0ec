#include "optim/block_jacobi.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace superdex {

namespace {

/// B ← B⁻¹ for a diagonal block; whether B was symmetric positive definite. A block that is
/// singular to working precision is replaced by the inverse of its diagonal (entries 0 → 1).
template <int N>
bool InvertBlock(Eigen::Matrix<double, N, N>* B) {
  using Matrix = Eigen::Matrix<double, N, N>;
  const double scale = B->cwiseAbs().maxCoeff();
  const bool symmetric = (*B - B->transpose()).cwiseAbs().maxCoeff() <= 1e-12 * scale;
  const Eigen::LLT<Matrix> llt(*B);
  const bool spd = symmetric && llt.info() == Eigen::Success;
  Matrix inverse;
  bool invertible = false;
  if constexpr (N == 3) {
    B->computeInverseWithCheck(inverse, invertible, 1e-14 * scale);  // closed form
  } else {
    const Eigen::FullPivLU<Matrix> lu(*B);
    // Invertible when its smallest pivot is not round-off of its largest entry.
    invertible = scale > 0.0 && lu.matrixLU().diagonal().cwiseAbs().minCoeff() > 1e-14 * scale;
    if (invertible) inverse = lu.inverse();
  }
  if (invertible && inverse.allFinite()) {
    *B = inverse;
    return spd;
  }
  const Eigen::Matrix<double, N, 1> d = B->diagonal();
  B->setZero();
  for (int k = 0; k < N; ++k) (*B)(k, k) = d[k] != 0.0 ? 1.0 / d[k] : 1.0;
  return spd;
}

}  // namespace

void BlockJacobi::Layout(Eigen::Index n) {
  sixEnd_ = 6 * static_cast<Eigen::Index>(leadingSix_);
  scalar_ = sixEnd_ > n || (n - sixEnd_) % 3 != 0;
  if (scalar_) {
    sixEnd_ = 0;
    six_.clear();
    three_.clear();
    diagonal_.setZero(n);
    return;
  }
  six_.assign(leadingSix_, Matrix6::Zero());
  three_.assign((n - sixEnd_) / 3, Eigen::Matrix3d::Zero());
}

void BlockJacobi::Invert() {
  positiveDefinite_ = true;
  if (scalar_) {
    for (Eigen::Index i = 0; i < diagonal_.size(); ++i) {
      positiveDefinite_ = positiveDefinite_ && diagonal_[i] > 0.0;
      diagonal_[i] = diagonal_[i] != 0.0 ? 1.0 / diagonal_[i] : 1.0;
    }
    return;
  }
  for (Matrix6& B : six_) positiveDefinite_ = InvertBlock(&B) && positiveDefinite_;
  for (Eigen::Matrix3d& B : three_) positiveDefinite_ = InvertBlock(&B) && positiveDefinite_;
}

void BlockJacobi::Apply(const Eigen::VectorXd& r, Eigen::VectorXd* z) const {
  z->resize(r.size());
  if (scalar_) {
    z->array() = diagonal_.array() * r.array();
    return;
  }
  for (size_t i = 0; i < six_.size(); ++i)
    z->segment<6>(6 * i).noalias() = six_[i] * r.segment<6>(6 * i);
  for (size_t i = 0; i < three_.size(); ++i)
    z->segment<3>(sixEnd_ + 3 * i).noalias() = three_[i] * r.segment<3>(sixEnd_ + 3 * i);
}

}  // namespace superdex
