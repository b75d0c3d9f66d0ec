#include "optim/newton_solver.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "optim/linear_solver.h"

namespace superdex {
namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string Describe(const char* what, double value, const char* rule, double bound) {
  std::ostringstream s;
  s << what << " " << value << " " << rule << " " << bound;
  return s.str();
}

}  // namespace

const char* ToString(StageStatus status) {
  switch (status) {
    case StageStatus::Converged: return "Converged";
    case StageStatus::Stopped: return "Stopped";
    case StageStatus::Diverged: return "Diverged";
  }
  return "?";
}

std::string Validate(const NonlinearSolverParams& p) {
  std::ostringstream s;
  if (p.maxIterations < 1) s << "max_iterations: must be >= 1, got " << p.maxIterations;
  else if (!(p.absoluteTolerance >= 0)) s << "absolute_tolerance: must be >= 0, got " << p.absoluteTolerance;
  else if (!(p.relativeTolerance >= 0)) s << "relative_tolerance: must be >= 0, got " << p.relativeTolerance;
  else if (!(p.stepTolerance >= 0)) s << "step_tolerance: must be >= 0, got " << p.stepTolerance;
  else if (!(p.armijoConstant > 0 && p.armijoConstant < 1))
    s << "armijo_constant: must be in (0, 1), got " << p.armijoConstant;
  else if (!(p.backtrackFactor > 0 && p.backtrackFactor < 1))
    s << "backtrack_factor: must be in (0, 1), got " << p.backtrackFactor;
  else if (p.maxLineSearchSteps < 1)
    s << "max_line_search_steps: must be >= 1, got " << p.maxLineSearchSteps;
  return s.str();
}

SolverStats MinimizeNewton(StageProblem& problem, const NonlinearSolverParams& params,
                           double timeScale) {
  SolverStats st;
  const int n = problem.NumDofs();
  Eigen::VectorXd g(n), d(n), trial(n);
  Eigen::SparseMatrix<double> H;
  SymmetricSolver solver;
  if (n == 0) {
    st.status = StageStatus::Converged;
    st.message = "no degrees of freedom";
    return st;
  }
  for (int it = 0; it < params.maxIterations; ++it) {
    auto t0 = Clock::now();
    const double f = problem.Evaluate(&g, &H, params.psdProjection);
    st.assemblySeconds += Since(t0);
    st.finalValue = f;
    st.finalGradientNorm = g.lpNorm<Eigen::Infinity>();
    if (it == 0) st.initialGradientNorm = st.finalGradientNorm;
    if (!std::isfinite(f) || !g.allFinite()) {
      st.status = StageStatus::Diverged;
      st.message = "non-finite value or gradient";
      return st;
    }
    if (st.finalGradientNorm == 0.0) {
      st.status = StageStatus::Converged;
      st.message = "gradient is exactly zero";
      return st;
    }
    // Newton direction d = −H⁻¹ g, with a diagonal shift where H is not positive definite.
    t0 = Clock::now();
    bool ok = solver.Factorize(H);
    if (ok) d = -solver.Solve(g);
    if (!ok || !d.allFinite() || g.dot(d) >= 0.0) {
      double maxDiag = 0.0;
      for (int k = 0; k < H.outerSize(); ++k) maxDiag = std::max(maxDiag, std::abs(H.coeff(k, k)));
      double tau = 1e-8 * std::max(maxDiag, 1e-12);
      Eigen::SparseMatrix<double> I(n, n);
      I.setIdentity();
      ok = false;
      for (int r = 0; r < 16 && !ok; ++r, tau *= 10.0) {
        ++st.regularizations;
        const Eigen::SparseMatrix<double> Hs = H + tau * I;
        if (solver.Factorize(Hs)) {
          d = -solver.Solve(g);
          ok = d.allFinite() && g.dot(d) < 0.0;
        }
      }
      if (!ok) d = -g;  // steepest descent as the last resort
    }
    st.factorizationSeconds += Since(t0);
    const double decrement = -0.5 * g.dot(d);
    st.finalDecrement = decrement;
    st.iterations = it + 1;

    std::string converged;
    if (decrement <= params.absoluteTolerance)
      converged = Describe("Newton decrement", decrement, "<=", params.absoluteTolerance);
    else if (st.finalGradientNorm <= params.relativeTolerance * st.initialGradientNorm && it > 0)
      converged = Describe("gradient norm", st.finalGradientNorm, "<= relative tolerance x",
                           st.initialGradientNorm);
    else if (problem.StepNorm(d) <= params.stepTolerance * timeScale)
      converged = Describe("step/dt", problem.StepNorm(d) / timeScale, "<=", params.stepTolerance);

    // Line search.
    t0 = Clock::now();
    double alpha = 1.0;
    const double slope = g.dot(d);
    bool accepted = false;
    for (int ls = 0; ls < params.maxLineSearchSteps; ++ls) {
      trial = alpha * d;
      const double ft = problem.Value(trial);
      if (params.lineSearch == LineSearchKind::None && std::isfinite(ft)) {
        accepted = true;
        break;
      }
      if (std::isfinite(ft) && (ft <= f + params.armijoConstant * alpha * slope ||
                                // Round-off band: at convergence f changes below its precision.
                                std::abs(ft - f) <= 1e-14 * std::abs(f) + 1e-300)) {
        accepted = true;
        break;
      }
      ++st.lineSearchSteps;
      alpha *= params.backtrackFactor;
    }
    st.lineSearchSeconds += Since(t0);
    if (accepted) problem.Commit(trial);
    if (!converged.empty()) {
      st.status = StageStatus::Converged;
      st.message = converged;
      return st;
    }
    if (!accepted) {
      st.status = StageStatus::Diverged;
      std::ostringstream s;
      s << "line search found no decrease after " << params.maxLineSearchSteps
        << " trials (gradient norm " << st.finalGradientNorm << ")";
      st.message = s.str();
      return st;
    }
  }
  st.status = StageStatus::Stopped;
  std::ostringstream s;
  s << "iteration cap " << params.maxIterations << " reached (gradient norm "
    << st.finalGradientNorm << ", decrement " << st.finalDecrement << ")";
  st.message = s.str();
  return st;
}

}  // namespace superdex
