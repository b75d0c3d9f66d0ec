// Bad observed trajectories and fits that cannot be computed: refused up front with the place
// and the rule, or ended with FitFailure; the reader skips a killed writer's truncated last line;
// a fit stops when asked to (regression tests for the findings of issue 38).
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include "scenes/fit.h"

using namespace superdex;

namespace {

const std::string kData = std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/";
const char* kHeader = R"({"format": "superdex-trajectory/1", "actors": [{"name": "ground"}, {"name": "box"}]})";

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = std::string(SUPERDEX_BINARY_DIR) + "/bad_fit_" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The observed trajectory of one frame at time t with the box at p.
ObservedTrajectory OneFrame(double t, const std::string& p = "[0.3, 0, 0.1]") {
  ObservedTrajectory obs;
  Error e;
  const std::string path = Write("one.jsonl", std::string(kHeader) + "\n{\"t\": " +
                                                  std::to_string(t) + ", \"actors\": [null, {\"p\": " +
                                                  p + "}]}\n");
  REQUIRE(ReadObservedTrajectory(path, &obs, &e));
  obs.frames[0].time = t;  // exactly, not its decimal text
  return obs;
}

struct Gradient {
  bool ok;
  FitFailure failure;
  std::string error;
};

Gradient GradientOf(const ObservedTrajectory& obs) {
  SceneFile file;
  Error e;
  REQUIRE(LoadSceneFile(kData + "fit_throw.json", &file, &e));
  FitOptions o;
  o.parameters = {"box.coulomb_friction_coefficient"};
  TrajectoryGradient g;
  Gradient out;
  out.ok = ComputeTrajectoryGradient(file, obs, o, &g, &e, &out.failure);
  out.error = e.message;
  return out;
}

}  // namespace

TEST_CASE("bad input: observed times beyond the step limit", "[scenes][bad_input][fit]") {
  // t = 1e7 (also 1e300, 4294967.296) used to crash `gradient` (SIGSEGV) and make `fit` print
  // uninitialized values: the step index (int) round(t / dt) was not range-checked.
  for (double t : {1e7, 1e300, 4294967.296}) {
    const Gradient g = GradientOf(OneFrame(t));
    CHECK_FALSE(g.ok);
    CHECK(g.failure == FitFailure::Input);
    CHECK(g.error.rfind("observed frame 0: t = ", 0) == 0);
    CHECK(g.error.find("beyond the limit of 1e+06 steps per fit") != std::string::npos);
  }
  SceneFile file;
  Error e;
  REQUIRE(LoadSceneFile(kData + "fit_throw.json", &file, &e));
  FitOptions o;
  o.parameters = {"box.coulomb_friction_coefficient"};
  FitResult r;
  FitFailure failure;
  CHECK_FALSE(FitSceneParameters(file, OneFrame(1e7), o, &r, &e, &failure));
  CHECK(failure == FitFailure::Input);
  o.dt = 0.0;
  CHECK_FALSE(FitSceneParameters(file, OneFrame(0.02), o, &r, &e, &failure));
  CHECK(e.message == "dt: must be > 0 and finite, got 0");
}

TEST_CASE("bad input: a cost that is not finite", "[scenes][bad_input][fit]") {
  // p = 1e308 printed nan gradients and cost inf at exit code 0.
  const Gradient g = GradientOf(OneFrame(0.02, "[1e308, 0, 0.1]"));
  CHECK_FALSE(g.ok);
  CHECK(g.failure == FitFailure::NonFinite);
  CHECK(g.error == "the cost (inf m^2) or its gradient is not finite: the simulated or observed "
                   "positions, or the parameter values, are beyond double precision");
}

TEST_CASE("bad input: observed trajectory files", "[scenes][bad_input][fit]") {
  ObservedTrajectory obs;
  Error e;
  // A killed writer's last line: reported and skipped.
  const std::string truncated = Write("truncated.jsonl", std::string(kHeader) +
      "\n{\"t\": 0.0, \"actors\": [null, {\"p\": [0, 0, 0.12]}]}\n{\"t\": 0.02, \"actors\": [nu");
  REQUIRE(ReadObservedTrajectory(truncated, &obs, &e));
  CHECK(obs.frames.size() == 1);
  REQUIRE(obs.notes.size() == 1);
  CHECK(obs.notes[0] == truncated + ":3: the last line is truncated (no newline, not valid JSON): "
                                    "skipped");
  // The same line with its newline is an error, with its place.
  const std::string broken = Write("broken.jsonl", std::string(kHeader) +
      "\n{\"t\": 0.02, \"actors\": [nu\n{\"t\": 0.04, \"actors\": [null, null]}\n");
  CHECK_FALSE(ReadObservedTrajectory(broken, &obs, &e));
  CHECK(e.message.rfind(broken + ":2: not valid JSON: ", 0) == 0);
  const std::string overflow = Write("overflow.jsonl", std::string(kHeader) +
      "\n{\"t\": 0.02, \"actors\": [null, {\"p\": [0, 1e999, 0]}]}\n");
  CHECK_FALSE(ReadObservedTrajectory(overflow, &obs, &e));
  CHECK(e.message == overflow + ":2: actors[1].p[1]: number 1e999 is out of range (line 1, "
                                "column 40)");
  const std::string scalar = Write("scalar.jsonl", std::string(kHeader) + "\n42\n");
  CHECK_FALSE(ReadObservedTrajectory(scalar, &obs, &e));
  CHECK(e.message == scalar + ":2: a frame needs a number \"t\" [s]");
}

TEST_CASE("fit: stopped after an iteration, the values written whole", "[scenes][fit]") {
  SceneFile file;
  Error e;
  REQUIRE(LoadSceneFile(kData + "fit_throw.json", &file, &e));
  ObservedTrajectory obs;
  REQUIRE(ReadObservedTrajectory(kData + "fit_throw_observed.jsonl", &obs, &e));
  FitOptions o;
  o.parameters = {"box.coulomb_friction_coefficient"};
  int calls = 0;
  o.iteration = [&](const FitProgress& p) {
    CHECK(p.iteration == calls);
    CHECK(std::isfinite(p.cost));
    return ++calls < 2;  // stop after iteration 1
  };
  FitResult r;
  REQUIRE(FitSceneParameters(file, obs, o, &r, &e));
  CHECK(r.interrupted);
  CHECK_FALSE(r.converged);
  CHECK(r.iterations == 1);
  const std::string path = std::string(SUPERDEX_BINARY_DIR) + "/bad_fit_out.json";
  REQUIRE(WriteFitJson(path, r, "interrupted", &e));
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text.find("\"status\": \"interrupted\"") != std::string::npos);
  CHECK(text.back() == '\n');
  CHECK_FALSE(WriteFitJson("/proc/nope/x.json", r, "done", &e));
  CHECK(e.message == "--out: cannot write \"/proc/nope/x.json\": No such file or directory");
}
