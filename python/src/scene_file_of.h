// A Scene built in Python where the fitting and the runner take a scene file.
#pragma once

#include <pybind11/pybind11.h>

#include <optional>

#include "scenes/scene_writer.h"

namespace superdex::python {

namespace py = pybind11;

/// A SceneFile holding a copy of `scene` with the time step dt [s] (required: ValueError
/// without) and the duration [s].
inline SceneFile FileOf(const Scene& scene, std::optional<double> dt, double duration) {
  if (!dt) throw py::value_error("dt: a Scene built in Python has no time step; give dt");
  SceneWriteOptions options;
  options.dt = *dt;
  options.duration = duration;
  return SceneFileOf(scene, options);
}

}  // namespace superdex::python
