// What a step advances (the actors' states, the multistep history and the time) and the step's
// working storage.
#pragma once

#include <vector>

#include "core/contact/dissipation_setup.h"
#include "core/dynamics/scene_stage.h"
#include "core/dynamics/step_report.h"
#include "core/model/actor_kind.h"
#include "core/model/rigid_body.h"
#include "core/model/vector_state.h"

namespace superdex {

/// The actors' vector states (vectorStates, in creation order), the multistep history
/// (vectorHistory[j]: the states at step n−1−j, at time historyTimes[j] [s]; at most 2) and the
/// time t_n [s]. In the scene `rigidStates` and `rigidHistory` are empty (rigid actors are
/// kinds); a snapshot (Scene::Save) carries the rigid actors' states there, and the others'
/// in vectorStates, in the checkpoint layout.
struct StepState {
  std::vector<RigidBodyState> rigidStates;
  std::vector<VectorState> vectorStates;
  std::vector<std::vector<RigidBodyState>> rigidHistory;
  std::vector<std::vector<VectorState>> vectorHistory;
  std::vector<double> historyTimes;
  double time = 0.0;
};

/// The step under way's working data: the actors' configurations (the stages' iterate), their
/// x_n, their end states, and the step's report.
struct StepWork {
  std::vector<Eigen::VectorXd>& x;
  const std::vector<Eigen::VectorXd>& stepStart;
  std::vector<VectorState>& next;
  StepReport report;
};

/// The last stage's dissipation data, kept so that the contact forces at the state it produced
/// can be reported with their dissipation (Scene::ContactSamples); `valid` until the state changes
/// otherwise.
struct ReportStage {
  bool valid = false;
  double dt = 0.0;  ///< Δt_i [s]
  DissipationMode mode = DissipationMode::ReconstructedLoad;  ///< as solved (a fallback's too)
  bool fadeFriction = true;
  std::vector<Eigen::VectorXd> q0, qLast;  ///< the actors' x⁰ and x_n
};

/// Storage of a scene's steps kept from step to step, so that a rigid step does not allocate once
/// it has run (scratch: every use overwrites it first).
struct StepBuffers {
  std::vector<double> bdfTimes, bdfWeights;
  std::vector<std::vector<KindSlope>> vectorSlopes;  ///< a DIRK step's slopes per vector state
  std::vector<double> stageWeights;                  ///< a DIRK step's h b_i
  // The actors' iterate, step start, next state, stage start and last configuration, and the
  // stage data built from them.
  std::vector<Eigen::VectorXd> x, stepStart, last, end;
  std::vector<VectorState> next, start;
  KindStage stage;
  ReportStage reportStage;                           ///< the last stage solved
};

}  // namespace superdex
