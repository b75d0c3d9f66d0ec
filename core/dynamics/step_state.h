// What a step advances: the actors' states, the multistep history and the time.
#pragma once

#include <vector>

#include "core/model/rigid_body.h"
#include "core/model/soft_body.h"

namespace superdex {

/// The rigid and soft actors' states (in the order of their kinds' arrays), the multistep
/// history (history[j]: the states at step n−1−j, at time historyTimes[j] [s]; at most 2) and
/// the time t_n [s].
struct StepState {
  std::vector<RigidBodyState> states;
  std::vector<SoftBodyState> softStates;
  std::vector<std::vector<RigidBodyState>> history;
  std::vector<std::vector<SoftBodyState>> softHistory;
  std::vector<double> historyTimes;
  double time = 0.0;
};

}  // namespace superdex
