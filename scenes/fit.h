// Fitting scene parameters to an observed trajectory: Ceres between simulated and observed centres
// of mass,
//
//   minimize ½ Σ_k Σ_a ‖c_a(t_k; θ) − ĉ_a(t_k)‖²     [m²]
//
// over the parameters θ (names as in core/sensitivity/sensitivity.h, "ACTOR.NAME"), with c_a the simulated
// centre of mass of actor a at the observed times t_k (which must fall on the step grid). Two
// methods: Levenberg–Marquardt with the residuals' Jacobian from the forward sensitivities
// (core/sensitivity/sensitivity.h; its cost grows with each parameter by a replay of every step), or L-BFGS
// with the cost's gradient from one adjoint pass (core/sensitivity/adjoint.h; for many parameters).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/sensitivity/sensitivity.h"
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
  /// What the reader skipped, e.g. "<path>:<line>: the last line is truncated (no newline, not
  /// valid JSON): skipped" (the trajectory of a killed run).
  std::vector<std::string> notes;
};
/// Reads an observed trajectory; false with "<path>:<line>: <defect>" in *error. A last line
/// without its newline that is not valid JSON is skipped and noted.
bool ReadObservedTrajectory(const std::string& path, ObservedTrajectory* out, Error* error);

enum class FitMethod {
  /// Ceres Levenberg–Marquardt (dense QR) with the Jacobian of the residuals from forward
  /// sensitivities; gives standard errors. For a few parameters.
  LevenbergMarquardt,
  /// Ceres L-BFGS on the cost with its gradient from an adjoint pass, in log θ for the
  /// (positive) model parameters and in θ for initial states. For many parameters; no standard
  /// errors.
  Lbfgs,
};
EnumNames<FitMethod> NamesOf(FitMethod);  ///< "lm", "lbfgs"
inline bool ParseFitMethod(const std::string& name, FitMethod* method) {
  return Parse(name, method);
}

/// A fit's state after one solver iteration (FitOptions::iteration).
struct FitProgress {
  int iteration = 0;
  std::vector<double> values;  ///< θ
  double cost = 0.0;           ///< ½ Σ r² [m²]
};

struct FitOptions {
  std::vector<std::string> parameters;  ///< "ACTOR.NAME"
  std::optional<double> dt;             ///< overrides the scene's dt [s]
  int maxIterations = 50;
  FitMethod method = FitMethod::LevenbergMarquardt;
  /// Called after every solver iteration; returning false stops the fit there
  /// (FitResult::interrupted).
  std::function<bool(const FitProgress&)> iteration;
};

/// Why FitSceneParameters or ComputeTrajectoryGradient returned false.
enum class FitFailure {
  None,
  Input,       ///< bad parameters, observations or options (also beyond limits::kMaxFitSteps)
  Simulation,  ///< a stage did not converge
  NonFinite,   ///< the cost, residuals or gradient are not finite
};

struct FitResult {
  std::vector<std::string> names;
  std::vector<double> initial, fitted;
  /// One-sigma standard errors from the Gauss–Newton covariance σ² (JᵀJ)⁻¹ with
  /// σ² = 2 cost / (residuals − parameters) (meaningful for independent, equal observation noise).
  std::vector<double> standardError;  ///< NaN with FitMethod::Lbfgs
  double initialCost = 0.0, finalCost = 0.0;  ///< ½ Σ r² [m²]
  double rmsResidual = 0.0;                   ///< √(2 cost / residuals) [m]
  int residuals = 0;
  int iterations = 0;
  int simulations = 0;          ///< forward runs, with or without sensitivities
  double wallSeconds = 0.0;
  bool converged = false;
  bool interrupted = false;     ///< FitOptions::iteration asked to stop
  std::string message;          ///< Ceres' termination message
};

/// Fits the parameters of `file`'s scene (left unchanged) to `observed`. False with an error for
/// bad input (unknown parameter or actor, frames off the step grid, nothing observed) or when a
/// simulation fails (a stage that does not converge).
bool FitSceneParameters(const SceneFile& file, const ObservedTrajectory& observed,
                        const FitOptions& options, FitResult* result, Error* error,
                        FitFailure* failure = nullptr);

/// The cost and its gradient at the scene file's parameter values, by one simulation and one
/// adjoint pass (options.method and maxIterations are not used).
struct TrajectoryGradient {
  std::vector<std::string> names;
  std::vector<double> values;    ///< θ
  double cost = 0.0;             ///< ½ Σ r² [m²]
  std::vector<double> gradient;  ///< d cost / dθ [m² per unit of θ]
  int residuals = 0;
  int steps = 0;
  double simulationSeconds = 0.0;  ///< the simulation with its checkpoints
  double gradientSeconds = 0.0;    ///< the adjoint pass
  int colors = 0;                  ///< most colours of a step's linearization
  double runsPerStep = 0.0;        ///< residual runs per step in the adjoint pass
};
bool ComputeTrajectoryGradient(const SceneFile& file, const ObservedTrajectory& observed,
                               const FitOptions& options, TrajectoryGradient* result,
                               Error* error, FitFailure* failure = nullptr);

/// Writes a fit's values as JSON to `path` (through a temporary file renamed into place, so the
/// file is always complete): {"parameters": {NAME: {"initial", "fitted", "standard_error"}},
/// "final_cost", "rms_residual", "iterations", "converged", "status"}. False with the system's
/// reason in *error when the file cannot be written.
bool WriteFitJson(const std::string& path, const FitResult& result, const std::string& status,
                  Error* error);

/// Sets values[j] of the parameters `names` (ACTOR.NAME) on `scene` (SetParameterValue); false
/// with the parameter and the rule on a bad name or value.
bool ApplyParameterValues(Scene* scene, const std::vector<std::string>& names,
                          const std::vector<double>& values, Error* error);
/// Writes the scene file `path`: the fitted scene, `file` with the fit's values (WriteSceneFile;
/// its run settings, output and description kept).
bool WriteFittedScene(const SceneFile& file, const FitResult& result, const std::string& path,
                      Error* error);

}  // namespace superdex
