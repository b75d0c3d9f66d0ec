// Warm start of a stage solve from the motion's own prediction.
//
// The cold start of a stage is the last configuration (x_n, or the previous stage's solution).
// The predicted start continues the step-start motion with the last step's mean acceleration:
//   p = p_n + τ v_n + ½ τ² a,          a = (v_n − v_{n−1}) / h_{n−1}            [m]
//   R = Exp(τ ω_n + ½ τ² α) R_n,       α = (ω_n − ω_{n−1}) / h_{n−1}            [rad]
// with τ the stage's time after t_n [s] (a BDF stage: h; a DIRK stage: c_i h), a = α = 0 without
// history. It is exact for constant acceleration (a sliding box, free flight), where the cold
// start is a whole step's motion away. Each body's predicted move is shortened by the stage
// problem's contact step limit (no sample's depth more than doubles, StageProblem::LimitStep),
// and the stage starts there only if it is better by the solver's own measure: a lower
// incremental potential Φ for potential stages, a lower ½‖r‖² for the residual modes. Soft nodes
// keep their cold start. The solution is the stage's root either way; only the path changes.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/rigid_body.h"
#include "core/rigid_contact.h"
#include "optim/stage_problem.h"

namespace superdex {

/// The predicted poses of the rigid bodies τ [s] after t_n (static bodies keep their pose).
/// `previous` is the state at t_{n−1} = t_n − hPrevious (null, or hPrevious <= 0: no history).
std::vector<RigidPose> PredictPoses(const std::vector<RigidBodyModel>& models,
                                    const std::vector<RigidBodyState>& current,
                                    const std::vector<RigidBodyState>* previous, double hPrevious,
                                    double tau);

/// The tangent step d with from ⊕ d = to for the rigid blocks of a stage problem (dofOffset[i] < 0:
/// not a degree of freedom); soft blocks and the rest of d are zero. d has numDofs entries.
Eigen::VectorXd TangentStep(const std::vector<int>& dofOffset, int numDofs,
                            const std::vector<RigidPose>& from, const std::vector<RigidPose>& to);

/// What WarmStart did.
struct WarmStartResult {
  bool moved = false;         ///< the problem now starts at the (limited) predicted start
  double coldNorm = 0.0;      ///< ‖g‖∞ (potential) or ‖r‖∞ (residual) at the cold start: the
                              ///< relative test's scale for the solve that follows
};

/// Moves `problem` from its current (cold) state by the step d (shortened by LimitStep) if that
/// lowers the solver's merit: Φ for a potential problem, ½‖r‖² otherwise. Costs one gradient (or
/// residual) evaluation at the cold start and one value (or residual) evaluation at the trial.
WarmStartResult WarmStart(StageProblem& problem, Eigen::VectorXd d, PsdProjection projection);

}  // namespace superdex
