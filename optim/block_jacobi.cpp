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
  if (n != laidOut_ || !(layout_ == laidOutLayout_)) {  // the blocks of a new layout
    laidOut_ = n;
    laidOutLayout_ = layout_;
    blocks_.clear();
    Eigen::Index next = 0;
    int sixes = 0, threes = 0;
    scalar_ = false;
    auto add = [&](int size) {
      blocks_.push_back({next, size, size == 6 ? sixes++ : threes++});
      next += size;
    };
    for (int size : layout_.sizes) {
      if ((size != 3 && size != 6) || next + size > n) {
        scalar_ = true;
        break;
      }
      add(size);
    }
    scalar_ = scalar_ || (n - next) % 3 != 0;
    while (!scalar_ && next < n) add(3);
    if (scalar_) {
      blocks_.clear();
      sixes = threes = 0;
    }
    blockOf_.assign(scalar_ ? 0 : n, 0);
    for (size_t k = 0; k < blocks_.size(); ++k)
      for (int i = 0; i < blocks_[k].size; ++i) blockOf_[blocks_[k].first + i] = static_cast<int>(k);
    six_.resize(sixes);
    three_.resize(threes);
  }
  if (scalar_) {
    diagonal_.setZero(n);
    return;
  }
  for (Matrix6& B : six_) B.setZero();
  for (Eigen::Matrix3d& B : three_) B.setZero();
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
  for (const Block& b : blocks_) {
    if (b.size == 6)
      z->segment<6>(b.first).noalias() = six_[b.index] * r.segment<6>(b.first);
    else
      z->segment<3>(b.first).noalias() = three_[b.index] * r.segment<3>(b.first);
  }
}

}  // namespace superdex
