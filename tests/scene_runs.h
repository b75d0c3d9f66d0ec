// Running scenes in the physics tests.
#pragma once

#include <catch2/catch.hpp>
#include <cmath>

#include "core/scene.h"

namespace superdex::test {

/// Steps the scene for `duration` [s] at dt [s]; every step must succeed and every stage converge.
inline void Run(Scene* scene, double duration, double dt) {
  Error e;
  const int steps = static_cast<int>(std::lround(duration / dt));
  for (int i = 0; i < steps; ++i) {
    StepReport r;
    REQUIRE(scene->Step(dt, &r, &e));
    REQUIRE(r.status == StageStatus::Converged);
  }
}

}  // namespace superdex::test
