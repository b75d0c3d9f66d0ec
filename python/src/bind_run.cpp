// Running a scene file as `superdex run` does (scenes/runner.h): the run summary with its
// expectations, and scene files from JSON text. superdex.sweep runs its variants with these.
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <cmath>

#include "bindings.h"
#include "scene_file_of.h"
#include "scenes/runner.h"

namespace superdex::python {

void BindRunSummary(py::module_& m) {
  py::class_<RunSummary> c(m, "RunSummary",
                           "The figures of a run of a scene file (what `superdex run` prints).");
  // A read-only property per row of the summary's table: "<description> [<unit>]".
  ForEachField(kRunSummaryFields, [&](const auto& f) {
    c.def_readonly(f.name, f.member,
                   Keep(std::string(f.doc) + (*f.unit ? std::string(" [") + f.unit + "]" : "")));
  });
  c.def_readonly("expectation_failures", &RunSummary::expectationFailures,
                 "One message per failed expectation of the scene file (empty: all hold)");
  c.def("__repr__", [](const RunSummary& s) {
    return "<superdex.RunSummary " + std::to_string(s.steps) + " steps, " +
           std::to_string(s.stopped + s.diverged) + " not converged, " +
           std::to_string(s.expectationFailures.size()) + " expectations failed>";
  });
}

void BindRunScene(py::module_& m) {
  auto run = [](SceneFile& file, std::optional<double> dt, std::optional<double> duration,
                std::optional<std::string> out, std::optional<std::string> vtk,
                const std::function<void(const StepReport&, double)>& progress) {
        RunOptions options;
        options.dt = dt;
        options.duration = duration;
        options.out = out;
        options.vtk = vtk;
        RunSummary summary;
        Error e;
        bool ok;
        if (progress) {
          // The callback needs the GIL after every step; without one the run releases it.
          options.progress = progress;
          ok = RunScene(&file, options, &summary, &e);
        } else {
          py::gil_scoped_release release;
          ok = RunScene(&file, options, &summary, &e);
        }
        if (!ok) throw py::value_error(e.message);
        return summary;
  };
  m.def(
      "run_scene", run,
      py::arg("scene_file"), py::arg("dt") = py::none(), py::arg("duration") = py::none(),
      py::arg("out") = py::none(), py::arg("vtk") = py::none(), py::arg("progress") = nullptr,
      "Runs a loaded scene file to its end as `superdex run` does and returns a RunSummary.\n"
      "dt, duration [s], out (trajectory path) and vtk (frame directory) override the file's\n"
      "settings; out='' and vtk='' write nothing. progress(report, fraction) is called after\n"
      "every step. Stages that do not converge are counted in the summary (stopped,\n"
      "diverged), not raised; bad input or an I/O error raises ValueError.");
  m.def(
      "run_scene",
      [run](const Scene& scene, std::optional<double> dt, std::optional<double> duration,
            std::optional<std::string> out, std::optional<std::string> vtk,
            const std::function<void(const StepReport&, double)>& progress) {
        if (!duration) throw py::value_error("duration: a Scene built in Python has none; give it");
        SceneFile file = FileOf(scene, dt, *duration);
        return run(file, dt, duration, out ? out : std::optional<std::string>(""),
                   vtk ? vtk : std::optional<std::string>(""), progress);
      },
      py::arg("scene"), py::arg("dt") = py::none(), py::arg("duration") = py::none(),
      py::arg("out") = py::none(), py::arg("vtk") = py::none(), py::arg("progress") = nullptr,
      "The same for a Scene built in Python (a copy runs; the scene is left unchanged): dt and\n"
      "duration are required; out and vtk default to writing nothing.");
}

void BindLoadSceneText(py::module_& m) {
  m.def(
      "load_scene_text",
      [](const std::string& text, const std::string& baseDir) {
        auto f = std::make_unique<SceneFile>();
        Error e;
        bool ok;
        {
          py::gil_scoped_release release;
          ok = LoadSceneText(text, baseDir, f.get(), &e);
        }
        if (!ok) throw py::value_error(e.message);
        return f;
      },
      py::arg("text"), py::arg("base_dir") = ".",
      "Loads a scene file from its JSON text; base_dir resolves relative mesh paths. Raises\n"
      "ValueError naming the JSON path and the rule.");
}

}  // namespace superdex::python
