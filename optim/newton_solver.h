// Projected Newton with a backtracking (Armijo) line search.
#pragma once

#include <string>

#include "optim/stage_problem.h"

namespace superdex {

enum class LineSearchKind {
  Armijo,  ///< backtracking until f(s ⊕ αd) <= f(s) + c α g·d
  None,    ///< full Newton steps
};

/// How a stage solve ended.
enum class StageStatus {
  Converged,  ///< a convergence test passed
  Stopped,    ///< the iteration cap was reached first
  Diverged,   ///< non-finite values, or no step the line search accepts
};
const char* ToString(StageStatus status);

/// Settings of the nonlinear stage solver. Units: `timeScale` passed to the solver is the stage's
/// time step Δt_i [s]; a step d is converted to a velocity by StepNorm(d) / Δt_i [m/s].
struct NonlinearSolverParams {
  int maxIterations = 100;            ///< Newton iterations before status Stopped
  double absoluteTolerance = 1e-12;   ///< converged when ½ g^T H^-1 g (Newton decrement) <= this [J]
  double relativeTolerance = 1e-10;   ///< ... or when ‖g‖∞ <= relativeTolerance * ‖g_0‖∞ [-]
  double stepTolerance = 1e-9;        ///< ... or when StepNorm(d)/Δt_i <= this [m/s]
  LineSearchKind lineSearch = LineSearchKind::Armijo;
  PsdProjection psdProjection = PsdProjection::Clamp;
  double armijoConstant = 1e-4;       ///< c in the Armijo condition
  double backtrackFactor = 0.5;       ///< α ← factor α on each rejected trial
  int maxLineSearchSteps = 40;        ///< trials before the stage is declared Diverged
};

/// Statistics of one stage solve. Times are wall seconds.
struct SolverStats {
  StageStatus status = StageStatus::Stopped;
  int iterations = 0;
  int lineSearchSteps = 0;             ///< rejected line-search trials, summed over iterations
  int regularizations = 0;             ///< times the Hessian needed a diagonal shift
  double initialGradientNorm = 0.0;    ///< ‖g‖∞ at the first iterate
  double finalGradientNorm = 0.0;      ///< ‖g‖∞ at the last evaluated iterate
  double finalDecrement = 0.0;         ///< ½ g^T H^-1 g at the last iteration [J]
  double finalValue = 0.0;
  double assemblySeconds = 0.0;
  double factorizationSeconds = 0.0;
  double lineSearchSeconds = 0.0;
  std::string message;                 ///< why it stopped, in words
};

/// Minimizes the problem from its current state. The problem is left at the last accepted iterate.
/// `timeScale` > 0 is the stage time step Δt_i [s] used by the step test.
SolverStats MinimizeNewton(StageProblem& problem, const NonlinearSolverParams& params,
                           double timeScale);

/// Validates the parameters; returns an empty string if valid, else a message naming the field.
std::string Validate(const NonlinearSolverParams& params);

}  // namespace superdex
