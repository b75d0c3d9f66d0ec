#include "energies/psd_projection.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace superdex {

namespace {

template <typename Matrix>
void Project(Matrix* H, bool useAbsoluteValues) {
  const Eigen::Index n = H->rows();
  if (n == 0) return;
  Eigen::LLT<Matrix> llt(*H);
  if (llt.info() == Eigen::Success) return;  // positive definite already
  Eigen::SelfAdjointEigenSolver<Matrix> eig(*H);
  auto lambda = eig.eigenvalues().eval();
  bool changed = false;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (lambda[i] < 0.0) {
      lambda[i] = useAbsoluteValues ? -lambda[i] : 0.0;
      changed = true;
    }
  }
  if (!changed) return;
  const Matrix& V = eig.eigenvectors();
  *H = V * lambda.asDiagonal() * V.transpose();
}

}  // namespace

void ProjectToPsd(StencilMatrix* H, bool useAbsoluteValues) { Project(H, useAbsoluteValues); }

void ProjectToPsd(SmallStencilMatrix* H, bool useAbsoluteValues) {
  Project(H, useAbsoluteValues);
}

}  // namespace superdex
