// The tape of one step's stages, as the derivative computations need them (core/sensitivity/
// sensitivity.h, step_linearization.h), and the recording policy that fills and replays it
// (core/dynamics/stage_recorder.h): Record keeps each stage's accepted solution and its factored
// Jacobian; Replay replaces each stage solve by one Newton step from the recorded solution with
// the recorded factors, the residual evaluated with the current (perturbed) inputs; Inject takes
// each stage's solution as the recorded one moved by the entry's `inject` and keeps the residual
// there.
#pragma once

#include <memory>
#include <vector>

#include "core/contact/slip_tape.h"
#include "core/dynamics/stage_recorder.h"
#include "core/scene.h"
#include "optim/linear_solver.h"

namespace superdex {

/// One stage as recorded: its accepted solution, the dissipation mode it was solved in, the stage
/// Jacobian ∂r/∂δ there and its LU factors.
struct StageTapeEntry {
  std::vector<Eigen::VectorXd> x;  ///< the actors' configurations (the stage's solution)
  DissipationMode mode = DissipationMode::ExplicitNormals;
  Eigen::SparseMatrix<double> jacobian;
  std::unique_ptr<UnsymmetricSolver> lu = std::make_unique<UnsymmetricSolver>();
  bool factored = false;
  /// Inject mode (core/sensitivity/step_linearization.h): the stage's solution is taken as
  /// x ⊕ inject (the stage's chart: each actor's free tangent dofs, a rigid body's [δp, δθ];
  /// empty = 0), and the stage residual there, with the inputs of the perturbed step, is kept in
  /// `residual`.
  Eigen::VectorXd inject, residual;
  /// The dissipative samples' slips at the solution (core/contact/slip_tape.h): the replays and
  /// injected runs evaluate the friction force about them.
  StageSlips slips;
};

struct StepTape {
  std::vector<StageTapeEntry> stages;  ///< kept from step to step (symbolic analyses reused)
  int used = 0;                        ///< stages of the last recorded step
};

class TapeRecorder : public StageRecorder {
 public:
  enum class Mode { Record, Replay, Inject };
  TapeRecorder(StepTape* tape, Mode mode) : tape_(tape), mode_(mode) {}
  void BeginStep() override { stage_ = 0; }
  bool Supplies() const override { return mode_ != Mode::Record; }
  bool Records() const override { return mode_ == Mode::Record; }
  void Supply(const StageInputs& inputs, const StageDissipation& dissipation,
              std::vector<Eigen::VectorXd>* x) override;
  void Record(const StageInputs& inputs, const StageDissipation& dissipation,
              const std::vector<Eigen::VectorXd>& x) override;

 private:
  StepTape* tape_;
  Mode mode_;
  int stage_ = 0;
};

/// Steps `scene` by dt recording every stage in *tape. False, with the reason, for invalid input,
/// a stage that did not converge or a singular stage Jacobian at the solution: the derivative of
/// such a step is not defined. The step's report in *report either way (may be null).
bool StepAndRecord(Scene* scene, double dt, StepTape* tape, StepReport* report, Error* error);

}  // namespace superdex
