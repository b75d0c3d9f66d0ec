#include "optim/linear_solver.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>

namespace superdex {

struct SymmetricSolver::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> cholmod;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt;
  std::vector<int> outer, inner;  // pattern of the last analysis
  bool analyzedCholmod = false;
  bool analyzedLdlt = false;
  int backend = 0;  // 1 cholmod, 2 ldlt

  bool SamePattern(const Eigen::SparseMatrix<double>& H) const {
    const int n = static_cast<int>(H.outerSize());
    if (static_cast<int>(outer.size()) != n + 1 ||
        static_cast<int>(inner.size()) != H.nonZeros())
      return false;
    return std::equal(outer.begin(), outer.end(), H.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), H.innerIndexPtr());
  }
};

SymmetricSolver::SymmetricSolver() : impl_(new Impl) {
  // A matrix that is not positive definite is an expected outcome here (the caller shifts it);
  // keep CHOLMOD from printing a warning for each one.
  impl_->cholmod.cholmod().print = 0;
}
SymmetricSolver::~SymmetricSolver() = default;

bool SymmetricSolver::Factorize(const Eigen::SparseMatrix<double>& H) {
  Impl& s = *impl_;
  if (!H.isCompressed()) return false;
  if (!s.SamePattern(H)) {
    s.outer.assign(H.outerIndexPtr(), H.outerIndexPtr() + H.outerSize() + 1);
    s.inner.assign(H.innerIndexPtr(), H.innerIndexPtr() + H.nonZeros());
    s.analyzedCholmod = s.analyzedLdlt = false;
  }
  if (!s.analyzedCholmod) {
    s.cholmod.analyzePattern(H);
    s.analyzedCholmod = true;
  }
  s.cholmod.factorize(H);
  if (s.cholmod.info() == Eigen::Success) {
    s.backend = 1;
    return true;
  }
  if (!s.analyzedLdlt) {
    s.ldlt.analyzePattern(H);
    s.analyzedLdlt = true;
  }
  s.ldlt.factorize(H);
  if (s.ldlt.info() == Eigen::Success && (s.ldlt.vectorD().array() > 0.0).all()) {
    s.backend = 2;
    return true;
  }
  s.backend = 0;
  return false;
}

Eigen::VectorXd SymmetricSolver::Solve(const Eigen::VectorXd& b) const {
  if (impl_->backend == 1) return impl_->cholmod.solve(b);
  if (impl_->backend == 2) return impl_->ldlt.solve(b);
  return Eigen::VectorXd::Constant(b.size(), std::numeric_limits<double>::quiet_NaN());
}

const char* SymmetricSolver::Backend() const {
  return impl_->backend == 1 ? "cholmod" : impl_->backend == 2 ? "ldlt" : "none";
}

}  // namespace superdex
