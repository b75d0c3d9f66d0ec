// What projected Newton (optim/newton_solver.cpp) and residual Newton (optim/residual_newton.cpp)
// share besides the line search (optim/line_search.h) and the regularized linear solve
// (optim/regularized_solve.h): the solve's buffers and linear solver, the Krylov forcing term,
// the convergence tests, the statistics and the timing.
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "optim/forcing_term.h"
#include "optim/linear_solver.h"
#include "optim/newton_solver.h"
#include "optim/stage_problem.h"

namespace superdex {

/// Wall time of a phase, added to a SolverStats total [s].
class Stopwatch {
 public:
  Stopwatch() : start_(Clock::now()) {}
  void Restart() { start_ = Clock::now(); }
  /// *total += the seconds since the (re)start.
  void AddTo(double* total) const {
    *total += std::chrono::duration<double>(Clock::now() - start_).count();
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_;
};

/// The line search's options from the solver's parameters.
LineSearch::Options LineSearchOptions(const NonlinearSolverParams& params);

/// The buffers and the linear solver of one Newton solve: the caller's where given, else owned
/// (only then: even empty, a workspace's sparse matrices allocate their outer index). Sizes the
/// vectors of the direction and the step to the problem's n dofs (no allocation once they have
/// it); sets the solver's settings and block layout and the line search's options.
template <typename LinearSolver>
class NewtonSetup {
 public:
  NewtonSetup(LinearSolver* cachedSolver, NewtonWorkspace* cachedWork,
              const NonlinearSolverParams& params, const StageProblem& problem)
      : ownWork_(cachedWork ? nullptr : std::make_unique<NewtonWorkspace>()),
        ownSolver_(cachedSolver ? nullptr : std::make_unique<LinearSolver>()),
        work(cachedWork ? *cachedWork : *ownWork_),
        solver(cachedSolver ? *cachedSolver : *ownSolver_),
        n(problem.NumDofs()) {
    for (Eigen::VectorXd* v : {&work.gradient, &work.direction, &work.step, &work.limited})
      v->resize(n);
    solver.SetSettings(params.linear);
    problem.BlockLayout(&work.layout);
    solver.SetBlockLayout(work.layout);
    work.search.SetOptions(LineSearchOptions(params));
  }

 private:
  std::unique_ptr<NewtonWorkspace> ownWork_;
  std::unique_ptr<LinearSolver> ownSolver_;

 public:
  NewtonWorkspace& work;
  LinearSolver& solver;
  const int n;  ///< the problem's dofs
};

/// The Krylov tolerance of each Newton iteration: the Eisenstat–Walker forcing term
/// (optim/forcing_term.h), started from the workspace's last converged solve; direct solves are
/// exact either way.
class KrylovForcing {
 public:
  /// Reads *lastConvergedIterations and sets it to -1 (until this solve converges).
  KrylovForcing(const LinearSolverSettings& linear, int* lastConvergedIterations)
      : forcing_(linear.tolerance, *lastConvergedIterations),
        linear_(linear),
        inexact_(linear.kind != LinearSolverKind::Direct) {
    *lastConvergedIterations = -1;
  }
  /// Sets the solver's tolerance for this iteration's F (the gradient or the residual).
  template <typename LinearSolver>
  void Next(LinearSolver& solver, const Eigen::VectorXd& F) {
    if (!inexact_) return;
    linear_.tolerance = forcing_.Next(F.norm());
    solver.SetSettings(linear_);
  }

 private:
  ForcingTerm forcing_;
  LinearSolverSettings linear_;
  bool inexact_;
};

/// How one solver names its convergence tests in its messages.
struct ConvergenceTestNames {
  const char* decrement;  ///< e.g. "Newton decrement 0.5 g^T H^-1 g"
  const char* norm;       ///< e.g. "gradient norm |g|_inf"
  const char* normBound;  ///< e.g. "relative_tolerance * |g0|_inf"
};

/// The first of the convergence tests (newton_solver.h, 3) that passes, in order: decrement <=
/// absoluteTolerance, st.finalGradientNorm <= relativeTolerance st.initialGradientNorm,
/// stepVelocity <= stepTolerance. None: `what` null.
ConvergenceTest FirstPassedTest(const NonlinearSolverParams& params,
                                const ConvergenceTestNames& names, const SolverStats& st,
                                double decrement, double stepVelocity);

/// Ends a solve whose convergence test passed: Converged, the test (with `notTakenNote` where the
/// last step was not committed); the workspace keeps the iteration count (the next solve's
/// forcing term).
SolverStats Converged(SolverStats* st, const ConvergenceTest& test, bool committed,
                      const char* notTakenNote, NewtonWorkspace* work);

/// Ends a solve as Diverged with `message`.
SolverStats Diverged(SolverStats* st, const std::string& message);

/// Ends a solve at the iteration cap: Stopped, "iteration cap max_iterations = N reached
/// (<normName> = ‖F‖∞, <decrementName> decrement)".
SolverStats StoppedAtCap(SolverStats* st, const NonlinearSolverParams& params,
                         const char* normName, const char* decrementName);

/// Records ‖F‖∞ of iteration `it` (the first one's as the initial norm).
void RecordNorm(SolverStats* st, int it, const Eigen::VectorXd& F);

/// Whether every stored entry of the compressed A is finite.
bool AllFinite(const Eigen::SparseMatrix<double>& A);

}  // namespace superdex
