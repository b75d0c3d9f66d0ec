// A stage's recording policy. A plain step passes none; core/sensitivity's tapes record every
// accepted stage (its solution, dissipation mode and Jacobian there) or supply each stage's
// solution in place of a solve (replay, inject). The stage driver asks the policy it is given; it
// knows nothing of what the policy keeps.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/dynamics/scene_stage.h"

namespace superdex {

class StageRecorder {
 public:
  virtual ~StageRecorder() = default;
  /// Called when a step begins.
  virtual void BeginStep() = 0;
  /// Whether the stages' solutions come from this policy (Supply) instead of a solve. Such a step
  /// updates the state only (no contact report).
  virtual bool Supplies() const = 0;
  /// In place of a solve: sets the stage's solution (the vector states) in *x. `inputs`
  /// builds the stage's problem at any configuration.
  virtual void Supply(const StageInputs& inputs, const StageDissipation& dissipation,
                      std::vector<Eigen::VectorXd>* x) = 0;
  /// After a stage was solved: its accepted solution, in the dissipation setting it was solved in.
  virtual void Record(const StageInputs& inputs, const StageDissipation& dissipation,
                      const std::vector<Eigen::VectorXd>& x) = 0;
  /// Whether stages are recorded (the driver then keeps them cold: no warm start, no closed form).
  virtual bool Records() const = 0;
};

}  // namespace superdex
