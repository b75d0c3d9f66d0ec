// The checks of a run (scenes/runner.cpp) that turn a silently wrong result into a reported
// failure: the initial state must be representable, and after every step the state must be
// finite, no soft tet inverted, and the deepest penetration within its bound. Each message says
// what, where (step, time, actor) and what to change.
#pragma once

#include <string>

#include "scenes/scene_file.h"

namespace superdex {

/// The deepest penetration a run accepts [m] and where the figure comes from.
struct PenetrationBound {
  double value = INFINITY;
  std::string reason;  ///< e.g. "the smallest half extent of the actors, of 'b1'"
};
/// settings.penetration_bound, else the smallest half extent (sphere radius, box half extent, the
/// half extents of a mesh's or a soft actor's bounding box) over every actor but planes: a
/// penetration deeper than that has pushed an actor halfway into or through another.
PenetrationBound MakePenetrationBound(const SceneFile& file);

/// "" when every actor's state and energies are finite at the start and the penetration is
/// within `bound`; else the reason ("at t = 0: ...").
std::string CheckInitialState(SceneFile* file, const PenetrationBound& bound);

/// "" when the state after step `step` (its report `rep`) is finite, no soft tet is inverted and
/// the penetration is within `bound`; else the reason ("step N (t = T s): ..."). *finite tells
/// whether the state is finite (a non-finite one must not be written or evaluated further).
std::string CheckStep(const SceneFile& file, long long step, const StepReport& rep,
                      const PenetrationBound& bound, bool* finite);

}  // namespace superdex
