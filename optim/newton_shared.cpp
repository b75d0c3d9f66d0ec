#include "optim/newton_shared.h"

#include <sstream>

namespace superdex {

LineSearch::Options LineSearchOptions(const NonlinearSolverParams& params) {
  LineSearch::Options o;
  o.kind = params.lineSearch;
  o.armijoConstant = params.armijoConstant;
  o.backtrackFactor = params.backtrackFactor;
  o.maxTrials = params.maxLineSearchSteps;
  o.byParts = params.partLineSearch;
  return o;
}

ConvergenceTest FirstPassedTest(const NonlinearSolverParams& params,
                                const ConvergenceTestNames& names, const SolverStats& st,
                                double decrement, double stepVelocity) {
  if (decrement <= params.absoluteTolerance)
    return {names.decrement, decrement, "absolute_tolerance", params.absoluteTolerance};
  if (st.finalGradientNorm <= params.relativeTolerance * st.initialGradientNorm)
    return {names.norm, st.finalGradientNorm, names.normBound,
            params.relativeTolerance * st.initialGradientNorm};
  if (stepVelocity <= params.stepTolerance)
    return {"step StepNorm(d)/dt [m/s]", stepVelocity, "step_tolerance", params.stepTolerance};
  return {};
}

SolverStats Converged(SolverStats* st, const ConvergenceTest& test, bool committed,
                      const char* notTakenNote, NewtonWorkspace* work) {
  st->status = StageStatus::Converged;
  st->passed = test;
  work->lastConvergedIterations = st->iterations;
  if (!committed) st->passed.note = notTakenNote;
  return *st;
}

SolverStats Diverged(SolverStats* st, const std::string& message) {
  st->status = StageStatus::Diverged;
  st->message = message;
  return *st;
}

SolverStats StoppedAtCap(SolverStats* st, const NonlinearSolverParams& params,
                         const char* normName, const char* decrementName) {
  st->status = StageStatus::Stopped;
  std::ostringstream s;
  s << "iteration cap max_iterations = " << params.maxIterations << " reached (" << normName
    << " = " << st->finalGradientNorm << ", " << decrementName << " " << st->finalDecrement << ")";
  st->message = s.str();
  return *st;
}

void RecordNorm(SolverStats* st, int it, const Eigen::VectorXd& F) {
  st->finalGradientNorm = F.lpNorm<Eigen::Infinity>();
  if (it == 0) st->initialGradientNorm = st->finalGradientNorm;
}

bool AllFinite(const Eigen::SparseMatrix<double>& A) {
  return Eigen::Map<const Eigen::VectorXd>(A.valuePtr(), A.nonZeros()).allFinite();
}

}  // namespace superdex
