#include "core/sensitivity/stage_tape.h"

namespace superdex {

void TapeRecorder::Record(const StageInputs& inputs, const StageDissipation& dissipation,
                          const std::vector<Eigen::VectorXd>& x) {
  if (static_cast<int>(tape_->stages.size()) <= stage_) tape_->stages.emplace_back();
  StageTapeEntry& e = tape_->stages[stage_++];
  tape_->used = stage_;
  e.x = x;
  e.mode = dissipation.mode;
  // The stage Jacobian at the accepted solution, in the same mode (a copy of the iterate: the
  // problem commits into the vectors it is given).
  std::vector<Eigen::VectorXd> at = e.x;
  StageDissipation recording = dissipation;
  e.slips.Clear();
  recording.slips = &e.slips;
  recording.recordSlips = true;
  SceneStageProblem problem = inputs.Problem(recording, &at);
  Eigen::VectorXd r;
  Eigen::SparseMatrix<double> J;
  problem.EvaluateResidual(&r, &J);
  e.factored = inputs.numDofs > 0 && e.lu->Factorize(J);
  e.jacobian = std::move(J);
}

void TapeRecorder::Supply(const StageInputs& inputs, const StageDissipation& dissipation,
                          std::vector<Eigen::VectorXd>* x) {
  StageTapeEntry& e = tape_->stages[stage_++];
  *x = e.x;
  const int numDofs = inputs.numDofs;
  if (numDofs == 0) {
    e.residual.resize(0);
    return;
  }
  StageDissipation d = dissipation;
  d.mode = e.mode;
  d.slips = &e.slips;
  SceneStageProblem problem = inputs.Problem(d, x);
  if (mode_ == Mode::Replay) {  // one Newton step with the recorded factors
    Eigen::VectorXd r;
    problem.Residual(Eigen::VectorXd::Zero(numDofs), &r);
    problem.Commit(-e.lu->Solve(r));
    return;
  }
  const Eigen::VectorXd delta =  // Inject
      e.inject.size() == numDofs ? e.inject : Eigen::VectorXd::Zero(numDofs);
  problem.Residual(delta, &e.residual);
  problem.Commit(delta);
}

bool StepAndRecord(Scene* scene, double dt, StepTape* tape, StepReport* report, Error* error) {
  StepReport rep;
  TapeRecorder recorder(tape, TapeRecorder::Mode::Record);
  const bool ok = scene->Step(dt, &rep, error, &recorder);
  if (report) *report = rep;
  if (!ok) return false;
  if (rep.status != StageStatus::Converged)
    return Fail(error, "a stage did not converge (" + rep.message +
                           "): the derivative of this step is not defined");
  for (int s = 0; s < tape->used; ++s)
    if (scene->StageDofs() > 0 && !tape->stages[s].factored)
      return Fail(error, "the stage Jacobian at the solution is singular: the derivative of this "
                         "step is not defined");
  return true;
}

}  // namespace superdex
