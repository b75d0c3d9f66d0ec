// Runs a loaded scene: steps it, writes the trajectory, checks every step (scenes/run_checks.h),
// stops cleanly when asked to (a signal), and summarizes the run.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <tuple>
#include <vector>

#include "scenes/checkpoint.h"
#include "scenes/run_accumulators.h"
#include "scenes/scene_file.h"

namespace superdex {

struct RunOptions {
  std::optional<double> dt;          ///< overrides the file's settings.dt [s]
  std::optional<double> duration;    ///< overrides settings.duration [s]
  std::optional<std::string> out;    ///< overrides output.path ("" = no file)
  std::optional<std::string> vtk;    ///< overrides output.vtk ("" = no frames)
  std::optional<bool> contacts;      ///< overrides output.contacts
  /// At the end, the viewer page next to the trajectory (scenes/viewer_page.h); needs a
  /// trajectory file.
  bool view = false;
  /// Called after every step with the step's report and the fraction done in [0, 1].
  std::function<void(const StepReport&, double)> progress;
  /// Polled after every step: a nonzero value (the number of the signal that asked for it) ends
  /// the run there, with that step's frame written and the files closed.
  std::function<int()> interrupted;
  /// Checkpoints (scenes/checkpoint.h): after every `checkpointEvery`-th step (0: never) and
  /// after the step a signal ended the run at, written to `checkpointPath`.
  long long checkpointEvery = 0;
  std::string checkpointPath;
  /// Continues the run `resume` was written from (it must fit: CheckpointFits) instead of
  /// starting at t = 0. The trajectory, when it is the checkpoint's, is cut to its length at the
  /// checkpoint and continued; another path gets a new file from the next frame on.
  const Checkpoint* resume = nullptr;
};

/// How a run ended; `superdex run` maps it to its exit code (docs/reliability.md).
enum class RunEnd {
  Completed,     ///< every step ran (stages may still have stopped or diverged: see the counts)
  InvalidInput,  ///< refused before the first step; *error says why (exit code 2)
  Unphysical,    ///< a step's state is not finite, a soft tet inverted, or the penetration
                 ///< exceeded its bound (exit code 5)
  OutputFailed,  ///< a trajectory, VTK or checkpoint file could not be written (exit code 6)
  Interrupted,   ///< a signal: the current step finished and its frame was written (128 + signal)
};

/// The steps of `duration` at `dt`: round(duration / dt), at least 1. False with the count and
/// the limit in *error when it is beyond limits::kMaxSteps (or dt, duration are not positive).
bool PlanSteps(double duration, double dt, long long* steps, std::string* error);

/// The figures of a run: the accumulators over its steps (RunAccumulators, which checkpoints
/// carry) and the others. Every number and text is named, with its unit, in kRunSummaryFields;
/// how the run ended (end, endMessage, signal) and the expectation failures are not.
struct RunSummary : RunAccumulators {
  RunEnd end = RunEnd::Completed;
  std::string endMessage;  ///< why the run ended early (Unphysical, OutputFailed, Interrupted)
  int signal = 0;          ///< Interrupted: the signal's number
  int steps = 0;           ///< steps run (at most limits::kMaxSteps)
  double simulatedSeconds = 0.0;  ///< [s]
  double wallSeconds = 0.0;    ///< in Scene::Step only (what the benchmarks compare) [s]
  double outputSeconds = 0.0;  ///< writing trajectory frames and VTK files, and progress calls [s]
  double assemblySeconds = 0.0, factorizationSeconds = 0.0, lineSearchSeconds = 0.0;  ///< [s]
  double finalEnergy = 0.0;  ///< total mechanical energy at the end [J]
  std::vector<std::string> expectationFailures;  ///< empty when every expectation holds
  std::string trajectoryPath;  ///< "" = none
  std::string viewerPage;      ///< the viewer page written ("" = none)
  double viewerSeconds = 0.0;  ///< writing it [s]
  std::string vtkDirectory;    ///< where the VTK frames went ("" = none)
};

/// The summary's figures (optim/field_table.h), one row per line: snake_case name (the Python
/// property), member, unit, description: the accumulators' rows (kRunAccumulatorFields), then
/// the others.
inline constexpr auto kRunSummaryFields = [] {
  using S = RunSummary;
  return std::tuple_cat(kRunAccumulatorFields, std::make_tuple(
      MakeField("steps", &S::steps, "", "Steps run"),
      MakeField("simulated_seconds", &S::simulatedSeconds, "s", "Simulated time"),
      MakeField("wall_seconds", &S::wallSeconds, "s", "In the steps only (Scene::Step)"),
      MakeField("output_seconds", &S::outputSeconds, "s", "Output files and progress calls"),
      MakeField("assembly_seconds", &S::assemblySeconds, "s", "Assembly of energies, derivatives"),
      MakeField("factorization_seconds", &S::factorizationSeconds, "s", "Linear solves"),
      MakeField("line_search_seconds", &S::lineSearchSeconds, "s", "Line-search evaluations"),
      MakeField("final_energy", &S::finalEnergy, "J", "Total mechanical energy at the end"),
      MakeField("trajectory_path", &S::trajectoryPath, "", "The trajectory file ('' = none)"),
      MakeField("viewer_page", &S::viewerPage, "", "The viewer page written ('' = none)"),
      MakeField("viewer_seconds", &S::viewerSeconds, "s", "Writing the viewer page"),
      MakeField("vtk_directory", &S::vtkDirectory, "", "Where the VTK frames went ('' = none)")));
}();

/// Runs to the end, or to the first failed check, failed write or interruption. True when every
/// step ran (summary->end == Completed); otherwise summary->end says why and *error the details
/// (also in summary->endMessage once a step has run).
bool RunScene(SceneFile* scene, const RunOptions& options, RunSummary* summary, Error* error);

/// The one-screen summary printed by `superdex run`.
void PrintSummary(const SceneFile& scene, const RunSummary& summary, std::ostream& os);

}  // namespace superdex
