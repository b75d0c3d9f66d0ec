// Warm start of a stage solve from the motion's own prediction.
//
// The cold start of a stage is the last configuration (x_n, or the previous stage's solution).
// The predicted start continues the step-start motion with the last step's mean acceleration,
// the position through the stage's own slope (PredictStagePoses):
//   p = p⁰ + Δt_i (v_n + τ a),         a = (v_n − v_{n−1}) / h_{n−1}            [m]
//   R = Exp(τ ω_n + ½ τ² α) R_n,       α = (ω_n − ω_{n−1}) / h_{n−1}            [rad]
// with τ the stage's time after t_n [s] (a BDF stage: h; a DIRK stage: c_i h), p⁰ and Δt_i the
// stage's start and step, a = α = 0 without history. The position is exact for constant
// acceleration (a sliding box, free flight) in every integrator, where the cold start is a whole
// step's motion away. Where contact is about to change (an impact), each body's
// predicted move is shortened by the stage problem's contact step limit, as Newton's own steps
// are; where the forces on a body changed over the last two steps (an impact: SteadyMotion), the
// prediction extrapolates them and its move is first bounded by the trust region of a Newton
// correction (a quarter of the body's radius, core/dynamics/scene_stage.h). Soft nodes keep their cold start. The solution is the stage's root either way; only the
// path to it changes.
//
// Measured against a merit safeguard (start there only if Φ, or ½‖r‖² for the residual modes, is
// lower than at the cold start, relative test scaled by the cold start's gradient): the same
// Newton iterations on every shipped scene and the 300-sphere pile, but its two extra gradient
// sweeps per stage cost 6 % more instructions on the settling 10-box stack than the cold start;
// without it the warm start costs 7 % fewer (callgrind, Δt = 1e-2).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/model/rigid_body.h"
#include "core/model/rigid_body.h"
#include "optim/stage_problem.h"

namespace superdex {

/// The predicted poses of the rigid bodies τ [s] after t_n (static bodies keep their pose).
/// `previous` is the state at t_{n−1} = t_n − hPrevious (null, or hPrevious <= 0: no history).
std::vector<RigidPose> PredictPoses(const std::vector<RigidBodyModel>& models,
                                    const std::vector<RigidBodyState>& current,
                                    const std::vector<RigidBodyState>* previous, double hPrevious,
                                    double tau);

/// The predicted solution of an implicit stage, its position consistent with the integrator. A
/// stage solves for p with the position slope V = (p − p⁰)/Δt_i (p⁰: the stage's start,
/// `stageStart` — for a BDF step an affine combination of past states, for a DIRK stage the step
/// start plus the earlier stages' slopes). The motion predicts that slope, not the position:
///   p = p⁰ + Δt_i (v_n + τ a),   R = PredictPoses' R,   a as in PredictPoses.
/// Exact for constant acceleration at every stage of every method: Backward Euler's
/// p_{n+1} = p_n + h v_{n+1}, BDF2 while its start-up transient decays (positions are then not a
/// quadratic in t, velocities stay linear), and DIRK stages of stage order below 2
/// (Σ_j a_ij c_j ≠ c_i²/2), where PredictPoses' position is off by O(h² a). Measured on the
/// 0.6 s drop (free flight but for one bounce, Δt = 1e-3, Newton iterations per step, before →
/// after): BackwardEuler 2.02 → 1.04, SymplecticDIRK12 2.02 → 1.03, SymplecticDIRK22 4.01 → 2.04,
/// DIRK22 3.03 → 2.04, DIRK33 5.04 → 3.07; the incline, stack, pyramid and 75-sphere pile within
/// ±4 %. The same rule for the rotation (the polar factor of R⁰ + Δt_i [ω]× R̃) made the tumbling
/// body's Backward Euler stages take 3.6 iterations instead of 2 and is not used.
std::vector<RigidPose> PredictStagePoses(const std::vector<RigidBodyModel>& models,
                                         const std::vector<RigidBodyState>& current,
                                         const std::vector<RigidBodyState>* previous,
                                         double hPrevious, double tau,
                                         const std::vector<RigidBodyState>& stageStart,
                                         double stageDt);
/// As above, into *poses (resized; no allocation once it has the capacity).
void PredictStagePoses(const std::vector<RigidBodyModel>& models,
                       const std::vector<RigidBodyState>& current,
                       const std::vector<RigidBodyState>* previous, double hPrevious, double tau,
                       const std::vector<RigidBodyState>& stageStart, double stageDt,
                       std::vector<RigidPose>* poses);

/// The tangent step d with from ⊕ d = to for the rigid blocks of a stage problem (dofOffset[i] < 0:
/// not a degree of freedom); soft blocks and the rest of d are zero. d has numDofs entries.
Eigen::VectorXd TangentStep(const std::vector<int>& dofOffset, int numDofs,
                            const std::vector<RigidPose>& from, const std::vector<RigidPose>& to);
/// As above, into *step.
void TangentStep(const std::vector<int>& dofOffset, int numDofs,
                 const std::vector<RigidPose>& from, const std::vector<RigidPose>& to,
                 Eigen::VectorXd* step);

/// Moves `problem` from its current (cold) state by the predicted step d, shortened blockwise by
/// the problem's step limit (StageProblem::LimitStep: no contact sample's depth more than doubles).
/// A step with StepNorm(d) <= negligibleStep [m] (e.g. step_tolerance × Δt: a body at rest) is not
/// taken. Returns whether the problem moved. Costs one step-limit sweep, no evaluation.
bool WarmStart(StageProblem& problem, Eigen::VectorXd d, double negligibleStep = 0.0);
/// As above, shortening *step in place.
bool WarmStart(StageProblem& problem, Eigen::VectorXd* step, double negligibleStep = 0.0);

/// Which bodies moved steadily over the last two steps (states `before`, `previous`, `current`,
/// hBefore and hPrevious seconds apart): the force and the torque on them changed by at most
///   |a_n − a_{n−1}| + |τ_n − τ_{n−1}| / (m ρ) <= kSteadyAcceleration |g| + kSteadyFloor   [m/s²]
/// with a_n = (v_n − v_{n−1})/h_{n−1}, τ_n = (L_n − L_{n−1})/h_{n−1}, L = I_w ω the world angular
/// momentum [kg·m²/s] and ρ the RMS radius √(tr J/m) [m] (a torque as the acceleration it gives the
/// body's points at ρ). Such a body's prediction (constant acceleration) is its exact motion — free
/// flight, torque-free tumbling, steady sliding, rest — until its contacts change. Static bodies,
/// and every body without two steps of history (either pointer null or a step <= 0), count as
/// steady. `steady` is resized to the bodies.
void SteadyMotion(const std::vector<RigidBodyModel>& models,
                  const std::vector<RigidBodyState>& current,
                  const std::vector<RigidBodyState>* previous, double hPrevious,
                  const std::vector<RigidBodyState>* before, double hBefore,
                  const Eigen::Vector3d& gravity, std::vector<char>* steady);
constexpr double kSteadyAcceleration = 0.01;  ///< fraction of |g| [-]
constexpr double kSteadyFloor = 1e-6;         ///< round-off floor, for scenes without gravity [m/s²]
/// The largest change kSteadyAcceleration |g| + kSteadyFloor [m/s²] of a steady motion.
inline double SteadyBound(const Eigen::Vector3d& gravity) {
  return kSteadyAcceleration * gravity.norm() + kSteadyFloor;
}

/// As above for a stage whose rigid bodies own the 6-dof blocks at dofOffset (< 0: none). The
/// predicted move of a body whose motion was not steady over the last two steps (`steady`, see
/// SteadyMotion: an impact, a contact made or broken) extrapolates forces that just changed: it
/// is first bounded by the trust region of a Newton correction (StageProblem::TrustStep), then
/// every move by the step limit. A steady body's prediction is only limited. `scratch` is working memory (no
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
/// The kinds of the generic layer are units as the bodies are: kind k's stage dofs are
/// (*kindDofs)[k] (−1: prescribed) and (*kindSteady)[k] says whether it moved steadily
/// (ActorKind::ForceChange); both may be null (no kinds).
bool WarmStart(StageProblem& problem, const std::vector<int>& dofOffset,
               const std::vector<char>& steady, Eigen::VectorXd* step,
               Eigen::VectorXd* scratch, double negligibleStep,
               const std::vector<std::vector<int>>* kindDofs = nullptr,
               const std::vector<char>* kindSteady = nullptr);

}  // namespace superdex
