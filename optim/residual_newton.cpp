#include "optim/residual_newton.h"

#include "optim/forcing_term.h"
#include "optim/linear_solver.h"
#include "optim/regularized_solve.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

namespace superdex {
namespace {

using Clock = std::chrono::steady_clock;
using SparseMatrix = Eigen::SparseMatrix<double>;

double SecondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

constexpr double kRoundoffBand = 1e-14;
constexpr double kStagnantDecrease = 1e-6;
constexpr int kStagnantIterations = 3;
constexpr double kQuadraticContraction = 1e-4;  // θ ratio of a full step in the quadratic regime

}  // namespace

SolverStats SolveResidualNewton(StageProblem& problem, const NonlinearSolverParams& params,
                                double timeScale, UnsymmetricSolver* solver,
                                NewtonWorkspace* work) {
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
  Eigen::VectorXd &r = w.gradient, &rTrial = w.trialGradient, &d = w.direction, &step = w.step;
  d.resize(n);
  step.resize(n);
  SparseMatrix &J = w.matrix, &JTrial = w.trialMatrix;
  bool evaluated = false;  // r and J already hold the current state's (from an accepted trial)
  std::unique_ptr<UnsymmetricSolver> ownSolver;  // only without a cached solver
  if (!solver) ownSolver = std::make_unique<UnsymmetricSolver>();
  UnsymmetricSolver& lu = solver ? *solver : *ownSolver;
  lu.SetSettings(params.linear);
  lu.SetBlockLayout(problem.BlockLayout());
  if (n == 0) {
    st.status = StageStatus::Converged;
    st.message = "no degrees of freedom";
    return st;
  }

  int stagnant = 0;  // consecutive stagnant iterations (below)
  bool quadratic = false;  // the last accepted step was full and cut θ by kQuadraticContraction
  const double stagnantStep = std::pow(params.backtrackFactor, 10);
  PartLineSearch& parts = w.parts;
  const bool usePartSearch = params.partLineSearch && params.lineSearch != LineSearchKind::None;
  bool split = false;  // the parts of s are known (parts.Begin): one step length per part
  // Krylov solves to the Eisenstat–Walker forcing term (optim/forcing_term.h).
  ForcingTerm forcing(params.linear.tolerance, w.lastConvergedIterations);
  w.lastConvergedIterations = -1;  // until this solve converges
  LinearSolverSettings linear = params.linear;
  const bool inexact = params.linear.kind != LinearSolverKind::Direct;
  for (int it = 0; it < params.maxIterations; ++it) {
    Clock::time_point t0 = Clock::now();
    if (!evaluated) {
      problem.EvaluateResidual(&r, &J);
      split = usePartSearch && parts.Begin(problem);
    }
    evaluated = false;
    st.assemblySeconds += SecondsSince(t0);
    if (r.size() != n || J.rows() != n || J.cols() != n)
      return diverge("the stage problem provides no residual of the right size");
    if (!r.allFinite()) return diverge("non-finite residual at iteration " + std::to_string(it + 1));
    const double theta = 0.5 * r.squaredNorm();
    st.finalValue = theta;
    st.finalGradientNorm = r.lpNorm<Eigen::Infinity>();
    if (it == 0) st.initialGradientNorm = st.finalGradientNorm;
    if (st.finalGradientNorm == 0.0) {
      st.status = StageStatus::Converged;
      st.message = "residual is exactly zero";
      return st;
    }

    if (inexact) {
      linear.tolerance = forcing.Next(r.norm());
      lu.SetSettings(linear);
    }
    t0 = Clock::now();
    J.makeCompressed();
    if (!Eigen::Map<const Eigen::VectorXd>(J.valuePtr(), J.nonZeros()).allFinite())
      return diverge("non-finite Jacobian entry at iteration " + std::to_string(it + 1));
    const RegularizedSolve rs = SolveRegularized(lu, &J, r, ShiftGoal::Nonsingular, &d,
                                                 &w.shifted, &w.diagonal, &st);
    if (!rs.solved) {
      st.factorizationSeconds += SecondsSince(t0);
      return diverge("singular Jacobian at iteration " + std::to_string(it + 1));
    }
    st.factorizationSeconds += SecondsSince(t0);
    st.iterations = it + 1;
    const double decrement = 0.5 * std::abs(r.dot(d));
    st.finalDecrement = decrement;

    // The passed test is kept, formatted only on demand (SolverStats::Message).
    ConvergenceTest converged;
    const double stepVelocity = problem.StepNorm(d) / timeScale;
    if (decrement <= params.absoluteTolerance) {
      converged = {"residual decrement 0.5|r.d|", decrement, "absolute_tolerance",
                   params.absoluteTolerance};
    } else if (st.finalGradientNorm <= params.relativeTolerance * st.initialGradientNorm) {
      converged = {"residual norm |r|_inf", st.finalGradientNorm, "relative_tolerance * |r0|_inf",
                   params.relativeTolerance * st.initialGradientNorm};
    } else if (stepVelocity <= params.stepTolerance) {
      converged = {"step StepNorm(d)/dt [m/s]", stepVelocity, "step_tolerance",
                   params.stepTolerance};
    }
    if (converged.what) {
      // The last correction: in the quadratic regime (the previous iteration's full step cut θ
      // by kQuadraticContraction or more) it is committed unchecked, as Newton's local theory
      // says it lowers θ further; otherwise only if r(s ⊕ d) shows it does not raise θ.
      t0 = Clock::now();
      bool commit = quadratic;
      if (!commit) {
        problem.Residual(d, &rTrial);
        commit = rTrial.allFinite() && 0.5 * rTrial.squaredNorm() <= theta;
        if (commit) {
          st.finalValue = 0.5 * rTrial.squaredNorm();
          st.finalGradientNorm = rTrial.lpNorm<Eigen::Infinity>();
        }
      }
      if (commit) problem.Commit(d);
      st.lineSearchSeconds += SecondsSince(t0);
      st.status = StageStatus::Converged;
      st.passed = converged;
      w.lastConvergedIterations = st.iterations;
      if (!commit) st.passed.note = " (last step not taken: it would raise |r|)";
      return st;
    }

    t0 = Clock::now();
    double alpha = 1.0;
    bool accepted = false;
    double trialTheta = NAN;
    const int trials = params.lineSearch == LineSearchKind::None ? 1 : params.maxLineSearchSteps;
    const bool partSearch = split;
    if (partSearch) parts.StartResidual(r, d);
    // The problem's trust region (StageProblem::TrustStep) as the first step length along d, per
    // part: α_P = φ_P, so that the merit tests (which assume Newton's direction) stay exact.
    if (params.lineSearch != LineSearchKind::None) {
      Eigen::VectorXd& limited = w.limited;
      limited = d;
      if (problem.TrustStep(&limited)) {
        if (partSearch) {
          parts.CapSteps(d, limited);
        } else {
          alpha = SmallestFraction(d, limited);
        }
      }
    }
    for (int trial = 0; trial < trials; ++trial) {
      if (partSearch) {
        parts.Step(d, &step);
      } else {
        step.noalias() = alpha * d;
      }
      // The full step is usually taken: its Jacobian is formed with its residual, to serve the
      // next iteration (wasted only when the step is cut back).
      const bool withJacobian =
          trial == 0 && problem.EvaluateResidualAtStep(step, &rTrial, &JTrial);
      if (!withJacobian) problem.Residual(step, &rTrial);
      trialTheta = 0.5 * rTrial.squaredNorm();
      const bool finite = std::isfinite(trialTheta);
      // By parts, Test cuts the failing groups' step lengths itself.
      const bool pass =
          finite &&
          (partSearch ? parts.Test(problem, trialTheta, &rTrial, params.armijoConstant,
                                   params.backtrackFactor, kRoundoffBand)
                      : params.lineSearch == LineSearchKind::None ||
                            trialTheta <= (1.0 - 2.0 * params.armijoConstant * alpha) * theta ||
                            (std::abs(trialTheta - theta) <= kRoundoffBand * theta &&
                             alpha * decrement <= kRoundoffBand * theta));
      if (pass) {
        accepted = true;
        if (withJacobian) {
          r.swap(rTrial);
          J.swap(JTrial);
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
    st.lineSearchSeconds += SecondsSince(t0);
    if (!accepted) {
      std::ostringstream s;
      s << "merit line search rejected " << trials << " trials at iteration " << it + 1
        << " (|r|_inf = " << st.finalGradientNorm << ", last trial 0.5|r|^2 = " << trialTheta
        << ")";
      return diverge(s.str());
    }
    problem.Commit(step);
    quadratic = alpha == 1.0 && trialTheta <= kQuadraticContraction * theta;
    // Stagnation: accepted steps cut back to α <= β^10 that lower ½‖r‖² by less than 1e-6 of it,
    // three iterations in a row, mean the Newton direction is no longer a useful descent
    // direction of the merit (a non-smooth residual, or no root nearby); the solve is reported
    // as failed at once, at the last accepted iterate, rather than after many more trials.
    if (alpha <= stagnantStep && theta - trialTheta <= kStagnantDecrease * theta) {
      if (++stagnant >= kStagnantIterations) {
        std::ostringstream s;
        s << "merit stagnation: " << kStagnantIterations << " iterations in a row with steps cut to "
          << alpha << " lowering 0.5|r|^2 by < " << kStagnantDecrease << " of it (iteration "
          << it + 1 << ", |r|_inf = " << st.finalGradientNorm << ")";
        return diverge(s.str());
      }
    } else {
      stagnant = 0;
    }
  }
  st.status = StageStatus::Stopped;
  std::ostringstream s;
  s << "iteration cap max_iterations = " << params.maxIterations << " reached (|r|_inf = "
    << st.finalGradientNorm << ", decrement " << st.finalDecrement << ")";
  st.message = s.str();
  return st;
}

}  // namespace superdex
