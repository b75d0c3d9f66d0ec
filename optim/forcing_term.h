// Forcing terms of an inexact Newton method: how accurately each Newton iteration's Krylov solve
// needs to be carried out (optim/newton_solver.cpp, optim/residual_newton.cpp).
//
// Iteration k solves J d = −F only to ‖J d + F‖₂ <= η_k ‖F‖₂, F the gradient (minimization) or
// the residual, with Eisenstat and Walker's choice 2 (S. C. Eisenstat, H. F. Walker, "Choosing the
// forcing terms in an inexact Newton method", SIAM J. Sci. Comput. 17 (1996) 16–32):
//   η_k = max(floor, min(η_max, γ (‖F_k‖ / ‖F_{k−1}‖)²)),   γ = 0.9,   η_max = 0.1,
// `floor` the user's linear_tolerance. (Their safeguard η_k >= γ η_{k−1}², applied where
// γ η_{k−1}² > 0.1, never applies with η_max = 0.1.) The first iteration has no ratio: η_0 = η_max,
// or η_0 = floor where the caller expects a stage close to linear from its start (the last solve
// converged within kTightStartIterations Newton iterations), since there an inexact first step
// costs one more assembly than its Krylov iterations save. Far from the solution a
// loose solve gives as good a step as an exact one; where Newton converges quadratically the ratio
// ‖F_k‖/‖F_{k−1}‖ collapses and η_k falls to the floor, so the last iterations are solved as
// accurately as before. A direction solved this loosely is still a descent direction: conjugate
// gradients from x = 0 give one for any iteration count (SPD preconditioner), and η < 1 gives
// F·J d <= −(1 − η)‖F‖² for the residual's merit ½‖F‖².
//
// See docs/solver.md; measurements behind η_max, η_0 and kTightStartIterations:
// docs/optim-notes.md.
#pragma once

namespace superdex {

class ForcingTerm {
 public:
  static constexpr double kGamma = 0.9;
  static constexpr double kEtaMax = 0.1;
  static constexpr int kTightStartIterations = 4;
  /// `floor`: the smallest η returned (the linear solver's own tolerance). `lastIterations`: the
  /// Newton iterations of the last solve of the same kind of stage that converged (negative:
  /// none), which decide η_0.
  ForcingTerm(double floor, int lastIterations)
      : floor_(floor),
        tightStart_(lastIterations >= 0 && lastIterations <= kTightStartIterations) {}
  /// η_k for this iteration's ‖F_k‖₂ (call once per Newton iteration, in order).
  double Next(double norm);

 private:
  double floor_;
  bool tightStart_;
  double lastNorm_ = -1.0;  // ‖F_{k−1}‖; negative before the first iteration
};

}  // namespace superdex
