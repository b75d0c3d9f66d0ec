// The JSON scene format (README "Scene format"): loading with errors that name the JSON path.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"

namespace superdex {

/// Output settings of a scene file.
struct OutputSpec {
  std::string path;      ///< trajectory file (JSON Lines); empty: no file
  int every = 1;         ///< write every n-th step
  std::string vtk;       ///< directory for VTK frames (frame_000000.vtk, ...); empty: none
  int vtkEvery = 10;     ///< a frame every n-th step
  bool contacts = false; ///< the trajectory frames carry the contact samples (for the viewer)
};

/// The fields (optim/field_table.h), named as the scene file's `output` keys.
inline constexpr auto kOutputSpecFields = std::make_tuple(
    MakeField("path", &OutputSpec::path, "", NoRule(),
              "Trajectory file (JSON Lines, docs/trajectory-format.md); empty: none. `--out` "
              "overrides"),
    MakeField("every", &OutputSpec::every, "", AtLeast(1, 1 << 30),
              "A trajectory frame every so many steps (plus the initial state and the last step)"),
    MakeField("vtk", &OutputSpec::vtk, "", NoRule(),
              "Directory for VTK frames; empty: none. `--vtk` overrides"),
    MakeField("vtk_every", &OutputSpec::vtkEvery, "", AtLeast(1, 1 << 30),
              "A VTK frame every so many steps"),
    MakeField("contacts", &OutputSpec::contacts, "", NoRule(),
              "Every frame carries the active contact samples (what the viewer page draws). "
              "`--contacts` sets it"));

/// The table of Validate (optim/field_table.h).
constexpr const auto& FieldsOf(const OutputSpec&) { return kOutputSpecFields; }

/// Expected figures of a shipped scene (regression checks run by `superdex run` and the tests).
struct SceneExpectations {
  std::optional<double> maxPenetration;        ///< max over the run of max(0, −φ) <= this [m]
  std::optional<double> maxRelativeEnergyDrift;///< |E_end − E_0| / |E_0| <= this
  bool allConverged = false;                   ///< every stage Converged
  struct RestingActor {
    std::string actor;
    Eigen::Vector3d position;
    double tolerance;                          ///< [m]
  };
  std::vector<RestingActor> finalPositions;    ///< centre of mass at the end of the run
};

/// A loaded scene: the Scene itself plus the run settings from the file.
struct SceneFile {
  std::string path;
  std::string description;
  std::unique_ptr<Scene> scene;
  double dt = 1e-3;        ///< [s]
  double duration = 1.0;   ///< [s]
  /// settings.penetration_bound [m]: a run fails when the penetration exceeds it (unset: the
  /// smallest half extent over the actors, scenes/run_checks.h).
  std::optional<double> penetrationBound;
  OutputSpec output;
  SceneExpectations expect;
  std::vector<std::string> actorNames;  ///< index → name
  std::uint64_t textHash = 0;  ///< SceneTextHash of the file's text (scenes/checkpoint.h)
};

/// Loads a scene file. Returns false and fills *error with "<json path>: <rule>" (e.g.
/// "actors[2].contact.penalty_coefficient: must be > 0, got -3") on the first problem found.
bool LoadSceneFile(const std::string& path, SceneFile* out, Error* error);
/// The same from a JSON text; `baseDir` resolves relative mesh paths.
bool LoadSceneText(const std::string& text, const std::string& baseDir, SceneFile* out,
                   Error* error);

}  // namespace superdex
