// Newton's method on a residual r that is not a gradient. See docs/solver.md; the notes and
// measurements behind these rules: docs/optim-notes.md.
//
// Each iteration k at state s_k:
//   1. r, J ← problem.EvaluateResidual (J = ∂r/∂δ, not symmetric). Non-finite → Diverged.
//   2. d = −J⁻¹ r with a sparse LU (KLU or UMFPACK; symbolic analysis kept while the pattern
//      holds; a dense partial-pivoting LU up to 48 unknowns). If J is singular, J + τI on the
//      shift ladder of optim/regularized_solve.h (ShiftGoal::Nonsingular: τ = 1e-8 max|J_ii|
//      ×10, 12 times); none works → Diverged.
//   3. Convergence tests on d before stepping, as the minimizer's (same parameters and units):
//        a. ½ |r·d| <= absoluteTolerance  [J]  (the Newton decrement's analogue)
//        b. ‖r‖∞ <= relativeTolerance ‖r_0‖∞
//        c. StepNorm(d)/timeScale <= stepTolerance [m/s]
//      On success the step d is still taken: unchecked when the previous iteration's full step
//      (α = 1) cut θ by 1e-4 or more (‖r‖ by 100×: the quadratic regime, where Newton's step
//      lowers θ further), otherwise only if θ(s ⊕ d) <= θ(s), which costs one residual
//      evaluation (SolverStats then reports ‖r‖ at s ⊕ d; unchecked, at s).
//   4. Trust region: where problem.TrustStep shortens d blockwise, the line search starts each
//      part at α_P = the smallest fraction any of its dofs was shortened to (the whole step
//      without parts), along Newton's own direction, so the merit test below stays exact.
//      problem.LimitStep is not used here.
//      Line search on the merit θ(s) = ½‖r(s)‖² (optim/line_search.h, Merit::ResidualSquared):
//      α = φ, φβ, φβ², ... (φ = 1 where the trust region did not shorten d) until
//        θ(s ⊕ αd) <= (1 − 2cα) θ(s)   (c = armijoConstant; d is a descent direction of θ with
//      slope −2θ because J d = −r), or |θ(s ⊕ αd) − θ(s)| within round-off of θ(s) while
//      α ½|r·d| is too. maxLineSearchSteps rejections → Diverged. The first trial is evaluated
//      with its Jacobian where the problem offers EvaluateResidualAtStep (equal bit for bit to
//      step 1 after the commit): when it is accepted, step 1 of the next iteration is skipped.
//      With partLineSearch, independent parts (StageProblem::LastSplit) get their own α, tested
//      on their own θ_P (optim/part_line_search.h); steps 3 and 5 then read the smallest α.
//   5. Stagnation: three iterations in a row whose accepted step was cut to α <= β^10 and lowered
//      θ by less than 1e-6 θ → Diverged at once (a residual without a nearby root, or with a kink
//      where Newton's direction stops helping: the caller's fallback then takes over).
//   Iteration cap → Stopped.
#pragma once

#include "optim/linear_solver.h"
#include "optim/newton_solver.h"

namespace superdex {

/// Solves r(s) = 0 from the problem's current state; leaves it at the last accepted iterate.
/// SolverStats fields keep their names: "gradient" norms are residual norms, finalDecrement is
/// ½|r·d| [J], finalValue is θ = ½‖r‖². `solver` (may be null) is a linear solver kept across
/// calls, so that its symbolic analysis survives from stage to stage while the pattern holds;
/// `work` (may be null) its buffers.
SolverStats SolveResidualNewton(StageProblem& problem, const NonlinearSolverParams& params,
                                double timeScale, UnsymmetricSolver* solver = nullptr,
                                NewtonWorkspace* work = nullptr);

}  // namespace superdex
