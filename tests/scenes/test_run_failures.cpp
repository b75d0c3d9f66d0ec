// Runs that used to end at exit code 0 with wrong results: too many steps (the count wrapped),
// non-finite initial states, inverted soft tets, deep penetration and failed writes now end
// with RunEnd and a message that says what, where and why (scenes/run_checks.h).
#include <catch2/catch.hpp>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>

#include "scene_text.h"
#include "scenes/runner.h"

using namespace superdex;

namespace {

const char* kDrop = R"({"settings": {"dt": 0.01, "duration": 1.0},
  "actors": [{"name": "ground", "dynamic": false, "shape": {"type": "plane"}},
             {"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1,
              "position": [0, 0, 0.5], "velocity": [0, 0, 0]}]})";

using test::Replace;

struct Outcome {
  bool completed = false;
  RunSummary summary;
  std::string error;
};

Outcome Run(const std::string& text, RunOptions options = RunOptions()) {
  SceneFile file;
  Error e;
  REQUIRE(LoadSceneText(text, ".", &file, &e));
  if (!options.out) options.out = "";
  Outcome o;
  o.completed = RunScene(&file, options, &o.summary, &e);
  o.error = e.message;
  return o;
}

}  // namespace

TEST_CASE("run failures: step counts beyond the limit, computed without wrapping",
          "[scenes][bad_input][run]") {
  // These ran 1 step at exit code 0, or planned 1410065408 steps instead of 1e10.
  for (const auto& [duration, dt, steps] :
       {std::tuple{4294967.296, 0.001, "4.29497e+09"}, std::tuple{2147483.648, 0.001, "2.14748e+09"},
        std::tuple{1e9, 0.001, "1e+12"}, std::tuple{1e308, 0.001, "inf"},
        std::tuple{0.01, 1e-12, "1e+10"}}) {
    RunOptions o;
    o.duration = duration;
    o.dt = dt;
    const Outcome r = Run(kDrop, o);
    CHECK_FALSE(r.completed);
    CHECK(r.summary.end == RunEnd::InvalidInput);
    CHECK(r.summary.steps == 0);
    CHECK(r.error.find(std::string(" = ") + steps + " steps, beyond the limit of 1e+08 steps "
                                                    "per run") != std::string::npos);
  }
  long long steps = 0;
  std::string why;
  REQUIRE(PlanSteps(2.0, 1e-3, &steps, &why));
  CHECK(steps == 2000);
}

TEST_CASE("run failures: a state that is not finite at the start", "[scenes][bad_input][run]") {
  // A velocity of 1e308 wrote null energies at exit code 0.
  const Outcome r = Run(Replace(kDrop, "\"velocity\": [0, 0, 0]", "\"velocity\": [0, 0, 1e308]"));
  CHECK(r.summary.end == RunEnd::InvalidInput);
  CHECK(r.error == "at t = 0: the kinetic energy of actor 'ball' is not finite (its velocity is "
                   "beyond double precision)");
  const Outcome g = Run(Replace(Replace(kDrop, "\"duration\": 1.0", "\"gravity\": [0, 0, -1e308]"),
                                "[0, 0, 0.5]", "[0, 0, 5]"));
  CHECK(g.summary.end == RunEnd::InvalidInput);
  CHECK(g.error.find("the gravity energy of actor 'ball' is not finite") != std::string::npos);
}

TEST_CASE("run failures: inverted soft tets end the run", "[scenes][bad_input][run]") {
  // Soft actors with E = 1 Pa inverted (min det F −17) and the run exited 0.
  const Outcome r = Run(R"({"settings": {"dt": 0.01, "duration": 1.0},
    "actors": [{"name": "ground", "dynamic": false, "shape": {"type": "plane"}},
               {"name": "jelly", "type": "soft", "material": {"youngs_modulus": 1},
                "mesh": {"type": "box", "size": [0.2, 0.2, 0.2], "cells": [2, 2, 2]},
                "position": [0, 0, 0.1]}]})");
  CHECK_FALSE(r.completed);
  CHECK(r.summary.end == RunEnd::Unphysical);
  CHECK(r.summary.steps < 100);
  CHECK(r.summary.endMessage.find("a tet of soft actor 'jelly' inverted (min det F = -") !=
        std::string::npos);
  CHECK(r.summary.endMessage.find("raise material.youngs_modulus") != std::string::npos);
}

TEST_CASE("run failures: penetration beyond its bound ends the run", "[scenes][bad_input][run]") {
  // Boxes of 1e-9, 1e-9 and 1e6 kg converged with 429 mm of penetration at exit code 0.
  const std::string stack = R"({"settings": {"dt": 0.01, "duration": 1.0},
    "actors": [{"name": "ground", "dynamic": false, "shape": {"type": "plane"}},
      {"name": "b1", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 1e-9, "position": [0, 0, 0.1]},
      {"name": "b2", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 1e-9, "position": [0, 0, 0.3]},
      {"name": "b3", "shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "mass": 1e6, "position": [0, 0, 0.5]}]})";
  const Outcome r = Run(stack);
  CHECK(r.summary.end == RunEnd::Unphysical);
  CHECK(r.summary.endMessage.find("exceeds the bound 100 mm (the smallest half extent of the "
                                  "actors, of 'b1')") != std::string::npos);
  CHECK(r.summary.endMessage.find("raise contact.penalty_coefficient") != std::string::npos);
  CHECK(r.summary.maxPenetration > 0.1);
  // The bound is the scene's to set: a small one stops the drop at its first contact.
  const Outcome bounded =
      Run(Replace(kDrop, "\"duration\": 1.0", "\"duration\": 1.0, \"penetration_bound\": 1e-4"));
  CHECK(bounded.summary.end == RunEnd::Unphysical);
  CHECK(bounded.summary.endMessage.find("exceeds the bound 0.1 mm (settings.penetration_bound)") !=
        std::string::npos);
}

TEST_CASE("run failures: a write that fails ends the run", "[scenes][bad_input][run]") {
  // run --out /dev/full exited 0 although every write failed.
  RunOptions o;
  o.out = "/dev/full";
  const Outcome r = Run(kDrop, o);
  CHECK(r.summary.end == RunEnd::OutputFailed);
  CHECK(r.error == "output.path: writing \"/dev/full\" failed: No space left on device");
  o.out = "/proc/nope/x.jsonl";
  const Outcome n = Run(kDrop, o);
  CHECK(n.summary.end == RunEnd::OutputFailed);
  CHECK(n.error.rfind("output.path: cannot write \"/proc/nope/x.jsonl\": ", 0) == 0);
  RunOptions v;
  v.vtk = "/proc/nope";
  const Outcome w = Run(kDrop, v);
  CHECK(w.summary.end == RunEnd::OutputFailed);
  CHECK(w.error.rfind("vtk: cannot write \"/proc/nope/frame_000000.vtk\": ", 0) == 0);
}

TEST_CASE("run failures: an interruption ends the run after the current step",
          "[scenes][run]") {
  const std::string path = std::string(SUPERDEX_BINARY_DIR) + "/interrupted.jsonl";
  RunOptions o;
  o.out = path;
  int polls = 0;
  o.interrupted = [&] { return ++polls == 7 ? 2 : 0; };
  const Outcome r = Run(kDrop, o);
  CHECK(r.summary.end == RunEnd::Interrupted);
  CHECK(r.summary.signal == 2);
  CHECK(r.summary.steps == 7);
  CHECK(r.summary.endMessage == "stopped by signal 2 after step 7 of 100 (t = 0.07 s); its frame "
                                "is written");
  // The file ends with the interrupted step's frame and a newline.
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE(!text.empty());
  CHECK(text.back() == '\n');
  const size_t last = text.rfind('\n', text.size() - 2);
  CHECK(text.find("\"step\":7", last) != std::string::npos);
}
