// Writing a Scene as a scene file (superdex-scene/1, docs/scene-format.md): what a scene built in
// C++ or Python says, so that `superdex run`, the fitting and the writers take it, and loading
// the file gives the same scene and the same trajectory, bit for bit.
#pragma once

#include <optional>
#include <string>

#include "core/scene.h"
#include "scenes/scene_file.h"

namespace superdex {

/// What a scene file holds besides the Scene.
struct SceneWriteOptions {
  double dt = 1e-3;        ///< [s]
  double duration = 1.0;   ///< [s]
  std::string description;
  OutputSpec output;
  std::optional<double> penetrationBound;  ///< settings.penetration_bound [m]
};

/// Writes `scene` to the scene file `path`: its settings, every actor from the description it
/// was created from with the values the setters changed since (contact parameters, layer, soft
/// material, rigid mass) and its current state where that differs from the description's (a
/// rigid actor's pose and velocity, a soft actor's uniform shift of positions and velocities; to
/// round-off), the contact filter's
/// settings, and the options. Numbers are written to read back exactly. Meshes are written beside
/// the file, as `<stem>.<actor>.obj` (rigid) and `<stem>.<actor>.msh` (soft, Gmsh 2.2). Refused
/// with a message naming the actor and the rule: a scene that has stepped (t > 0: write it
/// before stepping, or save its state with get_state or a checkpoint), an actor of the generic
/// layer (ActorKind: no scene-file form), a soft actor whose state was set after creation other
/// than by a uniform shift, a full (non-diagonal) inertia tensor.
bool WriteSceneFile(const Scene& scene, const std::string& path, const SceneWriteOptions& options,
                    Error* error);

/// A SceneFile holding a copy of `scene` and the options' run settings, as LoadSceneFile would
/// give for the file WriteSceneFile writes (without writing it): what the fitting and the
/// runner take.
SceneFile SceneFileOf(const Scene& scene, const SceneWriteOptions& options);

}  // namespace superdex
