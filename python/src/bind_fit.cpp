// Trajectory sensitivities, adjoint gradients and parameter fitting (core/sensitivity/sensitivity.h,
// core/sensitivity/adjoint.h, scenes/fit.h).
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>

#include "bindings.h"
#include "core/sensitivity/sensitivity.h"
#include "scenes/fit.h"
#include "scene_file_of.h"

namespace superdex::python {
namespace {

ActorHandle NamedActor(const Scene& scene, const std::string& name) {
  const ActorHandle h = scene.FindActor(name);
  if (!h.IsValid()) throw py::value_error("no actor named \"" + name + "\"");
  return h;
}

// Holds the scene it steps (kept alive by the Python object).
struct PySensitivity {
  Scene* scene = nullptr;
  ForwardSensitivity sens;
  std::vector<std::string> names;
};

ObservedTrajectory ObservedFromArrays(const std::vector<std::string>& actors,
                                      const py::handle& times, const py::dict& positions) {
  const auto t = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(times);
  if (!t || t.ndim() != 1) throw py::value_error("times: must be a 1-D array of numbers [s]");
  ObservedTrajectory obs;
  obs.actors = actors;
  obs.frames.resize(t.shape(0));
  for (py::ssize_t k = 0; k < t.shape(0); ++k) {
    obs.frames[k].time = t.at(k);
    obs.frames[k].position.assign(actors.size(), std::nullopt);
  }
  for (auto item : positions) {
    const std::string name = py::str(item.first);
    size_t a = 0;
    while (a < actors.size() && actors[a] != name) ++a;
    if (a == actors.size()) {
      obs.actors.push_back(name);
      for (auto& f : obs.frames) f.position.emplace_back(std::nullopt);
    }
    const std::string field = "positions['" + name + "']";
    const auto rows = RowsFromArray<3>(item.second, field.c_str());
    if (static_cast<py::ssize_t>(rows.size()) != t.shape(0))
      throw py::value_error(field + ": needs one row per time (" + std::to_string(t.shape(0)) +
                            "), got " + std::to_string(rows.size()));
    for (size_t k = 0; k < rows.size(); ++k)
      if (rows[k].allFinite()) obs.frames[k].position[a] = rows[k];  // NaN: not observed
  }
  return obs;
}

// The observation of superdex.fit and superdex.trajectory_gradient: a file, or arrays.
ObservedTrajectory Observed(const SceneFile& file, const std::optional<std::string>& observed,
                            const py::object& times, const std::optional<py::dict>& positions) {
  ObservedTrajectory obs;
  if (observed) {
    if (!times.is_none() || positions)
      throw py::value_error("observed: give a file or times and positions, not both");
    Error e;
    if (!ReadObservedTrajectory(*observed, &obs, &e)) throw py::value_error(e.message);
    for (const std::string& note : obs.notes)  // e.g. a truncated last line, skipped
      if (PyErr_WarnEx(PyExc_UserWarning, note.c_str(), 1) != 0) throw py::error_already_set();
    return obs;
  }
  if (times.is_none() || !positions)
    throw py::value_error("observed: give a trajectory file, or times and positions");
  return ObservedFromArrays(file.actorNames, times, *positions);
}

// A failed fit or gradient: RuntimeError for a simulation that did not converge, else ValueError.
[[noreturn]] void Raise(const Error& e) {
  if (e.message.find("converge") != std::string::npos) throw std::runtime_error(e.message);
  throw py::value_error(e.message);
}

}  // namespace

// ForwardSensitivity.
void BindForwardSensitivity(py::module_& m) {
  py::class_<PySensitivity>(
      m, "ForwardSensitivity",
      "Forward sensitivities dS/dθ carried along a simulation (core/sensitivity/sensitivity.h): each stage\n"
      "is differentiated by the implicit function theorem with its Jacobian factored at the\n"
      "solution; the partials of the stage residual are Richardson-extrapolated differences.\n"
      "Parameters are 'ACTOR.NAME' strings (see superdex.fit). Steps the scene it is given.")
      .def(py::init([](Scene& scene, const std::vector<std::string>& parameters) {
             auto s = std::make_unique<PySensitivity>();
             s->scene = &scene;
             s->names = parameters;
             std::vector<SceneParameter> params(parameters.size());
             Error e;
             for (size_t j = 0; j < params.size(); ++j)
               if (!ParseSceneParameter(scene, parameters[j], &params[j], &e))
                 throw py::value_error(e.message);
             if (!s->sens.Begin(&scene, params, &e)) throw py::value_error(e.message);
             return s;
           }),
           py::arg("scene"), py::arg("parameters"), py::keep_alive<1, 2>())
      .def(
          "step",
          [](PySensitivity& s, double dt) {
            StepReport r;
            Error e;
            const bool ok = WithoutGil([&] { return s.sens.Step(dt, &r, &e); });
            if (!ok) {
              if (r.status != StageStatus::Converged) throw std::runtime_error(e.message);
              throw py::value_error(e.message);
            }
            return r;
          },
          py::arg("dt"),
          "Steps the scene and the sensitivities; RuntimeError when a stage does not converge.")
      .def(
          "com_jacobian",
          [](const PySensitivity& s, const std::string& actor) {
            return Eigen::MatrixXd(s.sens.CenterOfMassJacobian(NamedActor(*s.scene, actor)));
          },
          py::arg("actor"), "d(centre of mass)/dθ of the named actor, a (3, P) array [m per unit θ]")
      .def_property_readonly(
          "state_jacobian", [](const PySensitivity& s) { return s.sens.StateJacobian(); },
          "dS/dθ, (state size, P): rows as the scene's packed state")
      .def_readonly("parameters", &PySensitivity::names);
}

// FitResult, TrajectoryGradient, fit() and gradient().
void BindFitting(py::module_& m) {
  py::class_<FitResult>(m, "FitResult", "The outcome of superdex.fit.")
      .def_readonly("names", &FitResult::names)
      .def_readonly("initial", &FitResult::initial)
      .def_readonly("fitted", &FitResult::fitted)
      .def_readonly("standard_error", &FitResult::standardError,
                    "one-sigma errors from the Gauss-Newton covariance")
      .def_readonly("initial_cost", &FitResult::initialCost, "½ Σ r² [m²]")
      .def_readonly("final_cost", &FitResult::finalCost, "½ Σ r² [m²]")
      .def_readonly("rms_residual", &FitResult::rmsResidual, "[m]")
      .def_readonly("iterations", &FitResult::iterations)
      .def_readonly("simulations", &FitResult::simulations)
      .def_readonly("wall_seconds", &FitResult::wallSeconds)
      .def_readonly("converged", &FitResult::converged)
      .def_readonly("message", &FitResult::message)
      .def(
          "apply",
          [](const FitResult& r, Scene& scene) {
            Error e;
            if (!ApplyParameterValues(&scene, r.names, r.fitted, &e))
              throw py::value_error(e.message);
          },
          py::arg("scene"),
          "Sets the fitted values on `scene` (a Scene, or a loaded file's .scene); then\n"
          "scene.write_scene_file(...) writes the fitted scene.")
      .def("__repr__", [](const FitResult& r) {
        std::string s = "<superdex.FitResult";
        for (size_t j = 0; j < r.names.size(); ++j)
          s += " " + r.names[j] + "=" + std::to_string(r.fitted[j]);
        return s + (r.converged ? "" : " (not converged)") + ">";
      });

  static const std::string fitDoc =
      "Fits parameters ('ACTOR.NAME', NAME one of " + SceneParameterNames() + ") of a\n"
      "loaded scene file (left unchanged) to observed centres of mass: a trajectory file\n"
      "(`observed`), or `times` (K,) [s] with `positions` {actor name: (K, 3) array [m], NaN\n"
      "rows unobserved}. Times must fall on the step grid. method 'lm': Levenberg-Marquardt\n"
      "with forward sensitivities and standard errors (a few parameters); 'lbfgs': L-BFGS with\n"
      "adjoint gradients (many parameters, no standard errors). Returns a FitResult.";
  auto fit = [](const SceneFile& file, const std::vector<std::string>& parameters,
                std::optional<std::string> observed, py::object times,
                std::optional<py::dict> positions, std::optional<double> dt, int maxIterations,
                const std::string& method) {
        const ObservedTrajectory obs = Observed(file, observed, times, positions);
        FitOptions options;
        options.parameters = parameters;
        options.dt = dt;
        options.maxIterations = maxIterations;
        if (!ParseFitMethod(method, &options.method)) {
          std::string names;
          for (const EnumName<FitMethod>& n : NamesOf(FitMethod()))
            names += std::string(names.empty() ? "'" : "' or '") + n.name;
          throw py::value_error("method: must be " + names + "', got '" + method + "'");
        }
        FitResult r;
        Error e;
        const bool ok = WithoutGil([&] { return FitSceneParameters(file, obs, options, &r, &e); });
        if (!ok) Raise(e);
        return r;
  };
  m.def("fit", fit, py::arg("scene_file"), py::arg("parameters"), py::arg("observed") = py::none(),
        py::arg("times") = py::none(), py::arg("positions") = py::none(),
        py::arg("dt") = py::none(), py::arg("max_iterations") = 50, py::arg("method") = "lm",
        fitDoc.c_str());
  m.def(
      "fit",
      [fit](const Scene& scene, const std::vector<std::string>& parameters,
            std::optional<std::string> observed, py::object times,
            std::optional<py::dict> positions, std::optional<double> dt, int maxIterations,
            const std::string& method) {
        return fit(FileOf(scene, dt, 1.0), parameters, observed, times, positions, dt,
                   maxIterations, method);
      },
      py::arg("scene"), py::arg("parameters"), py::arg("observed") = py::none(),
      py::arg("times") = py::none(), py::arg("positions") = py::none(), py::arg("dt") = py::none(),
      py::arg("max_iterations") = 50, py::arg("method") = "lm",
      "The same for a Scene built in Python (left unchanged); dt is required.");

  py::class_<TrajectoryGradient>(m, "TrajectoryGradient",
                                 "The outcome of superdex.trajectory_gradient.")
      .def_readonly("names", &TrajectoryGradient::names)
      .def_readonly("values", &TrajectoryGradient::values)
      .def_readonly("cost", &TrajectoryGradient::cost, "½ Σ r² [m²]")
      .def_property_readonly(
          "gradient",
          [](const TrajectoryGradient& g) {
            return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(g.gradient.data(),
                                                                     g.gradient.size()));
          },
          "d cost / d value, one entry per parameter")
      .def_readonly("residuals", &TrajectoryGradient::residuals)
      .def_readonly("steps", &TrajectoryGradient::steps)
      .def_readonly("simulation_seconds", &TrajectoryGradient::simulationSeconds)
      .def_readonly("gradient_seconds", &TrajectoryGradient::gradientSeconds);

  auto gradient = [](const SceneFile& file, const std::vector<std::string>& parameters,
                     std::optional<std::string> observed, py::object times,
                     std::optional<py::dict> positions, std::optional<double> dt) {
        const ObservedTrajectory obs = Observed(file, observed, times, positions);
        FitOptions options;
        options.parameters = parameters;
        options.dt = dt;
        TrajectoryGradient g;
        Error e;
        const bool ok = WithoutGil(
            [&] { return ComputeTrajectoryGradient(file, obs, options, &g, &e); });
        if (!ok) Raise(e);
        return g;
  };
  m.def("trajectory_gradient", gradient, py::arg("scene_file"), py::arg("parameters"),
        py::arg("observed") = py::none(), py::arg("times") = py::none(),
        py::arg("positions") = py::none(), py::arg("dt") = py::none(),
        "The fitting cost ½ Σ ‖c_a(t_k) − ĉ_a(t_k)‖² of superdex.fit at the scene file's values\n"
        "and its gradient in `parameters`, by one simulation and one adjoint pass (its cost does\n"
        "not grow with the number of initial-state parameters). Returns a TrajectoryGradient.");
  m.def(
      "trajectory_gradient",
      [gradient](const Scene& scene, const std::vector<std::string>& parameters,
                 std::optional<std::string> observed, py::object times,
                 std::optional<py::dict> positions, std::optional<double> dt) {
        return gradient(FileOf(scene, dt, 1.0), parameters, observed, times, positions, dt);
      },
      py::arg("scene"), py::arg("parameters"), py::arg("observed") = py::none(),
      py::arg("times") = py::none(), py::arg("positions") = py::none(), py::arg("dt") = py::none(),
      "The same for a Scene built in Python (left unchanged); dt is required.");
}

}  // namespace superdex::python
