// Ceres as an independent check of the residual stage solver: r(s₀ ⊕ d) = 0 solved as the
// nonlinear least-squares problem min_d ½‖r(s₀ ⊕ d)‖² (Levenberg–Marquardt, dense QR) with the
// exact chart Jacobian J T (optim/stage_problem.h). Works for every stage: for a potential the
// residual is its gradient. Dense, so meant for small scenes (NumDofs <= kMaxCeresDofs).
#pragma once

#include "optim/newton_solver.h"

namespace superdex {

constexpr int kMaxCeresDofs = 600;

struct CeresStageParams {
  double functionTolerance = 1e-20;   ///< relative decrease of ½‖r‖² [-]
  double gradientTolerance = 1e-20;   ///< max-norm of Jᵀr relative to its start [-]
  double parameterTolerance = 1e-15;  ///< relative step [-]
  int maxIterations = 200;
};

/// Solves the stage from its current state; leaves the problem at Ceres' solution. Refuses
/// (Diverged, with the reason) a problem without a chart or with more than kMaxCeresDofs dofs.
SolverStats SolveCeres(StageProblem& problem, const CeresStageParams& params);

}  // namespace superdex
