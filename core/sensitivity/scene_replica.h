// A copy of a scene for one thread of a derivative computation (core/sensitivity/sensitivity.h,
// core/sensitivity/step_linearization.h), with its own tape: the recorded stage solutions, and for the
// Replay mode its own LU factors of the recorded stage Jacobians (a solve writes into its
// factorization's status, so threads cannot share one).
#pragma once

#include <memory>

#include "core/scene.h"
#include "core/sensitivity/stage_tape.h"

namespace superdex {

struct SceneReplica {
  SceneReplica(const Scene& original, const StepTape& recorded, bool factor) : scene(original) {
    Refresh(recorded, factor);
  }
  /// Takes the stage solutions (and factors) of a newly recorded step.
  void Refresh(const StepTape& recorded, bool factor) {
    if (static_cast<int>(tape.stages.size()) < recorded.used) tape.stages.resize(recorded.used);
    tape.used = recorded.used;
    for (int s = 0; s < recorded.used; ++s) {
      const StageTapeEntry& from = recorded.stages[s];
      StageTapeEntry& to = tape.stages[s];
      to.x = from.x;
      to.mode = from.mode;
      to.slips = from.slips;
      to.factored = factor && from.factored && to.lu->Factorize(from.jacobian);
    }
  }
  Scene scene;
  StepTape tape;
  Error error;
};

}  // namespace superdex
