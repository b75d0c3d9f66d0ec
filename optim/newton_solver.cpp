// Projected Newton with a backtracking (Armijo) line search. See newton_solver.h for the
// iteration, the convergence tests and the statuses.
#include "optim/newton_solver.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "optim/line_search.h"
#include "optim/newton_shared.h"
#include "optim/regularized_solve.h"

namespace superdex {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

constexpr ConvergenceTestNames kTestNames{"Newton decrement 0.5 g^T H^-1 g",
                                          "gradient norm |g|_inf", "relative_tolerance * |g0|_inf"};

/// Step 1 with the exact Hessian H: d = −H⁻¹g if H factorizes as is and gives a descent
/// direction; otherwise false, and f, g, H are assembled again with `projection`.
bool SolveWithExactHessian(StageProblem& problem, PsdProjection projection,
                           SymmetricSolver& solver, double* f, Eigen::VectorXd* g, SparseMatrix* H,
                           Eigen::VectorXd* d, SolverStats* st) {
  Stopwatch clock;
  H->makeCompressed();
  bool good = AllFinite(*H) && g->allFinite() && solver.Factorize(*H);
  if (good) {
    SolveNegated(solver, *g, d, st);
    good = d->allFinite() && g->dot(*d) < 0.0;
  }
  clock.AddTo(&st->factorizationSeconds);
  if (!good) {
    clock.Restart();
    *f = problem.Evaluate(g, H, projection);
    clock.AddTo(&st->assemblySeconds);
  }
  return good;
}

/// Step 3's last correction d, committed unless it would raise f; whether it was. When the
/// decrease it promises, |g·d|, is itself inside the round-off band, f cannot tell its value there
/// from f(s) (the band test would accept any value f could resolve as equal): it is committed
/// without evaluating f there (finalValue stays f(s)).
bool CommitLastCorrection(StageProblem& problem, const Eigen::VectorXd& d, double f, double slope,
                          SolverStats* st) {
  const double band = kRoundoffBand * std::abs(f);
  const bool unresolvable = std::abs(slope) <= band;
  const double trialValue = unresolvable ? f : problem.Value(d);
  const bool commit = std::isfinite(trialValue) &&
                      (trialValue <= f || WithinRoundoff(trialValue, f, std::abs(slope), band));
  if (commit) {
    problem.Commit(d);
    st->finalValue = trialValue;
  }
  return commit;
}

/// Step 4's shortening: *limited = d shortened by problem.TrustStep, then LimitStep, and made a
/// descent direction (LineSearch::KeepDescent); false where neither shortened d.
bool ShortenStep(StageProblem& problem, LineSearch& search, const Eigen::VectorXd& g,
                 const Eigen::VectorXd& d, Eigen::VectorXd* limited) {
  *limited = d;
  const bool trusted = problem.TrustStep(limited);  // both run: no short circuit
  const bool capped = problem.LimitStep(limited);
  if (!(trusted || capped)) return false;
  search.KeepDescent(g, d, limited);
  return true;
}

std::string LineSearchFailure(const NonlinearSolverParams& params, int it,
                              const LineSearch::Summary& ls, double f, double slope) {
  std::ostringstream s;
  if (params.lineSearch == LineSearchKind::None) {
    s << "the full Newton step gives a non-finite value at iteration " << it + 1;
  } else {
    s << "line search rejected " << params.maxLineSearchSteps << " trials at iteration " << it + 1
      << " (step scale down to " << ls.alpha / params.backtrackFactor << ", f = " << f
      << ", g.d = " << slope << ", last trial value " << ls.trialMerit << ")";
  }
  return s.str();
}

}  // namespace

std::string Format(const ConvergenceTest& test) {
  if (!test.what) return std::string();
  auto append = [](double x, std::string* out) {
    char digits[32];
    const std::to_chars_result r =
        std::to_chars(digits, digits + sizeof digits, x, std::chars_format::general, 6);
    out->append(digits, r.ptr);
  };
  std::string s = test.what;
  if (!*test.bound) return s + test.note;  // a test without a bound: its name says it all
  s += " = ";
  append(test.value, &s);
  s += " <= ";
  s += test.bound;
  s += " = ";
  append(test.boundValue, &s);
  s += test.note;
  return s;
}

SUPERDEX_ENUM_NAMES(LineSearchKind,
    {LineSearchKind::Armijo, "Armijo", "backtracking until the Armijo condition holds"},
    {LineSearchKind::None, "None", "full Newton steps"})

SUPERDEX_ENUM_NAMES(StageStatus,
    {StageStatus::Converged, "Converged", "a convergence test passed"},
    {StageStatus::Stopped, "Stopped", "the iteration cap was reached first"},
    {StageStatus::Diverged, "Diverged", "non-finite values, or no step the line search accepts"})

std::string ValidateSolverInput(const NonlinearSolverParams& params, double timeScale) {
  if (std::string m = Validate(params); !m.empty()) return "invalid parameters: " + m;
  if (!(std::isfinite(timeScale) && timeScale > 0.0)) {
    std::ostringstream s;
    s << "invalid time scale: must be > 0, got " << timeScale;
    return s.str();
  }
  return "";
}

SolverStats MinimizeNewton(StageProblem& problem, const NonlinearSolverParams& params,
                           double timeScale, SymmetricSolver* solverCache,
                           NewtonWorkspace* work, NewtonStart start) {
  SolverStats st;
  if (std::string m = ValidateSolverInput(params, timeScale); !m.empty()) return Diverged(&st, m);

  NewtonSetup<SymmetricSolver> setup(solverCache, work, params, problem);
  const int n = setup.n;
  NewtonWorkspace& w = setup.work;
  SymmetricSolver& solver = setup.solver;
  Eigen::VectorXd &g = w.gradient, &d = w.direction, &limited = w.limited;
  SparseMatrix& H = w.matrix;
  if (n == 0) {
    Stopwatch clock;
    st.finalValue = problem.Evaluate(&g, nullptr, params.psdProjection);
    clock.AddTo(&st.assemblySeconds);
    if (!std::isfinite(st.finalValue)) return Diverged(&st, "non-finite value at the initial state");
    st.status = StageStatus::Converged;
    st.message = "no degrees of freedom";
    return st;
  }

  bool evaluated = false;  // f, g, H already hold the current state's (from an accepted trial)
  double evaluatedValue = 0.0;
  // Adaptive projection (newton_solver.h, 1); the caller may ask for it at once (NewtonStart).
  bool tryExact = start.exactHessian;
  KrylovForcing forcing(params.linear, &w.lastConvergedIterations);
  for (int it = 0; it < params.maxIterations; ++it) {
    // --- Assembly: f, g, H at the current state s.
    Stopwatch clock;
    const bool exact = tryExact && params.psdProjection != PsdProjection::None;
    const bool reused = evaluated;
    double f = evaluated ? evaluatedValue
                         : problem.Evaluate(&g, &H, exact ? PsdProjection::None : params.psdProjection);
    evaluated = false;
    clock.AddTo(&st.assemblySeconds);
    forcing.Next(solver, g);
    const bool exactDirection =
        exact && SolveWithExactHessian(problem, params.psdProjection, solver, &f, &g, &H, &d, &st);
    if (!reused) w.search.ReadSplit(problem);  // an accepted trial's split was read with it
    st.finalValue = f;
    if (g.size() != n || H.rows() != n || H.cols() != n) {
      std::ostringstream s;
      s << "gradient/Hessian of size " << g.size() << "/" << H.rows() << "x" << H.cols()
        << " for " << n << " degrees of freedom";
      return Diverged(&st, s.str());
    }
    if (!std::isfinite(f) || !g.allFinite()) {
      std::ostringstream s;
      s << "non-finite value or gradient at iteration " << it + 1 << " (f = " << f << ")";
      return Diverged(&st, s.str());
    }
    RecordNorm(&st, it, g);
    if (it == 0 && st.initialGradientNorm == 0.0) {
      st.status = StageStatus::Converged;
      st.message = "gradient is exactly zero at the initial state";
      return st;
    }

    // --- Direction d = −H̃⁻¹g (newton_solver.h, 2).
    clock.Restart();
    H.makeCompressed();
    if (!AllFinite(H))
      return Diverged(&st, "non-finite Hessian entry at iteration " + std::to_string(it + 1));
    if (st.finalGradientNorm == 0.0) {
      d.setZero();  // an exact stationary point: nothing to solve (g·d = 0 is no descent failure)
    } else if (!exactDirection) {
      const RegularizedSolve rs = SolveRegularized(solver, &H, g, ShiftGoal::Descent, &d,
                                                   &w.shifted, &w.diagonal, &st);
      if (!rs.solved) {
        clock.AddTo(&st.factorizationSeconds);
        std::ostringstream s;
        s << "no descent direction at iteration " << it + 1
          << ": the Hessian stays singular or indefinite with diagonal shifts up to "
          << rs.lastShift;
        return Diverged(&st, s.str());
      }
    }
    clock.AddTo(&st.factorizationSeconds);
    st.iterations = it + 1;
    const double slope = g.dot(d);  // g·d < 0 (or 0 at an exact stationary point)
    const double decrement = -0.5 * slope;
    st.finalDecrement = decrement;

    // --- Convergence tests (newton_solver.h, 3), before stepping.
    const ConvergenceTest converged =
        FirstPassedTest(params, kTestNames, st, decrement, problem.StepNorm(d) / timeScale);
    if (converged.what) {
      clock.Restart();
      const bool committed = CommitLastCorrection(problem, d, f, slope, &st);
      clock.AddTo(&st.lineSearchSeconds);
      return Converged(&st, converged, committed, " (last step not taken: it would raise f)", &w);
    }

    // --- The step the problem shortened (newton_solver.h, 4), and the line search along it.
    clock.Restart();
    const bool isLimited = params.lineSearch != LineSearchKind::None && !exactDirection &&
                           ShortenStep(problem, w.search, g, d, &limited);
    if (isLimited) ++st.limitedSteps;
    LineSearch::Start from =
        LineSearch::Start::Potential(f, g, isLimited ? g.dot(limited) : slope, slope);
    from.derivativesAtFirstTrial = !isLimited && params.lineSearch != LineSearchKind::None;
    const LineSearch::Summary ls = w.search.Search(problem, from, isLimited ? limited : d, &w.step,
                                                   &w.trialGradient, &w.trialMatrix);
    st.lineSearchSteps += ls.rejectedTrials;
    if (ls.accepted) {
      if (ls.withDerivatives) {  // the next iteration's f, g and (exact) H
        g.swap(w.trialGradient);
        H.swap(w.trialMatrix);
        evaluatedValue = ls.trialMerit;
        evaluated = true;
      }
      problem.Commit(w.step);
      st.finalValue = ls.trialMerit;
    }
    tryExact = ls.accepted && ls.alpha == 1.0 && !isLimited;
    clock.AddTo(&st.lineSearchSeconds);
    if (!ls.accepted) return Diverged(&st, LineSearchFailure(params, it, ls, f, slope));
  }
  return StoppedAtCap(&st, params, "|g|_inf", "Newton decrement");
}

}  // namespace superdex
