// SceneSettings and OutputSpec from their field tables (kSceneSettingsFields, kOutputSpecFields):
// the scene-file reader, the validation messages and the docs cover the same rows, and every row
// is read.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <string>

#include "core/scene.h"
#include "scenes/runner.h"
#include "scenes/scene_file.h"

using namespace superdex;

namespace {

std::string SceneText(const std::string& settings) {
  return R"({"format": "superdex-scene/1", "settings": {"dt": 0.001)" + settings +
         R"(}, "actors": [{"name": "ball", "shape": {"type": "sphere", "radius": 0.1}}]})";
}

std::string LoadError(const std::string& settings) {
  SceneFile f;
  Error e;
  return LoadSceneText(SceneText(settings), ".", &f, &e) ? std::string("<loaded>") : e.message;
}

}  // namespace

TEST_CASE("every row of kSceneSettingsFields is read from a scene file", "[scenes][settings]") {
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneText(SceneText(R"(, "gravity": [1, 2, 3], "integrator": "DIRK22",
      "solver": {"max_iterations": 7, "linear_solver": "iterative"}, "stage_solver": "Ceres",
      "experimental_eval_params": {"explicit_normals": true}, "warm_start": false,
      "closed_form_free_stages": false, "duration": 0.5, "penetration_bound": 0.01)"),
                        ".", &f, &e));
  const SceneSettings& s = f.scene->Settings();
  CHECK(s.gravity == Eigen::Vector3d(1, 2, 3));
  CHECK(s.integrator == IntegrationMethod::DIRK22);
  CHECK(s.solver.maxIterations == 7);
  CHECK(s.solver.linear.kind == LinearSolverKind::Iterative);
  CHECK(s.stageSolver == StageSolverKind::Ceres);
  CHECK(s.eval.explicitNormals);
  CHECK_FALSE(s.warmStart);
  CHECK_FALSE(s.closedFormFreeStages);
  CHECK(f.duration == 0.5);
  // Each row differs from its default above: none was skipped.
  const SceneSettings defaults;
  int changed = 0;
  int nested = 0;
  ForEachField(kSceneSettingsFields, [&](const auto& row) {
    if constexpr (kIsNested<decltype(row)>) ++nested;  // solver, eval: checked above
    else if (ValueText(row.Of(s)) != ValueText(row.Of(defaults))) ++changed;
  });
  CHECK(nested == 2);
  CHECK(changed == int(std::tuple_size_v<std::decay_t<decltype(kSceneSettingsFields)>>) - 2);
}

TEST_CASE("bad settings name the field path and the rule", "[scenes][settings]") {
  CHECK(LoadError(R"(, "gravity": [0, "down", 0])") == "settings.gravity[1]: must be a number");
  CHECK(LoadError(R"(, "gravity": [0, 0])") == "settings.gravity: must be an array of 3 numbers");
  CHECK(LoadError(R"(, "warm_start": 1)") ==
        "settings.warm_start: must be true or false, got number");
  CHECK(LoadError(R"(, "solver": {"max_iterations": 0})") ==
        "settings.solver.max_iterations: must be in [1, 1000000], got 0");
  CHECK(LoadError(R"(, "solver": {"max_iteration": 3})") ==
        "settings.solver.max_iteration: unknown field");
  CHECK(LoadError(R"(, "solver": 3)") == "settings.solver: must be an object, got number");
  CHECK(LoadError(R"(, "experimental_eval_params": {"explicit_normals": true,
      "implicit_normal_force_for_dissipation": true})") ==
        "settings.experimental_eval_params.explicit_normals, "
        "implicit_normal_force_for_dissipation: the combination (true, true) is unsupported");
  CHECK(LoadError(R"(, "gravty": [0, 0, 0])") == "settings.gravty: unknown field");
  CHECK(LoadError(R"(, "integrator": "Euler")") ==
        "settings.integrator: unknown value \"Euler\" (expected one of: BackwardEuler, BDF2, "
        "BDF3, DIRK22, DIRK23, DIRK33, SymplecticDIRK12, SymplecticDIRK22)");
}

TEST_CASE("Validate(SceneSettings) checks every row by the table's rule", "[scenes][settings]") {
  SceneSettings s;
  CHECK(Validate(s, "settings.") == "");
  s.gravity.y() = std::nan("");
  CHECK(Validate(s, "settings.") == "settings.gravity: must be finite, got [0, nan, -9.81]");
  s = SceneSettings();
  s.solver.backtrackFactor = 1.0;
  CHECK(Validate(s, "settings.") == "settings.solver.backtrack_factor: must be in (0, 1), got 1");
  s = SceneSettings();
  s.stageSolver = static_cast<StageSolverKind>(7);
  CHECK(Validate(s) == "stage_solver: must be newton, ipopt or ceres, got 7");
}

TEST_CASE("the docs' SceneSettings table has one row per field", "[scenes][settings][docs]") {
  const std::string md = FieldsMarkdown(kSceneSettingsFields);
  std::set<std::string> names;
  ForEachField(kSceneSettingsFields, [&](const auto& row) {
    names.insert(row.name);
    CHECK(md.find(std::string("| `") + row.name + "` |") != std::string::npos);
  });
  CHECK(names == std::set<std::string>{"gravity", "integrator", "solver", "stage_solver",
                                       "experimental_eval_params", "warm_start",
                                       "closed_form_free_stages"});
  CHECK(md.find("| `gravity` | 3 numbers | m/s² | [0, 0, -9.81] | finite |") != std::string::npos);
}

TEST_CASE("the output section is read and validated by kOutputSpecFields", "[scenes][settings]") {
  SceneFile f;
  Error e;
  const std::string text = R"({"format": "superdex-scene/1", "actors": [],
      "output": {"path": "a.jsonl", "every": 3, "vtk": "frames", "vtk_every": 4, "contacts": true}})";
  REQUIRE(LoadSceneText(text, ".", &f, &e));
  CHECK(f.output.path == "a.jsonl");
  CHECK(f.output.every == 3);
  CHECK(f.output.vtk == "frames");
  CHECK(f.output.vtkEvery == 4);
  CHECK(f.output.contacts);
  CHECK_FALSE(LoadSceneText(R"({"actors": [], "output": {"every": 0}})", ".", &f, &e));
  CHECK(e.message == "output.every: must be in [1, 1073741824], got 0");
  CHECK_FALSE(LoadSceneText(R"({"actors": [], "output": {"path": 3}})", ".", &f, &e));
  CHECK(e.message == "output.path: must be a string, got number");
  // A C++ caller's value is checked by the same rule before a run.
  REQUIRE(LoadSceneText(R"({"actors": [], "settings": {"duration": 0.01}})", ".", &f, &e));
  f.output.vtkEvery = 0;
  RunSummary summary;
  CHECK_FALSE(RunScene(&f, RunOptions(), &summary, &e));
  CHECK(e.message == "output.vtk_every: must be >= 1, got 0");
  CHECK(FieldsMarkdown(kOutputSpecFields).find("| `vtk_every` | integer |  | 10 | >= 1") !=
        std::string::npos);
}
