// Projected Newton with a backtracking (Armijo) line search. See newton_solver.h for the
// convergence tests and the statuses.
#include "optim/newton_solver.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <vector>

#include "optim/forcing_term.h"
#include "optim/linear_solver.h"
#include "optim/regularized_solve.h"

namespace superdex {
namespace {

using Clock = std::chrono::steady_clock;
using SparseMatrix = Eigen::SparseMatrix<double>;

double SecondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// Relative width of the round-off band of the line search: trial values with
/// |f(s ⊕ αd) − f(s)| <= kRoundoffBand |f(s)| cannot be told apart from f(s) in double precision
/// once f is a sum of many terms.
constexpr double kRoundoffBand = 1e-14;

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

namespace {
constexpr EnumName<LineSearchKind> kLineSearches[] = {
    {LineSearchKind::Armijo, "Armijo", "backtracking until the Armijo condition holds"},
    {LineSearchKind::None, "None", "full Newton steps"}};
constexpr EnumName<StageStatus> kStatuses[] = {
    {StageStatus::Converged, "Converged", "a convergence test passed"},
    {StageStatus::Stopped, "Stopped", "the iteration cap was reached first"},
    {StageStatus::Diverged, "Diverged", "non-finite values, or no step the line search accepts"}};
}  // namespace

EnumNames<LineSearchKind> NamesOf(LineSearchKind) { return kLineSearches; }
EnumNames<StageStatus> NamesOf(StageStatus) { return kStatuses; }

std::string Validate(const NonlinearSolverParams& p) {
  return ValidateFields(kNonlinearSolverFields, p);
}

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
  auto diverge = [&st](const std::string& message) {
    st.status = StageStatus::Diverged;
    st.message = message;
    return st;
  };
  if (std::string m = ValidateSolverInput(params, timeScale); !m.empty()) return diverge(m);

  const int n = problem.NumDofs();
  // Only without the caller's: even empty, its sparse matrices allocate their outer index.
  std::unique_ptr<NewtonWorkspace> ownWork;
  if (!work) ownWork = std::make_unique<NewtonWorkspace>();
  NewtonWorkspace& w = work ? *work : *ownWork;
  Eigen::VectorXd &g = w.gradient, &d = w.direction, &step = w.step, &limited = w.limited,
                  &gTrial = w.trialGradient;
  g.resize(n);
  d.resize(n);
  step.resize(n);
  limited.resize(n);
  SparseMatrix &H = w.matrix, &HTrial = w.trialMatrix;
  bool evaluated = false;  // f, g, H already hold the current state's (from an accepted trial)
  double evaluatedValue = 0.0;
  std::unique_ptr<SymmetricSolver> ownSolver;  // only without a cached solver
  if (!solverCache) ownSolver = std::make_unique<SymmetricSolver>();
  SymmetricSolver& solver = solverCache ? *solverCache : *ownSolver;
  solver.SetSettings(params.linear);
  solver.SetBlockLayout(problem.BlockLayout());

  if (n == 0) {
    Clock::time_point t0 = Clock::now();
    st.finalValue = problem.Evaluate(&g, nullptr, params.psdProjection);
    st.assemblySeconds = SecondsSince(t0);
    if (!std::isfinite(st.finalValue)) return diverge("non-finite value at the initial state");
    st.status = StageStatus::Converged;
    st.message = "no degrees of freedom";
    return st;
  }

  // Adaptive projection: after a full step (α = 1: the local regime) the next iteration tries the
  // exact Hessian; if it is not positive definite the iteration is re-assembled projected. The
  // caller may ask for it at the first iteration (NewtonStart).
  bool tryExact = start.exactHessian;
  PartLineSearch& parts = w.parts;
  const bool usePartSearch = params.partLineSearch && params.lineSearch != LineSearchKind::None;
  bool split = false;  // the parts of s are known (parts.Begin): one step length per part
  // Krylov solves to the Eisenstat–Walker forcing term (optim/forcing_term.h); direct solves are
  // exact either way.
  ForcingTerm forcing(params.linear.tolerance, w.lastConvergedIterations);
  w.lastConvergedIterations = -1;  // until this solve converges
  LinearSolverSettings linear = params.linear;
  const bool inexact = params.linear.kind != LinearSolverKind::Direct;
  for (int it = 0; it < params.maxIterations; ++it) {
    // --- Assembly: f, g, H at the current state s.
    Clock::time_point t0 = Clock::now();
    const bool exact = tryExact && params.psdProjection != PsdProjection::None;
    const bool reused = evaluated;
    double f = evaluated ? evaluatedValue
                         : problem.Evaluate(&g, &H, exact ? PsdProjection::None : params.psdProjection);
    evaluated = false;
    st.assemblySeconds += SecondsSince(t0);
    if (inexact) {
      linear.tolerance = forcing.Next(g.norm());
      solver.SetSettings(linear);
    }
    if (exact) {
      // Accept the exact Hessian only if it factorizes as is and gives a descent direction.
      t0 = Clock::now();
      H.makeCompressed();
      bool good = Eigen::Map<const Eigen::VectorXd>(H.valuePtr(), H.nonZeros()).allFinite() &&
                  g.allFinite() && solver.Factorize(H);
      if (good) {
        SolveNegated(solver, g, &d, &st);
        good = d.allFinite() && g.dot(d) < 0.0;
      }
      st.factorizationSeconds += SecondsSince(t0);
      if (!good) {
        t0 = Clock::now();
        f = problem.Evaluate(&g, &H, params.psdProjection);
        st.assemblySeconds += SecondsSince(t0);
      }
      tryExact = good;
    }
    // The split of the evaluation at s (an accepted trial's was adopted with it).
    if (!reused) split = usePartSearch && parts.Begin(problem);
    st.finalValue = f;
    if (g.size() != n || H.rows() != n || H.cols() != n) {
      std::ostringstream s;
      s << "gradient/Hessian of size " << g.size() << "/" << H.rows() << "x" << H.cols()
        << " for " << n << " degrees of freedom";
      return diverge(s.str());
    }
    if (!std::isfinite(f) || !g.allFinite()) {
      std::ostringstream s;
      s << "non-finite value or gradient at iteration " << it + 1 << " (f = " << f << ")";
      return diverge(s.str());
    }
    st.finalGradientNorm = g.lpNorm<Eigen::Infinity>();
    if (it == 0) st.initialGradientNorm = st.finalGradientNorm;
    if (it == 0 && st.initialGradientNorm == 0.0) {
      st.status = StageStatus::Converged;
      st.message = "gradient is exactly zero at the initial state";
      return st;
    }

    // --- Direction d = −H̃⁻¹g, H̃ = H or H + τI (the smallest shift on the ladder that gives a
    // positive definite matrix and a descent direction).
    t0 = Clock::now();
    H.makeCompressed();
    if (!Eigen::Map<const Eigen::VectorXd>(H.valuePtr(), H.nonZeros()).allFinite())
      return diverge("non-finite Hessian entry at iteration " + std::to_string(it + 1));
    if (st.finalGradientNorm == 0.0) {
      d.setZero();  // an exact stationary point: nothing to solve (g·d = 0 is no descent failure)
    } else if (!(exact && tryExact)) {  // else: the exact Hessian's direction, solved above
      const RegularizedSolve rs = SolveRegularized(solver, &H, g, ShiftGoal::Descent, &d,
                                                   &w.shifted, &w.diagonal, &st);
      if (!rs.solved) {
        st.factorizationSeconds += SecondsSince(t0);
        std::ostringstream s;
        s << "no descent direction at iteration " << it + 1
          << ": the Hessian stays singular or indefinite with diagonal shifts up to "
          << rs.lastShift;
        return diverge(s.str());
      }
    }
    st.factorizationSeconds += SecondsSince(t0);
    st.iterations = it + 1;
    const double slope = g.dot(d);  // g·d < 0 (or 0 at an exact stationary point)
    const double decrement = -0.5 * slope;
    st.finalDecrement = decrement;

    // Round-off band: accept a trial value indistinguishable from f when the predicted change
    // |α g·d| (≈ α‖d‖²_H̃, the step length in the Hessian norm) is itself inside the band, i.e.
    // the step is too small for f to resolve its decrease. Far from a minimum it never applies.
    const double band = kRoundoffBand * std::abs(f);
    auto withinRoundoff = [&](double trialValue, double alpha) {
      return std::abs(trialValue - f) <= band && alpha * std::abs(slope) <= band;
    };

    // --- Convergence tests (see newton_solver.h), before stepping.
    ConvergenceTest converged;
    const double stepVelocity = problem.StepNorm(d) / timeScale;
    if (decrement <= params.absoluteTolerance) {
      converged = {"Newton decrement 0.5 g^T H^-1 g", decrement, "absolute_tolerance",
                   params.absoluteTolerance};
    } else if (st.finalGradientNorm <= params.relativeTolerance * st.initialGradientNorm) {
      converged = {"gradient norm |g|_inf", st.finalGradientNorm, "relative_tolerance * |g0|_inf",
                   params.relativeTolerance * st.initialGradientNorm};
    } else if (stepVelocity <= params.stepTolerance) {
      converged = {"step StepNorm(d)/dt [m/s]", stepVelocity, "step_tolerance",
                   params.stepTolerance};
    }
    if (converged.what) {
      // Take the last Newton correction as well, unless it would raise f. When the decrease it
      // promises, |g·d|, is itself inside the round-off band, f cannot tell its value there from
      // f(s) (the band test below would accept any trial value f could resolve as equal): the
      // correction is committed without evaluating f there (finalValue stays f(s)). Measured:
      // 11 % of a free-flight step of the drop, 8 % of the explicit-normals incline at Δt = 0.2.
      t0 = Clock::now();
      const bool unresolvable = std::abs(slope) <= band;
      const double trialValue = unresolvable ? f : problem.Value(d);
      const bool commit = std::isfinite(trialValue) &&
                          (trialValue <= f || withinRoundoff(trialValue, 1.0));
      if (commit) {
        problem.Commit(d);
        st.finalValue = trialValue;
      }
      st.lineSearchSeconds += SecondsSince(t0);
      st.status = StageStatus::Converged;
      st.passed = converged;
      w.lastConvergedIterations = st.iterations;
      if (!commit) st.passed.note = " (last step not taken: it would raise f)";
      return st;
    }

    // --- The problem may shorten d blockwise (StageProblem::TrustStep, LimitStep); the
    // shortened step is used, made a descent direction where it is none (newton_solver.h, 4).
    t0 = Clock::now();
    limited = d;
    bool isLimited = false;
    if (params.lineSearch != LineSearchKind::None && !(exact && tryExact)) {
      const bool trusted = problem.TrustStep(&limited);  // both run: no short circuit
      const bool capped = problem.LimitStep(&limited);
      isLimited = trusted || capped;
      // A part whose shortened step is no descent direction takes its Newton direction scaled
      // uniformly instead; so does the whole step if it still is none (one part). Never the
      // unshortened step: its bodies would move past what the bounds allow.
      if (isLimited && split) parts.ShortenByParts(g, d, &limited);
      if (isLimited && !(g.dot(limited) < 0.0)) limited = SmallestFraction(d, limited) * d;
    }
    const Eigen::VectorXd& dir = isLimited ? limited : d;
    const double dirSlope = isLimited ? g.dot(limited) : slope;
    if (isLimited) ++st.limitedSteps;

    // --- Line search along dir. No allocation here: `step` is preallocated.
    double alpha = 1.0;
    double trialValue = std::numeric_limits<double>::quiet_NaN();
    bool accepted = false;
    if (params.lineSearch == LineSearchKind::None) {
      trialValue = problem.Value(dir);
      accepted = std::isfinite(trialValue);
      step = dir;
    } else {
      const bool partSearch = split;
      if (partSearch) parts.StartMinimization(g, dir);
      for (int trial = 0; trial < params.maxLineSearchSteps; ++trial) {
        if (partSearch) {
          parts.Step(dir, &step);
        } else {
          step.noalias() = alpha * dir;
        }
        // The full, unshortened step is usually taken: its gradient and Hessian (the exact one,
        // as the next iteration tries first) are formed with its value, to serve the next
        // iteration (wasted only when the step is cut back).
        const bool withDerivatives =
            trial == 0 && !isLimited &&
            problem.EvaluateAtStep(step, &trialValue, &gTrial, &HTrial, PsdProjection::None);
        if (!withDerivatives) trialValue = problem.Value(step);
        // Non-finite values (e.g. inverted elements) are rejections; comparisons with NaN fail.
        // By parts, Test cuts the failing groups' step lengths itself.
        const bool finite = std::isfinite(trialValue);
        const bool pass =
            finite && (partSearch ? parts.Test(problem, trialValue, nullptr,
                                               params.armijoConstant, params.backtrackFactor,
                                               kRoundoffBand)
                                  : trialValue <= f + params.armijoConstant * alpha * dirSlope ||
                                        withinRoundoff(trialValue, alpha * dirSlope / slope));
        if (pass) {
          accepted = true;
          if (withDerivatives) {
            g.swap(gTrial);
            H.swap(HTrial);
            evaluatedValue = trialValue;
            evaluated = true;
            // The trial's split is the next state's.
            split = partSearch ? parts.AdoptTrial() : usePartSearch && parts.Begin(problem);
          }
          break;
        }
        ++st.lineSearchSteps;
        if (!partSearch) {
          alpha *= params.backtrackFactor;
        } else if (!finite) {
          parts.CutAll(params.backtrackFactor);
        }
      }
      if (partSearch) alpha = accepted && parts.AllFull() ? 1.0 : parts.MinAlpha();
    }
    if (accepted) {
      problem.Commit(step);
      st.finalValue = trialValue;
    }
    tryExact = accepted && alpha == 1.0 && !isLimited;
    st.lineSearchSeconds += SecondsSince(t0);
    if (!accepted) {
      std::ostringstream s;
      if (params.lineSearch == LineSearchKind::None) {
        s << "the full Newton step gives a non-finite value at iteration " << it + 1;
      } else {
        s << "line search rejected " << params.maxLineSearchSteps << " trials at iteration "
          << it + 1 << " (step scale down to " << alpha / params.backtrackFactor << ", f = " << f
          << ", g.d = " << slope << ", last trial value " << trialValue << ")";
      }
      return diverge(s.str());
    }
  }

  st.status = StageStatus::Stopped;
  std::ostringstream s;
  s << "iteration cap max_iterations = " << params.maxIterations << " reached (|g|_inf = "
    << st.finalGradientNorm << ", Newton decrement " << st.finalDecrement << ")";
  st.message = s.str();
  return st;
}

}  // namespace superdex
