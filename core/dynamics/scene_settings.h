// A scene's stepping settings: gravity, integrator, the stage solver and its parameters, the
// dissipation evaluation (ExperimentalEvalParams), and the stage policy's switches.
#pragma once

#include <Eigen/Core>
#include <string>

#include "core/model/enums.h"
#include "core/model/eval_params.h"
#include "optim/newton_solver.h"

namespace superdex {

/// Which solver runs each implicit stage. Newton is the production solver (projected Newton for
/// potential stages, residual Newton otherwise); Ipopt (potential stages only) and Ceres (every
/// stage) are independent checks for small scenes (dense, at most 600 degrees of freedom).
enum class StageSolverKind { Newton, Ipopt, Ceres };
EnumNames<StageSolverKind> NamesOf(StageSolverKind);  ///< "newton", "ipopt", "ceres"
/// A name of NamesOf(StageSolverKind), or one with its first letter capitalized ("Newton");
/// false for anything else. Every reader parses the stage solver with it (optim/field_table.h).
bool ParseName(const std::string& name, StageSolverKind* kind);

struct SceneSettings {
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81);  ///< [m/s²]
  IntegrationMethod integrator = IntegrationMethod::BDF2;
  NonlinearSolverParams solver;
  StageSolverKind stageSolver = StageSolverKind::Newton;
  ExperimentalEvalParams eval;
  /// Newton stage solves of rigid bodies start from the motion's prediction (the last step's
  /// acceleration continued, each body's move limited by the contact step limit;
  /// core/dynamics/warm_start.h). Changes the path to each stage's solution, not the solution or
  /// the convergence tests.
  bool warmStart = true;
  /// A Newton stage of rigid bodies whose contact terms all vanish at the minimizer of inertia and
  /// gravity (no contact sample active there, penalty or dissipation) is solved in closed form,
  /// per body (MinimizeRigidInertia, energies/rigid_inertia.h), with 0 Newton iterations: free
  /// flight pays no Newton iteration. That point is the stage's exact global minimizer (the
  /// contact energies are >= 0 and vanish there) and the root of the residual modes' equations
  /// (their contact terms vanish there too); Newton reaches the same point to its tolerance.
  /// Not for scenes with soft actors, nor for the Ipopt and Ceres checks, nor for recorded steps.
  bool closedFormFreeStages = true;
};

/// The fields (optim/field_table.h), named as the scene file's `settings` keys, in the order of
/// validation.
inline constexpr auto kSceneSettingsFields = std::make_tuple(
    MakeField("gravity", &SceneSettings::gravity, "m/s²", FiniteRule(),
              "Gravitational acceleration g"),
    MakeField("integrator", &SceneSettings::integrator, "", NoRule(), "The time integrator"),
    MakeNested("solver", &SceneSettings::solver, "NonlinearSolverParams", kNonlinearSolverFields,
               "The stage solver's settings"),
    MakeField("stage_solver", &SceneSettings::stageSolver, "", NoRule(),
              "Which solver runs each implicit stage (also capitalized: Newton, Ipopt, Ceres)"),
    MakeNested("experimental_eval_params", &SceneSettings::eval, "ExperimentalEvalParams",
               kExperimentalEvalFields, "Time levels of the dissipative terms"),
    MakeField("warm_start", &SceneSettings::warmStart, "", NoRule(),
              "Newton stage solves of rigid bodies start from the motion's prediction (the "
              "last step's acceleration continued)"),
    MakeField("closed_form_free_stages", &SceneSettings::closedFormFreeStages, "", NoRule(),
              "A Newton stage with no contact sample active at the minimizer of inertia and "
              "gravity is solved in closed form (0 Newton iterations)"));

/// The table of Validate (optim/field_table.h); a nested row's message follows
/// "<prefix><field>.".
constexpr const auto& FieldsOf(const SceneSettings&) { return kSceneSettingsFields; }

/// The dissipation mode the settings select (ExperimentalEvalParams' supported combinations).
DissipationMode ModeOf(const ExperimentalEvalParams& eval);

}  // namespace superdex
