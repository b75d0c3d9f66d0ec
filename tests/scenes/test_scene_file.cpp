// Scene files: bad input gets one clear error naming the JSON path and the rule (and exit code 2
// from the command line); shipped scenes load and meet their expectations.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include "scene_text.h"
#include "scenes/parameter_docs.h"
#include "scenes/runner.h"
#include "scenes/scene_file.h"

using namespace superdex;

namespace {

const char* kGood = R"({
  "format": "superdex-scene/1",
  "settings": {"dt": 0.001, "duration": 0.01},
  "actors": [
    {"name": "ground", "dynamic": false, "shape": {"type": "plane"}},
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1.0, "position": [0, 0, 0.5]},
    {"name": "box", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 1.0, "position": [1, 0, 0.5]}
  ]
})";

using test::LoadError;

using test::Replace;

int RunCli(const std::string& args) {
  const std::string cmd = std::string(SUPERDEX_CLI) + " " + args + " > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("scene file: the good file loads", "[scenes]") {
  CHECK(LoadError(kGood) == "<loaded>");
}

TEST_CASE("scene file: each defect gives one error with its JSON path", "[scenes]") {
  CHECK(LoadError(Replace(kGood, R"(, "radius": 0.1)", "")) ==
        "actors[1].shape.radius: missing required field");
  CHECK(LoadError(Replace(kGood, R"("mass": 1.0, "position": [0, 0, 0.5])", R"("mass": "heavy")")) ==
        "actors[1].mass: must be a number, got string");
  CHECK(LoadError(Replace(kGood, R"("mass": 1.0, "position": [1)", R"("mass": -2, "position": [1)")) ==
        "actors[2].mass: must be > 0, got -2");
  CHECK(LoadError(Replace(kGood, R"("duration": 0.01})", R"("duration": 0.01, "integrator": "RK4"})")) ==
        "settings.integrator: unknown value \"RK4\" (expected one of: BackwardEuler, BDF2, BDF3, "
        "DIRK22, DIRK23, DIRK33, SymplecticDIRK12, SymplecticDIRK22)");
  CHECK(LoadError(Replace(kGood, R"("mass": 1.0, "position": [0)",
                          R"("mass": 1.0, "contact": {"max_alignment_normals": 1.5}, "position": [0)")) ==
        "actors[1].contact.max_alignment_normals: must be in [-1, 1], got 1.5");
  CHECK(LoadError(Replace(kGood, R"("mass": 1.0, "position": [0)",
                          R"("mass": 1.0, "contact": {"penalty_coefficient": -3}, "position": [0)")) ==
        "actors[1].contact.penalty_coefficient: must be > 0, got -3");
  CHECK(LoadError(Replace(kGood, R"("shape": {"type": "sphere")", R"("shpe": {"type": "sphere")")) ==
        "actors[1].shpe: unknown field");
  CHECK(LoadError(Replace(kGood, R"("dynamic": false, "shape": {"type": "plane"})",
                          R"("shape": {"type": "plane"})")) ==
        "actors[0].shape: a plane can only be a static actor");
  CHECK(LoadError(Replace(kGood, R"("duration": 0.01})", R"("duration": 0.01, "integrator": "DIRK32"})"))
            .rfind("settings.integrator: unknown value \"DIRK32\"", 0) == 0);
  CHECK(LoadError(Replace(kGood, R"("duration": 0.01})", R"("duration": 0.01, "stage_solver": "lbfgs"})")) ==
        "settings.stage_solver: unknown value \"lbfgs\" (expected one of: newton, ipopt, ceres)");
  CHECK(LoadError(Replace(kGood, R"("duration": 0.01})", R"("duration": 0.01, "warm_start": "yes"})")) ==
        "settings.warm_start: must be true or false, got string");
  CHECK(LoadError(Replace(kGood, R"("duration": 0.01})",
                          R"("duration": 0.01, "experimental_eval_params": {"explicit_normals": true, "implicit_normal_force_for_dissipation": true}})")) ==
        "settings.experimental_eval_params.explicit_normals, implicit_normal_force_for_dissipation: "
        "the combination (true, true) is unsupported");
  CHECK(LoadError(Replace(kGood, R"("duration": 0.01})",
                          R"("duration": 0.01, "solver": {"linear_solver": "cg"}})")) ==
        "settings.solver.linear_solver: unknown value \"cg\" (expected one of: auto, direct, "
        "iterative)");
  CHECK(LoadError(Replace(kGood, R"("duration": 0.01})",
                          R"("duration": 0.01, "solver": {"linear_tolerance": 1}})")) ==
        "settings.solver.linear_tolerance: must be in (0, 1), got 1");
  CHECK(LoadError(Replace(kGood, R"("duration": 0.01})",
                          R"("duration": 0.01, "solver": {"linear_solver": "iterative", "linear_tolerance": 1e-6, "linear_max_iterations": 50}})")) ==
        "<loaded>");
  CHECK(LoadError("{ not json").rfind("(file): not valid JSON", 0) == 0);
  SceneFile cold;
  Error e;
  REQUIRE(LoadSceneText(Replace(kGood, R"("duration": 0.01})", R"("duration": 0.01, "warm_start": false})"),
                        ".", &cold, &e));
  CHECK_FALSE(cold.scene->Settings().warmStart);
  CHECK(cold.scene->Settings().closedFormFreeStages);
  SceneFile newton;
  REQUIRE(LoadSceneText(Replace(kGood, R"("duration": 0.01})",
                                R"("duration": 0.01, "closed_form_free_stages": false})"),
                        ".", &newton, &e));
  CHECK_FALSE(newton.scene->Settings().closedFormFreeStages);
  CHECK(LoadError(Replace(kGood, R"("duration": 0.01})",
                          R"("duration": 0.01, "closed_form_free_stages": 1})")) ==
        "settings.closed_form_free_stages: must be true or false, got number");
}

TEST_CASE("command line: bad scene files exit with code 2", "[scenes][cli]") {
  const std::string dir = std::string(SUPERDEX_BINARY_DIR) + "/cli-test-tmp";
  std::system(("mkdir -p " + dir).c_str());
  const std::string bad = dir + "/bad.json";
  std::ofstream(bad) << Replace(kGood, R"("mass": 1.0, "position": [1)", R"("mass": -2, "position": [1)");
  CHECK(RunCli("run " + bad + " --quiet") == 2);
  CHECK(RunCli("run " + dir + "/missing.json --quiet") == 2);
  const std::string good = dir + "/good.json";
  std::ofstream(good) << kGood;
  CHECK(RunCli("run " + good + " --quiet --out " + dir + "/good.jsonl") == 0);
  CHECK(RunCli("run " + good + " --quiet --integrator Euler") == 2);
  std::ifstream traj(dir + "/good.jsonl");
  std::string header;
  std::getline(traj, header);
  CHECK(header.find("\"format\":\"superdex-trajectory/1\"") != std::string::npos);
  int frames = 0;
  for (std::string line; std::getline(traj, line);) ++frames;
  CHECK(frames == 11);  // the initial state and 10 steps
  std::system(("rm -rf " + dir).c_str());
}

TEST_CASE("shipped scenes meet their expectations", "[scenes][shipped]") {
  for (const char* name : {"drop", "box_rest", "stack", "slide_to_rest", "push"}) {
    SceneFile f;
    Error e;
    REQUIRE(LoadSceneFile(std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/" + name + ".json", &f, &e));
    RunOptions o;
    o.out = "";
    RunSummary s;
    REQUIRE(RunScene(&f, o, &s, &e));
    INFO(name << ": max penetration " << s.maxPenetration);
    for (const auto& msg : s.expectationFailures) FAIL_CHECK(name << ": " << msg);
    CHECK(s.stopped + s.diverged == 0);
  }
}

TEST_CASE("shipped soft scenes meet their expectations, no tet inverts", "[scenes][shipped][soft]") {
  for (const char* name : {"soft_ball_drop", "soft_cube_press", "soft_cylinder_on_blocks"}) {
    SceneFile f;
    Error e;
    REQUIRE(LoadSceneFile(std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/" + name + ".json", &f, &e));
    RunOptions o;
    o.out = "";
    o.vtk = "";
    RunSummary s;
    REQUIRE(RunScene(&f, o, &s, &e));
    INFO(name << ": max penetration " << s.maxPenetration << ", min det F " << s.minDetF);
    for (const auto& msg : s.expectationFailures) FAIL_CHECK(name << ": " << msg);
    CHECK(s.stopped + s.diverged == 0);
    CHECK(s.minDetF > 0.5);
  }
}

TEST_CASE("the 1000-sphere pile loads and its first steps converge", "[scenes][shipped]") {
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneFile(std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/pile.json", &f, &e));
  REQUIRE(f.scene->NumActors() == 1005);
  RunOptions o;
  o.out = "";
  o.duration = 0.05;
  RunSummary s;
  REQUIRE(RunScene(&f, o, &s, &e));
  CHECK(s.stopped + s.diverged == 0);
  CHECK(s.maxPenetration < 0.01);
}

TEST_CASE("no energy gain under BackwardEuler in the dissipative shipped scenes",
          "[scenes][shipped][dissipation]") {
  // Every shipped scene but the frictionless drop is dissipative (the default μ = 0.5, plus
  // damping where set). Under
  // BackwardEuler the total energy (kinetic + gravity + penalty) must not rise by more than 1e-6
  // of its initial magnitude from one step to the next. Each scene runs for up to 1 s (the pile:
  // its first 0.05 s); the friction bound ‖T_C‖ <= μ λ̂_n is checked at every stage as well.
  for (const char* name : {"box_rest", "stack", "slide_to_rest", "incline",
                           "incline_creep", "damping_sweep", "pile"}) {
    SceneFile f;
    Error e;
    REQUIRE(LoadSceneFile(std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/" + name + ".json", &f,
                          &e));
    Scene& scene = *f.scene;
    REQUIRE(scene.HasDissipation());
    REQUIRE(scene.SetIntegrator(IntegrationMethod::BackwardEuler, &e));
    const double duration = std::string(name) == "pile" ? 0.05 : std::min(1.0, f.duration);
    const int steps = static_cast<int>(std::lround(duration / f.dt));
    double previous = scene.Energies().Total();
    const double scale = std::abs(previous);
    double worstRise = -INFINITY, worstRatio = 0.0;
    for (int i = 0; i < steps; ++i) {
      StepReport r;
      REQUIRE(scene.Step(f.dt, &r, &e));
      INFO(name << " step " << i << ": " << r.message);
      REQUIRE(r.status == StageStatus::Converged);
      const double energy = scene.Energies().Total();
      worstRise = std::max(worstRise, energy - previous);
      worstRatio = std::max(worstRatio, r.maxCoulombRatio);
      previous = energy;
    }
    INFO(name << ": largest step-to-step energy change " << worstRise << " J (initial |E| "
              << scale << " J), largest |T_C|/(mu lambda) " << worstRatio);
    CHECK(worstRise <= 1e-6 * scale);
    CHECK(worstRatio <= 1.0 + 1e-12);
  }
}

TEST_CASE("scene file: layers, parents and the contact_filter controls", "[scenes][filter]") {
  const std::string text = R"({"format": "superdex-scene/1",
    "actors": [
      {"name": "ground", "dynamic": false, "shape": {"type": "plane"}, "contact_layer": "ground"},
      {"name": "arm", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}},
      {"name": "hand", "parent": "arm", "shape": {"type": "box", "size": [0.1, 0.1, 0.1]}},
      {"name": "ghost", "shape": {"type": "sphere", "radius": 0.1}, "contact_layer": "ghosts"}],
    "contact_filter": [
      {"layers": ["ghosts", "ground"], "enable": false, "symmetric": false},
      {"actors": ["arm", "arm"], "enable": false, "include_nested": true}]})";
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneText(text, ".", &f, &e));
  const Scene& s = *f.scene;
  CHECK_FALSE(s.ContactAllowed({3}, {0}));  // ghost against ground
  CHECK(s.ContactAllowed({0}, {3}));
  CHECK_FALSE(s.ContactAllowed({1}, {2}));  // arm and hand, both ways
  CHECK_FALSE(s.ContactAllowed({2}, {1}));
  CHECK(s.ContactAllowed({1}, {3}));
  CHECK(s.ContactLayer({3}) == "ghosts");
  SceneFile bad;
  CHECK_FALSE(LoadSceneText(Replace(text, R"("actors": ["arm", "arm"])", R"("actors": ["arm", "leg"])"),
                            ".", &bad, &e));
  CHECK(e.message == "contact_filter[1].actors[1]: no actor named \"leg\"");
  CHECK_FALSE(LoadSceneText(Replace(text, R"("parent": "arm")", R"("parent": "hand")"), ".", &bad, &e));
  CHECK(e.message == "actors[2].parent: no earlier actor named \"hand\"");
}

TEST_CASE("scene file: an open mesh used as a collider names the file and the defect",
          "[scenes][mesh]") {
  const std::string dir = std::string(SUPERDEX_BINARY_DIR);
  const std::string open = dir + "/open_tet.obj";
  std::ofstream(open) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n";
  const std::string closed = dir + "/closed_tet.obj";
  std::ofstream(closed) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  auto text = [](const std::string& file, const std::string& collider) {
    return R"({"format": "superdex-scene/1", "actors": [{"name": "rock", "dynamic": false,
      "shape": {"type": "mesh", "file": ")" + file + R"("}, "collider_type": ")" + collider + R"("}]})";
  };
  SceneFile f;
  Error e;
  CHECK_FALSE(LoadSceneText(text(open, "Auto"), ".", &f, &e));
  CHECK(e.message.rfind("actors[0].shape.mesh: not closed (boundary edge", 0) == 0);
  CHECK(e.message.find("in " + open + "; collider_type Sdf needs a closed") != std::string::npos);
  REQUIRE(LoadSceneText(text(closed, "Auto"), ".", &f, &e));
  CHECK(f.scene->Model({0}).collider.type == ColliderType::Sdf);
  REQUIRE(LoadSceneText(text(closed, "Mesh"), ".", &f, &e));
  CHECK(f.scene->Model({0}).collider.type == ColliderType::Mesh);
  // The grid's size and memory are reported.
  bool reported = false;
  REQUIRE(LoadSceneText(text(closed, "Sdf"), ".", &f, &e));
  for (const auto& n : f.scene->Notices()) reported |= n.find("MiB") != std::string::npos;
  CHECK(reported);
}

TEST_CASE("docs/parameters.md is the output of superdex params --markdown", "[scenes][docs]") {
  std::ostringstream generated;
  PrintParameterMarkdown(generated);
  std::ifstream in(std::string(SUPERDEX_SOURCE_DIR) + "/docs/parameters.md");
  REQUIRE(in);
  std::stringstream file;
  file << in.rdbuf();
  INFO("regenerate it: superdex params --markdown > docs/parameters.md");
  CHECK(file.str() == generated.str());
  CHECK(RunCli("params --markdown") == 0);
}

TEST_CASE("trajectory contacts carry the per-pair totals: a resting box's is its weight",
          "[scenes][trajectory][contact_report]") {
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneFile(std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/box_rest.json", &f, &e));
  const std::string out = SUPERDEX_BINARY_DIR "/box_rest_pairs.jsonl";
  RunOptions o;
  o.out = out;
  o.contacts = true;
  RunSummary s;
  REQUIRE(RunScene(&f, o, &s, &e));
  std::ifstream in(out);
  std::string line, last;
  while (std::getline(in, line)) last = line;
  const nlohmann::json frame = nlohmann::json::parse(last);
  const nlohmann::json& totals = frame["contacts"]["pair_totals"];
  REQUIRE(totals.size() == 1);
  CHECK(totals[0]["a"] == 0);
  CHECK(totals[0]["b"] == 1);
  // On the ground (a): the 1 kg box's weight, down, at rest.
  CHECK(totals[0]["force"][2].get<double>() == Approx(-9.81).epsilon(1e-6));
  CHECK(std::abs(totals[0]["force"][0].get<double>()) < 1e-6);
  CHECK(totals[0]["area"].get<double>() == Approx(0.04).epsilon(1e-9));
  CHECK(std::abs(totals[0]["centre_of_pressure"][0].get<double>()) < 1e-6);
}

TEST_CASE("VTK contact frames: the samples' forces on a resting box sum to its weight",
          "[scenes][vtk][contact_report]") {
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneFile(std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/box_rest.json", &f, &e));
  const std::string dir = SUPERDEX_BINARY_DIR "/box_rest_vtk";
  std::system(("rm -rf " + dir).c_str());
  RunOptions o;
  o.out = "";
  o.vtk = dir;
  RunSummary s;
  REQUIRE(RunScene(&f, o, &s, &e));
  // The last frame (2 s at dt = 5 ms: step 400).
  std::ifstream in(dir + "/contacts_000400.vtk");
  REQUIRE(in);
  std::string word;
  long points = -1;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  while (in >> word) {
    if (word == "POINTS") in >> points >> word;
    if (word == "force") {
      in >> word;  // "double"
      for (long i = 0; i < points; ++i) {
        Eigen::Vector3d v;
        in >> v.x() >> v.y() >> v.z();
        sum += v;
      }
      break;
    }
  }
  REQUIRE(points > 0);
  // On the box (the colliding actor): its weight, up; written to 9 digits.
  CHECK(sum.z() == Approx(9.81).epsilon(1e-6));
  CHECK(sum.head<2>().norm() < 1e-6);
}
