#include "optim/stage_problem.h"

namespace superdex {

SUPERDEX_ENUM_NAMES(PsdProjection,
    {PsdProjection::None, "None", "exact Hessian (may be indefinite)"},
    {PsdProjection::Clamp, "Clamp", "negative eigenvalues set to zero"},
    {PsdProjection::Abs, "Abs", "negative eigenvalues replaced by their absolute value"})

// A problem without a residual interface reports an empty residual; the residual solvers refuse it.
void StageProblem::Residual(const Eigen::VectorXd&, Eigen::VectorXd* r) { r->resize(0); }

void StageProblem::EvaluateResidual(Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J) {
  r->resize(0);
  if (J) J->resize(0, 0);
}

}  // namespace superdex
