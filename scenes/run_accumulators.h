// The figures a run gathers over its steps (RunAccumulators): the part of the run summary
// (RunSummary, scenes/runner.h) that a checkpoint carries (CheckpointRun, scenes/checkpoint.h), so
// that a resumed run's summary continues the interrupted one's. Their names, units and
// descriptions are written once, in kRunAccumulatorFields (optim/field_table.h): the checkpoint's
// keys under "run" and, with RunSummary's other figures, the Python properties.
#pragma once

#include <cmath>
#include <tuple>

#include "optim/field_table.h"

namespace superdex {

/// The summary's accumulators over steps 1..n; names and units are in kRunAccumulatorFields.
struct RunAccumulators {
  int vtkFrames = 0;          ///< VTK frames written
  long newtonIterations = 0;  ///< summed over steps
  long stages = 0;            ///< stages solved, summed over steps
  long freeStages = 0;        ///< of those, solved in closed form (StepReport::freeStages)
  long krylovIterations = 0;  ///< iterative linear solves: their iterations, summed
  long krylovFallbacks = 0;   ///< iterative linear solves that fell back to the direct solve
  int fallbacks = 0;  ///< stages re-solved with explicit normals after a failed residual solve
  int maxNewtonIterations = 0;                   ///< in one step
  int converged = 0, stopped = 0, diverged = 0;  ///< steps by their stages' worst outcome
  double maxPenetration = 0.0;  ///< max over steps of max(0, −min φ) [m]
  double minDetF = INFINITY;    ///< smallest det F over soft tets at step ends [-] (+∞: none)
  double initialEnergy = 0.0;   ///< total mechanical energy at the start [J]
};

/// The fields (optim/field_table.h), one row per line, in the order a checkpoint's "run" object
/// is read. The summary is an output: no row has a rule.
inline constexpr auto kRunAccumulatorFields = [] {
  using A = RunAccumulators;
  return std::make_tuple(
      MakeField("vtk_frames", &A::vtkFrames, "", "VTK frames written"),
      MakeField("newton_iterations", &A::newtonIterations, "", "Newton iterations, summed"),
      MakeField("stages", &A::stages, "", "Stages solved, summed over steps"),
      MakeField("free_stages", &A::freeStages, "", "Stages solved in closed form"),
      MakeField("krylov_iterations", &A::krylovIterations, "", "Krylov iterations, summed"),
      MakeField("krylov_fallbacks", &A::krylovFallbacks, "", "Krylov solves fallen back to direct"),
      MakeField("fallbacks", &A::fallbacks, "", "Stages re-solved with explicit normals"),
      MakeField("max_newton_iterations", &A::maxNewtonIterations, "", "Most in one step"),
      MakeField("converged", &A::converged, "", "Steps whose stages converged"),
      MakeField("stopped", &A::stopped, "", "Steps with a stage Stopped"),
      MakeField("diverged", &A::diverged, "", "Steps with a stage Diverged"),
      MakeField("max_penetration", &A::maxPenetration, "m", "Max over steps of max(0, −min φ)"),
      MakeField("min_det_f", &A::minDetF, "-", "Smallest det F of soft tets (inf: none)"),
      MakeField("initial_energy", &A::initialEnergy, "J", "Total mechanical energy at the start"));
}();

}  // namespace superdex
