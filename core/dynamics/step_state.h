// What a step advances (the actors' states, the multistep history and the time) and the step's
// working storage.
#pragma once

#include <vector>

#include "core/contact/dissipation_setup.h"
#include "core/dynamics/scene_stage.h"
#include "core/dynamics/step_report.h"
#include "core/model/actor_kind.h"
#include "core/model/rigid_body.h"
#include "core/model/soft_body.h"

namespace superdex {

/// The actors' vector states (softStates: soft actors, then the kinds'), the multistep history
/// (softHistory[j]: the states at step n−1−j, at time historyTimes[j] [s]; at most 2) and the
/// time t_n [s]. In the scene `states` and `history` are empty (rigid actors are kinds); a
/// snapshot (Scene::Save) carries the rigid actors' states there, in the checkpoint layout.
struct StepState {
  std::vector<RigidBodyState> states;
  std::vector<SoftBodyState> softStates;
  std::vector<std::vector<RigidBodyState>> history;
  std::vector<std::vector<SoftBodyState>> softHistory;
  std::vector<double> historyTimes;
  double time = 0.0;
};

/// The step under way's working data: the vector states' positions (soft actors, then kinds; the
/// stages' iterate), their x_n, their end state, and the step's report.
struct StepWork {
  std::vector<Eigen::VectorXd>& softX;
  const std::vector<Eigen::VectorXd>& softStepStart;
  std::vector<SoftBodyState>& softNext;
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
  std::vector<Eigen::VectorXd> x0, xLast, q0, qLast;  ///< soft actors', kinds' x⁰ and x_n
};

/// Storage of a scene's steps kept from step to step, so that a rigid step does not allocate once
/// it has run (scratch: every use overwrites it first).
struct StepBuffers {
  std::vector<double> bdfTimes, bdfWeights;
  std::vector<std::vector<KindSlope>> vectorSlopes;  ///< a DIRK step's slopes per vector state
  std::vector<double> stageWeights;                  ///< a DIRK step's h b_i
  // The vector states' (soft actors', then the kinds') iterate, step start, next state, stage
  // start and last configuration, and the stage data built from them.
  std::vector<Eigen::VectorXd> softX, softStepStart, softLast, softEnd;
  std::vector<SoftBodyState> softNext, softStart;
  SoftStage softStage;
  ReportStage reportStage;                           ///< the last stage solved
};

}  // namespace superdex
