// The time stepper: one step of h [s] by the scene's integrator (core/dynamics/integrators.h) as
// a sequence of implicit stages — a variable-step BDF step, or the DIRK method's stages — over the
// actors' vector states (combined affinely; a kind on a manifold, as a rigid body, through its
// DIRK hooks). The host (the Scene) solves each stage with its stage policy and recorder, and
// builds the actors' stage data.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/dynamics/scene_stage.h"
#include "core/dynamics/step_report.h"
#include "core/dynamics/step_state.h"
#include "core/model/actor_kind.h"
#include "core/model/enums.h"

namespace superdex {

/// What a step needs from its host besides the states.
class StageHost {
 public:
  virtual ~StageHost() = default;
  /// The kind of actor a (the index of the vector states).
  virtual const ActorKind& KindOf(size_t a) const = 0;
  /// Writes the actors' prescribed dofs at time t [s] into x.
  virtual void ApplyConstraints(double t, std::vector<Eigen::VectorXd>* x) const = 0;
  /// The actors' data for a stage of step dt [s] at time t [s]: targets from the stage start,
  /// geometry from the last configuration; into *out (its storage reused).
  virtual void MakeStage(double dt, double t, const std::vector<VectorState>& start,
                         const std::vector<Eigen::VectorXd>& last, KindStage* out) const = 0;
  /// Solves one stage (its data in `stage`, from MakeStage) from *x, which then holds its
  /// solution; accounts it in *rep. `predictTime` > 0 (the stage's time after t_n [s]) allows
  /// the warm start.
  virtual void SolveStage(double dt, const KindStage& stage, std::vector<Eigen::VectorXd>* x,
                          double predictTime, StepReport* rep) = 0;
};

/// A variable-step BDF step of h [s] (the states of step.history) from step's states to the end
/// states in *work.
void StepBdf(const StepState& step, double h, IntegrationMethod method, StageHost& host,
             StepBuffers* buffers, StepWork* work);
/// The DIRK method's stages from step's states to the end states in *work.
void StepDirk(const StepState& step, double h, IntegrationMethod method, StageHost& host,
              StepBuffers* buffers, StepWork* work);
/// Ends a step of h [s]: the multistep history takes x_n, the states the end states of *work,
/// the time advances. work->next is left with storage only (its values are not kept).
void EndStep(double h, StepWork* work, StepState* step);

}  // namespace superdex
