// Projected Newton with a backtracking (Armijo) line search. See docs/solver.md; the notes and
// measurements behind these rules: docs/optim-notes.md.
//
// Each iteration k at state s_k:
//   1. f, g, H ← problem.Evaluate (local Hessians projected as params.psdProjection says).
//      Non-finite f or g (or H) → Diverged.
//      Adaptive projection: after an iteration whose full step was accepted (α = 1) the next one
//      assembles the exact Hessian (no projection); if that is not positive definite or gives no
//      descent direction, the iteration is re-assembled projected.
//   2. d = −H̃⁻¹ g with H̃ = H if it factorizes (CHOLMOD, LDLᵀ fallback) and g·d < 0; otherwise
//      H̃ = H + τI on the shift ladder of optim/regularized_solve.h (ShiftGoal::Descent: τ =
//      1e-8 max_i |H_ii| ×10, 12 times, then one Gershgorin shift). The first τ that gives a
//      positive definite H̃ and a descent direction is taken; SolverStats::regularizations counts
//      the iterations that needed a shift. If none works → Diverged.
//   3. Convergence tests, in this order, on d before stepping (the first that passes is named in
//      SolverStats::message):
//        a. Newton decrement  λ = ½ gᵀH̃⁻¹g = −½ g·d <= absoluteTolerance            [J]
//        b. gradient          ‖g_k‖∞ <= relativeTolerance ‖g_0‖∞                     [-]
//           (if ‖g_0‖∞ == 0 the solve is Converged at once, with 0 iterations)
//        c. step              StepNorm(d) / timeScale <= stepTolerance               [m/s]
//      When one passes, the full step d is still committed if f(s ⊕ d) <= f(s) (or lies in the
//      round-off band below), so the returned state includes the last Newton correction; status
//      Converged. A correction whose promised decrease |g·d| is itself inside the round-off band
//      (<= 1e-14 |f(s)|: f cannot resolve it) is committed without evaluating f(s ⊕ d), and
//      SolverStats::finalValue stays f(s).
//   4. Step shortening: d' = d shortened blockwise by problem.TrustStep, then by
//      problem.LimitStep (optim/stage_problem.h). Where a part's d' is no descent direction for
//      its share, that part takes d_P scaled by the smallest fraction its dofs were shortened to,
//      and so does the whole step if g·d' >= 0 remains (LineSearch::KeepDescent; never the
//      unshortened d, which would pass the bounds). An iteration on a shortened step is not a
//      full step for the adaptive projection. Skipped with LineSearchKind::None and on
//      exact-Hessian iterations.
//      Line search on f (optim/line_search.h, Merit::Potential): α = 1, β, β², ...
//      (β = backtrackFactor); accept the first α with
//        f(s ⊕ αd') <= f(s) + c α g·d'                                  (c = armijoConstant)
//      or the round-off band: |f(s ⊕ αd') − f(s)| <= 1e-14 |f(s)| while the predicted change
//      α|g·d'| is also <= 1e-14 |f(s)|. Non-finite trial values are rejections. After
//      maxLineSearchSteps rejections → Diverged. LineSearchKind::None takes α = 1 (Diverged only
//      if f(s ⊕ d) is not finite). s ← s ⊕ αd'. The unshortened full step's trial is evaluated
//      with its gradient and exact Hessian where the problem offers EvaluateAtStep (equal bit for
//      bit to step 1 after the commit): when it is accepted, step 1 of the next iteration is
//      skipped. Where the problem splits into independent parts (StageProblem::LastSplit) and
//      partLineSearch is set, each part gets its own α, tested on its own share of f
//      (optim/part_line_search.h); a part whose direction is no descent for its share stays put.
//      The next iteration tries the exact Hessian only if every part took α = 1.
//   After maxIterations iterations without convergence → Stopped (the last step is committed but
//   not tested: Stopped is reported even if it happened to reach the minimum).
#pragma once

#include <string>
#include <vector>

#include "optim/line_search.h"
#include "optim/linear_solver.h"
#include "optim/stage_problem.h"

namespace superdex {

/// How a stage solve ended.
enum class StageStatus {
  Converged,  ///< a convergence test passed
  Stopped,    ///< the iteration cap was reached first
  Diverged,   ///< non-finite values, or no step the line search accepts
};
EnumNames<LineSearchKind> NamesOf(LineSearchKind);
EnumNames<StageStatus> NamesOf(StageStatus);

/// Settings of the nonlinear stage solver. Units: `timeScale` passed to the solver [s] converts a
/// step d to a velocity, StepNorm(d) / timeScale [m/s].
struct NonlinearSolverParams {
  int maxIterations = 100;            ///< Newton iterations before status Stopped
  double absoluteTolerance = 1e-12;   ///< converged when ½ g^T H^-1 g (Newton decrement) <= this [J]
  double relativeTolerance = 1e-10;   ///< ... or when ‖g‖∞ <= relativeTolerance * ‖g_0‖∞ [-]
  double stepTolerance = 1e-9;        ///< ... or when StepNorm(d)/timeScale <= this [m/s]
  LineSearchKind lineSearch = LineSearchKind::Armijo;
  PsdProjection psdProjection = PsdProjection::Clamp;
  double armijoConstant = 1e-4;       ///< c in the Armijo condition
  double backtrackFactor = 0.5;       ///< α ← factor α on each rejected trial
  int maxLineSearchSteps = 40;        ///< trials before the stage is declared Diverged
  /// Line search by independent parts where the problem splits (optim/part_line_search.h): each
  /// part gets its own step length. False: one step length for all dofs.
  bool partLineSearch = true;
  /// The linear solves (optim/linear_solver.h); Auto: Krylov from 3000 unknowns up.
  LinearSolverSettings linear{LinearSolverKind::Auto};
};

/// The fields (optim/field_table.h), named as the scene file's settings.solver keys, in the
/// order of validation.
inline constexpr auto kNonlinearSolverFields = std::tuple_cat(
    std::make_tuple(
        MakeField("max_iterations", &NonlinearSolverParams::maxIterations, "",
                  AtLeast(1, 1000000), "Newton iterations before the stage is Stopped"),
        MakeField("absolute_tolerance", &NonlinearSolverParams::absoluteTolerance, "J",
                  NonNegativeRule(), "Converged when the Newton decrement ½ gᵀH⁻¹g is <= this"),
        MakeField("relative_tolerance", &NonlinearSolverParams::relativeTolerance, "-",
                  NonNegativeRule(),
                  "Converged also when the gradient's max norm is <= this times the first one's"),
        MakeField("step_tolerance", &NonlinearSolverParams::stepTolerance, "m/s",
                  NonNegativeRule(),
                  "Converged also when the step divided by the stage's time step is <= this"),
        MakeField("line_search", &NonlinearSolverParams::lineSearch, "", NoRule(),
                  "Armijo backtracking, or None: full Newton steps"),
        MakeField("psd_projection", &NonlinearSolverParams::psdProjection, "", NoRule(),
                  "How local Hessians are made positive semi-definite"),
        MakeField("armijo_constant", &NonlinearSolverParams::armijoConstant, "-", InOpen(0, 1),
                  "The constant c of the Armijo condition"),
        MakeField("backtrack_factor", &NonlinearSolverParams::backtrackFactor, "-", InOpen(0, 1),
                  "The step length's factor on each rejected trial"),
        MakeField("max_line_search_steps", &NonlinearSolverParams::maxLineSearchSteps, "",
                  AtLeast(1, 1000000), "Rejected trials before the stage is Diverged"),
        MakeField("part_line_search", &NonlinearSolverParams::partLineSearch, "", NoRule(),
                  "One step length per independent part of a stage (bodies no contact joins)")),
    LiftFields(&NonlinearSolverParams::linear, kLinearSolverFields));

/// The convergence test a solve passed, formatted only on demand (SolverStats::Message; why:
/// docs/optim-notes.md).
struct ConvergenceTest {
  const char* what = nullptr;  ///< null: no test passed
  double value = 0.0;
  const char* bound = "";
  double boundValue = 0.0;
  const char* note = "";  ///< appended, e.g. that the last step was not taken
};

/// "<what> = <value> <= <bound> = <boundValue><note>" (values with 6 significant digits;
/// formatted without streams); "<what><note>" for a test without a bound (bound empty).
std::string Format(const ConvergenceTest& test);

/// Statistics of one stage solve. Times are wall seconds.
struct SolverStats {
  StageStatus status = StageStatus::Stopped;
  int iterations = 0;
  int lineSearchSteps = 0;             ///< rejected line-search trials, summed over iterations
  int regularizations = 0;             ///< times the Hessian needed a diagonal shift
  int limitedSteps = 0;                ///< iterations that took the problem's shortened step
                                       ///< (StageProblem::TrustStep, LimitStep)
  double initialGradientNorm = 0.0;    ///< ‖g‖∞ at the first iterate
  double finalGradientNorm = 0.0;      ///< ‖g‖∞ at the last evaluated iterate
  double finalDecrement = 0.0;         ///< ½ g^T H^-1 g at the last iteration [J]
  double finalValue = 0.0;
  double assemblySeconds = 0.0;
  double factorizationSeconds = 0.0;
  double lineSearchSeconds = 0.0;
  int krylovIterations = 0;            ///< summed over the iterative linear solves
  int krylovFallbacks = 0;             ///< iterative solves that fell back to the direct solve
  std::string message;                 ///< why it stopped, in words (empty when `passed` says)
  ConvergenceTest passed;              ///< the convergence test that ended a Newton solve
  bool fallback = false;               ///< set by a caller that re-solved the stage another way
  bool closedForm = false;             ///< set by a caller that solved it without iterating
  /// Why it stopped: `message`, or the passed convergence test formatted.
  std::string Message() const { return message.empty() && passed.what ? Format(passed) : message; }
};

/// The vectors and matrices a Newton solve works in (MinimizeNewton, SolveResidualNewton), kept
/// by a caller that solves stage after stage so that none is allocated again once the sizes
/// settle. Carries nothing from one solve to the next.
struct NewtonWorkspace {
  Eigen::VectorXd gradient, direction, step, limited, trialGradient;
  Eigen::SparseMatrix<double> matrix, shifted, trialMatrix;
  std::vector<Eigen::Index> diagonal;
  DofBlockLayout layout;  ///< the problem's block layout (StageProblem::BlockLayout)
  LineSearch search;
  /// Newton iterations of the last solve on this workspace that converged in its main loop;
  /// -1 when the last solve ended otherwise (its Krylov forcing term's start: optim/forcing_term.h).
  int lastConvergedIterations = -1;
};

/// What a caller knows about a solve's start: a hint, not a setting (the iterates may change, the
/// convergence tests do not).
struct NewtonStart {
  /// Assemble the exact Hessian at the first iteration, as the adaptive projection does after a
  /// full step (step 1 above; projected again if it is not positive definite or gives no descent
  /// direction). For a start the caller expects in the local regime (docs/optim-notes.md).
  bool exactHessian = false;
};

/// Minimizes the problem from its current state. The problem is left at the last accepted iterate.
/// `timeScale` > 0 [s] scales the step test. Invalid `params` (see
/// Validate) or `timeScale` give Diverged with the reason, without touching the problem.
/// `iterations` counts the Newton directions computed: a quadratic takes 2 (the step, then the
/// iteration whose decrement test passes).
/// `solver` (may be null) is a linear solver kept across calls (its symbolic analysis survives
/// from stage to stage while the Hessian's pattern holds); `work` (may be null) its buffers;
/// `start` the caller's hint about the start.
SolverStats MinimizeNewton(StageProblem& problem, const NonlinearSolverParams& params,
                           double timeScale, SymmetricSolver* solver = nullptr,
                           NewtonWorkspace* work = nullptr, NewtonStart start = {});

/// The table of Validate (optim/field_table.h): its message names the first invalid field, e.g.
/// "max_iterations: must be >= 1, got 0".
constexpr const auto& FieldsOf(const NonlinearSolverParams&) { return kNonlinearSolverFields; }

/// The input checks every stage solver makes first: "" if valid, else "invalid parameters: ..."
/// or "invalid time scale: must be > 0, got ...".
std::string ValidateSolverInput(const NonlinearSolverParams& params, double timeScale);

}  // namespace superdex
