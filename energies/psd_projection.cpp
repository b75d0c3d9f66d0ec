#include "energies/psd_projection.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace superdex {

void ProjectToPsd(StencilMatrix* H, bool useAbsoluteValues) {
  const Eigen::Index n = H->rows();
  if (n == 0) return;
  Eigen::LLT<StencilMatrix> llt(*H);
  if (llt.info() == Eigen::Success) return;  // positive definite already
  Eigen::SelfAdjointEigenSolver<StencilMatrix> eig(*H);
  StencilVector lambda = eig.eigenvalues();
  bool changed = false;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (lambda[i] < 0.0) {
      lambda[i] = useAbsoluteValues ? -lambda[i] : 0.0;
      changed = true;
    }
  }
  if (!changed) return;
  const StencilMatrix& V = eig.eigenvectors();
  *H = V * lambda.asDiagonal() * V.transpose();
}

}  // namespace superdex
