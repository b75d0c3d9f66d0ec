// Warm start of a stage solve from the motion's own prediction.
//
// The cold start of a stage is the last configuration (x_n, or the previous stage's solution).
// The predicted start continues each kind's step-start motion with the last step's mean
// acceleration, the position through the stage's own slope (ActorKind::PredictStage; a rigid
// actor: PredictRigidPose, core/model/rigid_kind.h):
//   p = p⁰ + Δt_i (v_n + τ a),         a = (v_n − v_{n−1}) / h_{n−1}            [m]
//   R = Exp(τ ω_n + ½ τ² α) R_n,       α = (ω_n − ω_{n−1}) / h_{n−1}            [rad]
// with τ the stage's time after t_n [s] (a BDF stage: h; a DIRK stage: c_i h), p⁰ and Δt_i the
// stage's start and step, a = α = 0 without history. The position is exact for constant
// acceleration (a sliding box, free flight) in every integrator, where the cold start is a whole
// step's motion away. Where contact is about to change (an impact), each unit's predicted move
// is shortened by the stage problem's contact step limit, as Newton's own steps are; where the
// forces on a unit changed over the last two steps (an impact: ActorKind::ForceChange), the
// prediction extrapolates them and its move is first bounded by the trust region of a Newton
// correction (a quarter of a rigid body's radius, core/dynamics/scene_stage.h). Soft nodes keep
// their cold start. The solution is the stage's root either way; only the path to it changes.
//
// A merit safeguard (start there only if Φ, or ½‖r‖², is lower than at the cold start) gave the
// same Newton iterations on every shipped scene and cost two gradient sweeps per stage; it is
// not used (docs/solver.md).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "optim/stage_problem.h"

namespace superdex {

/// Moves `problem` from its current (cold) state by the predicted step d, shortened blockwise by
/// the problem's step limit (StageProblem::LimitStep: no contact sample's depth more than doubles).
/// A step with StepNorm(d) <= negligibleStep [m] (e.g. step_tolerance × Δt: a body at rest) is not
/// taken. Returns whether the problem moved. Costs one step-limit sweep, no evaluation.
bool WarmStart(StageProblem& problem, Eigen::VectorXd d, double negligibleStep = 0.0);
/// As above, shortening *step in place.
bool WarmStart(StageProblem& problem, Eigen::VectorXd* step, double negligibleStep = 0.0);

/// A unit (a kind's actor) moved steadily over the last two steps when the force on it changed by
/// at most SteadyBound (ActorKind::ForceChange; a rigid actor: RigidForceChange,
/// core/model/rigid_kind.h). Such a unit's prediction (constant acceleration) is its exact motion
/// — free flight, torque-free tumbling, steady sliding, rest — until its contacts change.
constexpr double kSteadyAcceleration = 0.01;  ///< fraction of |g| [-]
constexpr double kSteadyFloor = 1e-6;         ///< round-off floor, for scenes without gravity [m/s²]
/// The largest change kSteadyAcceleration |g| + kSteadyFloor [m/s²] of a steady motion.
inline double SteadyBound(const Eigen::Vector3d& gravity) {
  return kSteadyAcceleration * gravity.norm() + kSteadyFloor;
}

/// As above for a stage of units: unit k owns the stage dofs unitDofs[k] (−1: prescribed). The
/// predicted move of a unit whose motion was not steady over the last two steps (steady[k] = 0:
/// an impact, a contact made or broken) extrapolates forces that just changed: it is first
/// bounded by the trust region of a Newton correction (StageProblem::TrustStep), then every move
/// by the step limit. A steady unit's prediction is only limited. `scratch` is working memory (no
/// allocation once it has the capacity). Costs one step-limit sweep, no evaluation.
///
/// Measured (mean Newton iterations per step, without → with the bound, Δt = 2e-2 unless named):
/// the 160-sphere column (0.5 s) 46.0 → 24.7 with explicit normals, 61.5 → 42.2 in the default
/// mode; the 1000-sphere pile with explicit normals 25.3 → 22.0 (0.6 s), 10.07 → 9.67 (0.3 s at
/// Δt = 1e-2); default mode 12.00 → 11.77 (0.3 s at 1e-2), 39.0 → 45.8 at 2e-2 (0.6 s: 8 → 13
/// stages re-solved with explicit normals; that mode's landing stages at 2e-2 fail erratically).
/// Bounding only the bodies not in free flight also cut the sliding incline's exact prediction
/// (BDF2 at Δt = 0.1: 2.55 → 3.35 Newton iterations per step); bounding every body's prediction
/// also cut free flight (the drop at Δt = 1e-2 under BDF2: 1.35 → 1.68); the bound after the
/// step limit instead of before it did worse on the pile (10.10 and 23.10 with explicit normals).
bool WarmStart(StageProblem& problem, Eigen::VectorXd* step, Eigen::VectorXd* scratch,
               double negligibleStep, const std::vector<std::vector<int>>& unitDofs,
               const std::vector<char>& steady);

}  // namespace superdex
