// Runs a loaded scene: steps it, writes the trajectory, and summarizes the run.
#pragma once

#include <functional>
#include <ostream>
#include <string>

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
};

struct RunSummary {
  int steps = 0;
  double simulatedSeconds = 0.0;
  double wallSeconds = 0.0;    ///< in Scene::Step only (what the benchmarks compare)
  double outputSeconds = 0.0;  ///< writing trajectory frames and VTK files, and progress calls
  long newtonIterations = 0;
  int fallbacks = 0;  ///< stages re-solved with explicit normals after a failed residual solve
  long stages = 0;      ///< stages solved, summed over steps
  long freeStages = 0;  ///< of those, solved in closed form (StepReport::freeStages)
  long krylovIterations = 0;  ///< iterative linear solves: their iterations, summed
  long krylovFallbacks = 0;   ///< iterative linear solves that fell back to the direct solve
  double assemblySeconds = 0.0, factorizationSeconds = 0.0, lineSearchSeconds = 0.0;
  int maxNewtonIterations = 0;
  int converged = 0, stopped = 0, diverged = 0;  ///< stages by outcome
  double maxPenetration = 0.0;        ///< max over steps of max(0, −min φ) [m]
  double minDetF = INFINITY;          ///< smallest det F over soft tets at step ends (+∞: none)
  double initialEnergy = 0.0, finalEnergy = 0.0;  ///< total mechanical energy [J]
  std::vector<std::string> expectationFailures;   ///< empty when every expectation holds
  std::string trajectoryPath;
  std::string viewerPage;    ///< the viewer page written ("" = none)
  double viewerSeconds = 0.0;  ///< writing it
  std::string vtkDirectory;  ///< where the VTK frames went ("" = none)
  int vtkFrames = 0;
};

/// Runs to the end. Returns false only for I/O or input errors (then *error says which).
bool RunScene(SceneFile* scene, const RunOptions& options, RunSummary* summary, Error* error);

/// The one-screen summary printed by `superdex run`.
void PrintSummary(const SceneFile& scene, const RunSummary& summary, std::ostream& os);

}  // namespace superdex
