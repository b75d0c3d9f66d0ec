// What a step did (StepReport) and the energies of a state (EnergyReport).
#pragma once

#include <cmath>
#include <string>

#include "core/contact/contact_pipeline.h"
#include "optim/newton_solver.h"

namespace superdex {

/// What one step did.
struct StepReport {
  double time = 0.0;           ///< simulated time at the end of the step [s]
  double dt = 0.0;             ///< [s]
  int stages = 0;
  int newtonIterations = 0;    ///< summed over stages
  int lineSearchSteps = 0;
  StageStatus status = StageStatus::Converged;  ///< worst over the stages
  std::string message;         ///< the solver's message for a non-converged stage
  int freeStages = 0;          ///< stages solved in closed form (no active contact sample;
                               ///< SceneSettings::closedFormFreeStages)
  int fallbacks = 0;           ///< stages re-solved with explicit normals after a failed
                               ///< residual solve (StageDriver)
  std::string fallbackMessage; ///< the first such stage's message
  double finalGradientNorm = 0.0;  ///< largest over the stages
  ContactStats contact;        ///< at the end of the step (penalty only)
  /// The stages' contact evaluations at their last iterates (with dissipation): largest
  /// ‖T_C‖/(μ λ̂_n) and most dissipative samples over the stages; the dissipation Δt_i Σ w R [J]
  /// summed over the stages.
  double maxCoulombRatio = 0.0;
  int dissipativeSamples = 0;
  double dissipation = 0.0;
  double wallSeconds = 0.0;
  double assemblySeconds = 0.0;       ///< stage solvers: energy/residual and derivative assembly
  double factorizationSeconds = 0.0;  ///< stage solvers: linear solves (Cholesky / LU)
  double lineSearchSeconds = 0.0;     ///< stage solvers: line-search evaluations
  int krylovIterations = 0;           ///< iterative linear solves (LinearSolverKind): iterations
  int krylovFallbacks = 0;            ///< iterative linear solves that fell back to the direct one
  double minDetF = INFINITY;          ///< smallest det F over the soft tets at the end of the step
                                      ///< (<= 0: an inverted tet); +∞ without soft actors
};

/// Energies of the current state [J].
struct EnergyReport {
  double kinetic = 0.0;
  double gravity = 0.0;  ///< Σ −m g·p
  double contact = 0.0;  ///< penalty energy Σ Π_{A,B}
  double elastic = 0.0;  ///< soft actors: Σ V Ψ(F)
  double Total() const { return kinetic + gravity + contact + elastic; }
};

}  // namespace superdex
