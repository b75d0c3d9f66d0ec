// A scene's state in Python: Scene.get_state / set_state (a SceneState, picklable, exact),
// Scene.clone (and copy.copy / copy.deepcopy).
#include <pybind11/stl.h>

#include "bindings.h"
#include "core/scene.h"
#include "scenes/checkpoint.h"

namespace superdex::python {

void BindSceneState(py::module_& m) {
  py::class_<Scene::Snapshot>(
      m, "SceneState",
      "A scene's complete dynamic state at one time (Scene.get_state): the actors' states, the\n"
      "integrator's history and the stage policy's state, so that set_state on the same scene\n"
      "(or a copy of it, or the same scene built again) continues bit for bit. Picklable; the\n"
      "pickle holds every number exactly (superdex-state/1 JSON with hex floats).")
      .def_property_readonly("time", [](const Scene::Snapshot& s) { return s.step.time; },
                             "simulated time [s]")
      .def_property_readonly(
          "history_states", [](const Scene::Snapshot& s) { return s.step.rigidHistory.size(); },
          "how many earlier states the multistep integrator keeps (0 after a state change)")
      .def(py::pickle(
          [](const Scene::Snapshot& s) { return py::bytes(StateText(s)); },
          [](const py::bytes& text) {
            Scene::Snapshot s;
            Error e;
            if (!ReadStateText(std::string(text), &s, &e)) throw py::value_error(e.message);
            return s;
          }))
      .def("__repr__", [](const Scene::Snapshot& s) {
        return "<superdex.SceneState t=" + std::to_string(s.step.time) + " s>";
      });
}

void BindSceneStateMethods(py::class_<Scene>& scene) {
  auto clone = [](const Scene& s) { return std::make_unique<Scene>(s); };
  scene
      .def("get_state", &Scene::Save,
           "The scene's complete dynamic state now (a SceneState; see set_state).")
      .def(
          "set_state",
          [](Scene& s, const Scene::Snapshot& state) {
            Error e;
            if (!StateFits(state, s, &e)) throw py::value_error(e.message);
            s.Restore(state);
          },
          py::arg("state"),
          "Returns the scene to a state from get_state (of this scene, a clone, or the same\n"
          "scene built again): the next steps equal those that followed it, bit for bit.\n"
          "ValueError when the state's actors have other sizes than this scene's.")
      .def("clone", clone,
           "An independent copy of the scene (actors, settings, state and history).")
      .def("__copy__", clone)
      .def("__deepcopy__", [=](const Scene& s, py::dict) { return clone(s); }, py::arg("memo"))
      .def("__reduce__", [](const Scene&) -> py::object {
        throw py::type_error(
            "a superdex.Scene cannot be pickled; pickle scene.get_state() and restore it with "
            "set_state() on the same scene built again, or use scene.clone()");
      });
}

}  // namespace superdex::python
