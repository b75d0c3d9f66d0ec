// Ipopt as an independent check of the stage minimizer: the unconstrained minimization of a
// potential stage f(s₀ ⊕ d) over the chart vector d, with the exact gradient Tᵀg and Hessian
// TᵀHT (optim/stage_problem.h; exact at the minimizer, where g = 0), Ipopt's own inertia
// correction for indefinite Hessians, and no scaling. The Hessian is passed as a dense lower
// triangle, so the adapter is meant for small scenes (NumDofs <= kMaxIpoptDofs).
#pragma once

#include "optim/newton_solver.h"

namespace superdex {

constexpr int kMaxIpoptDofs = 600;

struct IpoptStageParams {
  double tolerance = 1e-10;  ///< Ipopt "tol": max-norm of the gradient at convergence [N, N·m]
  int maxIterations = 500;
};

/// Minimizes a potential stage (problem.IsPotential() and SupportsChart()) from its current state;
/// leaves the problem at Ipopt's solution. Refuses (Diverged, with the reason) a non-potential
/// stage, a problem without a chart, or more than kMaxIpoptDofs degrees of freedom.
SolverStats MinimizeIpopt(StageProblem& problem, const IpoptStageParams& params);

}  // namespace superdex
