// Checkpoints of `superdex run` (docs/reliability.md "Checkpoints"): the complete state of a run
// after a step, written atomically (a temporary file renamed over the old one), from which
// `superdex run --resume FILE` continues so that the resumed trajectory equals the
// uninterrupted one bit for bit.
//
// The file is JSON (format "superdex-checkpoint", version 1) with every double as a C99 hex
// float string ("0x1.999999999999ap-4", exact), headed by the hash of the scene file's text: a
// checkpoint is refused for another scene file, another dt or integrator, or actors of another
// size, with the field named.
//
// A scene's state alone (Python's Scene.get_state / set_state, picklable) is the same snapshot in
// its own JSON document (format "superdex-state", version 1).
#pragma once

#include <cstdint>
#include <string>

#include "core/scene.h"
#include "scenes/run_accumulators.h"

namespace superdex {

/// The run's side of a checkpoint: what the runner needs besides the scene's state to continue
/// the run, its outputs and its summary as if it had not stopped. The summary's accumulators
/// over steps 1..step (RunAccumulators) are written and read through kRunAccumulatorFields.
struct CheckpointRun : RunAccumulators {
  long long step = 0;      ///< steps done; the resumed run continues with step + 1
  double dt = 0.0;         ///< [s], as run (refused on resume when it differs)
  std::string integrator;  ///< as run (refused on resume when it differs)
  std::string trajectoryPath;     ///< "" = none
  long long trajectoryBytes = 0;  ///< its length after the frames due by `step` (resume truncates)
};

struct Checkpoint {
  std::uint64_t sceneHash = 0;  ///< SceneTextHash of the scene file
  std::string scenePath;        ///< as given when it was written (for the messages)
  CheckpointRun run;
  Scene::Snapshot snapshot;
};

/// FNV-1a (64 bit) of a scene file's text.
std::uint64_t SceneTextHash(const std::string& text);

/// Writes `checkpoint` to `path` + ".part", flushes it and renames it to `path`; false with
/// "checkpoint: writing \"PATH\" failed: <reason>" in *error.
bool WriteCheckpoint(const std::string& path, const Checkpoint& checkpoint, Error* error);

/// Reads a checkpoint written by WriteCheckpoint; false with "checkpoint PATH: <field>: <rule>"
/// in *error for a missing or truncated file, another format or version, or a malformed field.
bool ReadCheckpoint(const std::string& path, Checkpoint* checkpoint, Error* error);

/// Whether `checkpoint` continues a run of `scene` (loaded from text of hash `sceneHash`, with
/// its settings as they will run, at step dt [s]): the same scene file, dt, integrator, and
/// states of the scene's sizes. False with "checkpoint PATH: <field>: <what differs>".
bool CheckpointFits(const Checkpoint& checkpoint, const std::string& path, const Scene& scene,
                    std::uint64_t sceneHash, double dt, Error* error);

/// The scene's state `snapshot` (Scene::Save) as text: exact (hex floats), for a copy of the same
/// scene to Restore.
std::string StateText(const Scene::Snapshot& snapshot);
/// Reads StateText's text; false with "state: <field>: <rule>" in *error.
bool ReadStateText(const std::string& text, Scene::Snapshot* snapshot, Error* error);
/// Whether `snapshot` has the sizes of `scene`'s actors (its states and history); false with
/// "state: <field>: <what differs>" in *error.
bool StateFits(const Scene::Snapshot& snapshot, const Scene& scene, Error* error);

}  // namespace superdex
