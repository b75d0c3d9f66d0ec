// Newton's method on a residual that is not a gradient. See residual_newton.h for the iteration.
#include "optim/residual_newton.h"

#include <cmath>
#include <sstream>

#include "optim/line_search.h"
#include "optim/newton_shared.h"
#include "optim/regularized_solve.h"

namespace superdex {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

constexpr double kStagnantDecrease = 1e-6;
constexpr int kStagnantIterations = 3;
constexpr double kQuadraticContraction = 1e-4;  // θ ratio of a full step in the quadratic regime

constexpr ConvergenceTestNames kTestNames{"residual decrement 0.5|r.d|", "residual norm |r|_inf",
                                          "relative_tolerance * |r0|_inf"};

/// Step 3's last correction d: in the quadratic regime (the previous iteration's full step cut θ
/// by kQuadraticContraction or more) committed unchecked, as Newton's local theory says it lowers
/// θ further; otherwise only if r(s ⊕ d) (into *rTrial) shows it does not raise θ. Whether it was.
bool CommitLastCorrection(StageProblem& problem, const Eigen::VectorXd& d, double theta,
                          bool quadratic, Eigen::VectorXd* rTrial, SolverStats* st) {
  bool commit = quadratic;
  if (!commit) {
    problem.Residual(d, rTrial);
    commit = rTrial->allFinite() && 0.5 * rTrial->squaredNorm() <= theta;
    if (commit) {
      st->finalValue = 0.5 * rTrial->squaredNorm();
      st->finalGradientNorm = rTrial->lpNorm<Eigen::Infinity>();
    }
  }
  if (commit) problem.Commit(d);
  return commit;
}

/// Step 5: counts the iterations in a row whose accepted step was cut to α <= `stagnantStep` and
/// lowered θ by less than kStagnantDecrease θ; a message once there are kStagnantIterations.
std::string Stagnation(const LineSearch::Summary& ls, double theta, double stagnantStep, int it,
                       const SolverStats& st, int* stagnant) {
  if (!(ls.alpha <= stagnantStep && theta - ls.trialMerit <= kStagnantDecrease * theta)) {
    *stagnant = 0;
    return "";
  }
  if (++*stagnant < kStagnantIterations) return "";
  std::ostringstream s;
  s << "merit stagnation: " << kStagnantIterations << " iterations in a row with steps cut to "
    << ls.alpha << " lowering 0.5|r|^2 by < " << kStagnantDecrease << " of it (iteration "
    << it + 1 << ", |r|_inf = " << st.finalGradientNorm << ")";
  return s.str();
}

}  // namespace

SolverStats SolveResidualNewton(StageProblem& problem, const NonlinearSolverParams& params,
                                double timeScale, UnsymmetricSolver* solver,
                                NewtonWorkspace* work) {
  SolverStats st;
  if (std::string m = ValidateSolverInput(params, timeScale); !m.empty()) return Diverged(&st, m);
  NewtonSetup<UnsymmetricSolver> setup(solver, work, params, problem);
  const int n = setup.n;
  if (n == 0) {
    st.status = StageStatus::Converged;
    st.message = "no degrees of freedom";
    return st;
  }

  NewtonWorkspace& w = setup.work;
  UnsymmetricSolver& lu = setup.solver;
  Eigen::VectorXd &r = w.gradient, &rTrial = w.trialGradient, &d = w.direction;
  SparseMatrix &J = w.matrix, &JTrial = w.trialMatrix;
  bool evaluated = false;  // r and J already hold the current state's (from an accepted trial)
  int stagnant = 0;  // consecutive stagnant iterations (residual_newton.h, 5)
  bool quadratic = false;  // the last accepted step was full and cut θ by kQuadraticContraction
  const double stagnantStep = std::pow(params.backtrackFactor, 10);
  KrylovForcing forcing(params.linear, &w.lastConvergedIterations);
  for (int it = 0; it < params.maxIterations; ++it) {
    Stopwatch clock;
    if (!evaluated) {
      problem.EvaluateResidual(&r, &J);
      w.search.ReadSplit(problem);
    }
    evaluated = false;
    clock.AddTo(&st.assemblySeconds);
    if (r.size() != n || J.rows() != n || J.cols() != n)
      return Diverged(&st, "the stage problem provides no residual of the right size");
    if (!r.allFinite())
      return Diverged(&st, "non-finite residual at iteration " + std::to_string(it + 1));
    const double theta = 0.5 * r.squaredNorm();
    st.finalValue = theta;
    RecordNorm(&st, it, r);
    if (st.finalGradientNorm == 0.0) {
      st.status = StageStatus::Converged;
      st.message = "residual is exactly zero";
      return st;
    }

    // --- Direction d = −J⁻¹r, regularized (residual_newton.h, 2).
    forcing.Next(lu, r);
    clock.Restart();
    J.makeCompressed();
    if (!AllFinite(J))
      return Diverged(&st, "non-finite Jacobian entry at iteration " + std::to_string(it + 1));
    const RegularizedSolve rs = SolveRegularized(lu, &J, r, ShiftGoal::Nonsingular, &d, &w.shifted,
                                                 &w.diagonal, &st);
    clock.AddTo(&st.factorizationSeconds);
    if (!rs.solved)
      return Diverged(&st, "singular Jacobian at iteration " + std::to_string(it + 1));
    st.iterations = it + 1;
    const double decrement = 0.5 * std::abs(r.dot(d));
    st.finalDecrement = decrement;

    // --- Convergence tests (residual_newton.h, 3), before stepping.
    const ConvergenceTest converged =
        FirstPassedTest(params, kTestNames, st, decrement, problem.StepNorm(d) / timeScale);
    if (converged.what) {
      clock.Restart();
      const bool committed = CommitLastCorrection(problem, d, theta, quadratic, &rTrial, &st);
      clock.AddTo(&st.lineSearchSeconds);
      return Converged(&st, converged, committed, " (last step not taken: it would raise |r|)", &w);
    }

    // --- Line search on θ = ½‖r‖² (residual_newton.h, 4), the problem's trust region as the
    // first step length along d.
    clock.Restart();
    LineSearch::Start from = LineSearch::Start::Residual(theta, r, decrement);
    from.jacobian = &J;
    if (params.lineSearch != LineSearchKind::None) {
      w.limited = d;
      if (problem.TrustStep(&w.limited)) from.firstStep = &w.limited;
    }
    const LineSearch::Summary ls = w.search.Search(problem, from, d, &w.step, &rTrial, &JTrial);
    st.lineSearchSteps += ls.rejectedTrials;
    if (ls.withDerivatives) {  // the next iteration's r and J
      r.swap(rTrial);
      J.swap(JTrial);
      evaluated = true;
    }
    clock.AddTo(&st.lineSearchSeconds);
    if (!ls.accepted) {
      std::ostringstream s;
      s << "merit line search rejected "
        << (params.lineSearch == LineSearchKind::None ? 1 : params.maxLineSearchSteps)
        << " trials at iteration " << it + 1 << " (|r|_inf = " << st.finalGradientNorm
        << ", last trial 0.5|r|^2 = " << ls.trialMerit << ")";
      return Diverged(&st, s.str());
    }
    problem.Commit(w.step);
    quadratic = ls.alpha == 1.0 && ls.trialMerit <= kQuadraticContraction * theta;
    if (std::string m = Stagnation(ls, theta, stagnantStep, it, st, &stagnant); !m.empty())
      return Diverged(&st, m);
  }
  return StoppedAtCap(&st, params, "|r|_inf", "decrement");
}

}  // namespace superdex
