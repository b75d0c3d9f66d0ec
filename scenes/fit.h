// Fitting scene parameters to an observed trajectory: Ceres least squares between simulated and
// observed centres of mass, with the Jacobian from the forward sensitivities (core/sensitivity.h).
//
//   minimize ½ Σ_k Σ_a ‖c_a(t_k; θ) − ĉ_a(t_k)‖²     [m²]
//
// over the parameters θ (names as in core/sensitivity.h, "ACTOR.NAME"), with c_a the simulated
// centre of mass of actor a at the observed times t_k (which must fall on the step grid).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/sensitivity.h"
#include "scenes/scene_file.h"

namespace superdex {

/// Observed centres of mass: the trajectory format (README "Trajectory format": a header line
/// naming the actors, then frames {"t": …, "actors": [{"p": [x, y, z]}, …]}); an actor entry that
/// is null or has no "p" is not observed in that frame.
struct ObservedFrame {
  double time = 0.0;                            ///< [s]
  std::vector<std::optional<Eigen::Vector3d>> position;  ///< per actor of the header [m]
};
struct ObservedTrajectory {
  std::vector<std::string> actors;  ///< names from the header
  std::vector<ObservedFrame> frames;
};
bool ReadObservedTrajectory(const std::string& path, ObservedTrajectory* out, Error* error);

struct FitOptions {
  std::vector<std::string> parameters;  ///< "ACTOR.NAME"
  std::optional<double> dt;             ///< overrides the scene's dt [s]
  int maxIterations = 50;
};

struct FitResult {
  std::vector<std::string> names;
  std::vector<double> initial, fitted;
  /// One-sigma standard errors from the Gauss–Newton covariance σ² (JᵀJ)⁻¹ with
  /// σ² = 2 cost / (residuals − parameters) (meaningful for independent, equal observation noise).
  std::vector<double> standardError;
  double initialCost = 0.0, finalCost = 0.0;  ///< ½ Σ r² [m²]
  double rmsResidual = 0.0;                   ///< √(2 cost / residuals) [m]
  int residuals = 0;
  int iterations = 0;
  int simulations = 0;          ///< forward runs, with or without sensitivities
  double wallSeconds = 0.0;
  bool converged = false;
  std::string message;          ///< Ceres' termination message
};

/// Fits the parameters of `file`'s scene (left unchanged) to `observed`. False with an error for
/// bad input (unknown parameter or actor, frames off the step grid, nothing observed) or when a
/// simulation fails (a stage that does not converge).
bool FitSceneParameters(const SceneFile& file, const ObservedTrajectory& observed,
                        const FitOptions& options, FitResult* result, Error* error);

}  // namespace superdex
