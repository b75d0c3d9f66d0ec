// Checkpoints (scenes/checkpoint.h, docs/reliability.md): a run of 2N steps and a run of N steps
// that writes a checkpoint, resumed in a new scene for N more, end in the same state bit for bit
// and write the same trajectory; bad checkpoint files are refused with the field named.
#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "scenes/checkpoint.h"
#include "scenes/runner.h"

using namespace superdex;

namespace {

const std::string kData = std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/";
// Files of this test process's own (ctest runs the test cases as parallel processes).
const std::string kDir =
    std::string(SUPERDEX_BINARY_DIR) + "/checkpoint_" + std::to_string(getpid()) + "_";

std::string Read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void Load(const std::string& scene, IntegrationMethod method, SceneFile* file) {
  Error e;
  REQUIRE(LoadSceneFile(kData + scene, file, &e));
  REQUIRE(file->scene->SetIntegrator(method, &e));
}

// Runs `scene` for `steps` steps of dt (resuming from `resume` if given) with a trajectory of
// every step at `out` (the scene's output.every is set to 1) and a checkpoint every
// `checkpointEvery` steps.
void Run(SceneFile* file, double dt, long long steps, const std::string& out,
         long long checkpointEvery = 0, const Checkpoint* resume = nullptr) {
  RunOptions o;
  o.dt = dt;
  o.duration = dt * static_cast<double>(steps);
  o.out = out;
  o.checkpointEvery = checkpointEvery;
  o.checkpointPath = kDir + "state.checkpoint";
  o.resume = resume;
  file->output.every = 1;
  RunSummary summary;
  Error e;
  const bool completed = RunScene(file, o, &summary, &e);
  INFO(e.message);
  REQUIRE(completed);
  REQUIRE(summary.steps == steps);
}

// Every double of the step state, compared with ==.
void RequireSameState(const Scene::Snapshot& a, const Scene::Snapshot& b) {
  REQUIRE(a.step.time == b.step.time);
  REQUIRE(a.step.rigidStates.size() == b.step.rigidStates.size());
  auto same = [](const auto& x, const auto& y) { return (x.array() == y.array()).all(); };
  auto rigid = [&](const std::vector<RigidBodyState>& x, const std::vector<RigidBodyState>& y) {
    REQUIRE(x.size() == y.size());
    for (size_t i = 0; i < x.size(); ++i) {
      CHECK(same(x[i].p, y[i].p));
      CHECK(same(x[i].R, y[i].R));
      CHECK(same(x[i].v, y[i].v));
      CHECK(same(x[i].Rdot, y[i].Rdot));
    }
  };
  auto vector = [&](const std::vector<SoftBodyState>& x, const std::vector<SoftBodyState>& y) {
    REQUIRE(x.size() == y.size());
    for (size_t i = 0; i < x.size(); ++i) {
      REQUIRE(x[i].x.size() == y[i].x.size());
      CHECK(same(x[i].x, y[i].x));
      CHECK(same(x[i].v, y[i].v));
    }
  };
  rigid(a.step.rigidStates, b.step.rigidStates);
  vector(a.step.vectorStates, b.step.vectorStates);
  REQUIRE(a.step.rigidHistory.size() == b.step.rigidHistory.size());
  for (size_t h = 0; h < a.step.rigidHistory.size(); ++h) {
    CHECK(a.step.historyTimes[h] == b.step.historyTimes[h]);
    rigid(a.step.rigidHistory[h], b.step.rigidHistory[h]);
    vector(a.step.vectorHistory[h], b.step.vectorHistory[h]);
  }
  CHECK(a.driver.explicitFirstStages == b.driver.explicitFirstStages);
  CHECK(a.driver.explicitFirstRun == b.driver.explicitFirstRun);
  CHECK(a.driver.lastPotentialIterations == b.driver.lastPotentialIterations);
  CHECK(a.driver.lastStageInContact == b.driver.lastStageInContact);
}

// The trajectory's lines as JSON without the one field that may differ (wall_seconds).
std::vector<nlohmann::json> Frames(const std::string& path) {
  std::vector<nlohmann::json> frames;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    nlohmann::json j = nlohmann::json::parse(line);
    if (j.contains("stats")) j["stats"].erase("wall_seconds");
    frames.push_back(j);
  }
  return frames;
}

// Run 2N steps straight; run N with a checkpoint, resume it in a new scene and run N more.
void CheckResume(const std::string& scene, IntegrationMethod method, double dt, long long n) {
  INFO(scene << " " << ToString(method) << ", N = " << n);
  const std::string straight = kDir + "straight.jsonl", resumed = kDir + "resumed.jsonl";
  SceneFile a;
  Load(scene, method, &a);
  Run(&a, dt, 2 * n, straight);

  SceneFile b;
  Load(scene, method, &b);
  Run(&b, dt, n, resumed, n);
  Checkpoint c;
  Error e;
  REQUIRE(ReadCheckpoint(kDir + "state.checkpoint", &c, &e));
  CHECK(c.run.step == n);
  SceneFile resumedFile;  // a new scene, as `superdex run --resume` loads it
  Load(scene, method, &resumedFile);
  REQUIRE(CheckpointFits(c, "state.checkpoint", *resumedFile.scene, resumedFile.textHash, dt, &e));
  Run(&resumedFile, dt, 2 * n, resumed, 0, &c);

  RequireSameState(a.scene->Save(), resumedFile.scene->Save());
  const std::vector<nlohmann::json> x = Frames(straight), y = Frames(resumed);
  REQUIRE(x.size() == static_cast<size_t>(2 * n + 2));  // header, step 0 … 2N
  REQUIRE(y.size() == x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    INFO("trajectory line " << i + 1);
    CHECK(x[i] == y[i]);
  }
}

}  // namespace

TEST_CASE("checkpoint: a resumed rigid run equals the uninterrupted one bit for bit",
          "[scenes][checkpoint]") {
  for (IntegrationMethod m : {IntegrationMethod::BDF2, IntegrationMethod::BDF3}) {
    // The ball falls (closed-form free stages, warm starts) and lands after the checkpoint.
    CheckResume("drop.json", m, 0.005, 60);
    CheckResume("stack.json", m, 0.005, 20);  // ten boxes in contact from the start
  }
}

TEST_CASE("checkpoint: a resumed soft run equals the uninterrupted one bit for bit",
          "[scenes][checkpoint]") {
  for (IntegrationMethod m : {IntegrationMethod::BDF2, IntegrationMethod::BDF3})
    CheckResume("soft_cube_press.json", m, 0.01, 8);  // the box presses into the cube
}

TEST_CASE("checkpoint: exact doubles, atomic write", "[scenes][checkpoint]") {
  SceneFile file;
  Load("tumble.json", IntegrationMethod::BDF3, &file);
  Run(&file, 0.01, 3, "", 3);
  CHECK(Read(kDir + "state.checkpoint.part").empty());  // renamed, not left behind
  Checkpoint c;
  Error e;
  REQUIRE(ReadCheckpoint(kDir + "state.checkpoint", &c, &e));
  RequireSameState(c.snapshot, file.scene->Save());
  CHECK(c.snapshot.step.rigidHistory.size() == 2);  // BDF3's two past states
  CHECK(c.sceneHash == file.textHash);
  CHECK(c.run.integrator == "BDF3");
  Error w;
  CHECK_FALSE(WriteCheckpoint("/proc/nonexistent/x.checkpoint", c, &w));
  CHECK(w.message.find("checkpoint: writing \"/proc/nonexistent/x.checkpoint\" failed: ") == 0);
}

TEST_CASE("checkpoint: bad checkpoint files are refused with the field named",
          "[scenes][checkpoint][bad_input]") {
  SceneFile file;
  Load("drop.json", IntegrationMethod::BDF2, &file);
  Run(&file, 0.005, 4, "", 4);
  const std::string path = kDir + "state.checkpoint";
  const std::string good = Read(path);
  auto error = [&](const std::string& text) {
    const std::string bad = kDir + "bad.checkpoint";
    std::ofstream(bad, std::ios::binary) << text;
    Checkpoint c;
    Error e;
    if (!ReadCheckpoint(bad, &c, &e)) return e.message.substr(("checkpoint " + bad + ": ").size());
    SceneFile fresh;
    Load("drop.json", IntegrationMethod::BDF2, &fresh);
    if (!CheckpointFits(c, bad, *fresh.scene, fresh.textHash, 0.005, &e))
      return e.message.substr(("checkpoint " + bad + ": ").size());
    return std::string("<fits>");
  };
  auto edited = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = nlohmann::json::parse(good);
    edit(j);
    return j.dump();
  };
  using J = nlohmann::json;
  CHECK(error(good) == "<fits>");
  CHECK(error("") == "the file is empty");
  CHECK(error(good.substr(0, good.size() / 2)).find("(the file is truncated)") != std::string::npos);
  CHECK(error(edited([](J& j) { j["version"] = 2; })) ==
        "version: 2 is not supported (this build reads version 1)");
  CHECK(error(edited([](J& j) { j["format"] = "x"; })) ==
        "format: \"x\" is not \"superdex-checkpoint\"");
  CHECK(error(edited([](J& j) { j.erase("driver"); })) == "driver: missing");
  CHECK(error(edited([](J& j) { j["driver"]["last_stage_in_contact"] = 1; })) ==
        "driver.last_stage_in_contact: must be true or false");
  CHECK(error(edited([](J& j) { j["run"]["step"] = -1; })) == "run.step: out of range: -1");
  CHECK(error(edited([](J& j) { j["rigid"][0].push_back("0x1p+0"); })) ==
        "rigid[0]: needs 24 numbers (p, R, v, dR/dt), got 25");
  CHECK(error(edited([](J& j) { j["history"][0]["rigid"][1][3] = 1.0; })) ==
        "history[0].rigid[1][3]: must be a hex float string, got number");
  CHECK(error(edited([](J& j) { j["time"] = "z0x1p+0"; })) == "time: \"z0x1p+0\" is not a number");
  CHECK(error(edited([](J& j) { j["history"].push_back(j["history"][0]); })) ==
        "history: holds at most 2 states, got 3");
  CHECK(error(edited([](J& j) { j["scene_hash"] = "fnv1a64:xyz"; })) ==
        "scene_hash: \"fnv1a64:xyz\" is not fnv1a64:<16 hex digits>");
  CHECK(error(edited([](J& j) { j["scene_hash"] = "fnv1a64:0000000000000000"; }))
            .find("scene_hash: written for the scene file \"" + kData + "drop.json\" "
                  "(fnv1a64:0000000000000000); this scene file's text has fnv1a64:") == 0);
  CHECK(error(edited([](J& j) { j["run"]["integrator"] = "BDF3"; })) ==
        "run.integrator: written with BDF3, resumed with BDF2 (give the same --integrator)");
  CHECK(error(edited([](J& j) { j["run"]["dt"] = "0x1p-8"; })) ==
        "run.dt: written at dt = 0x1p-8 s, resumed at 0x1.47ae147ae147bp-8 s (give the same --dt)");
  CHECK(error(edited([](J& j) { j["vector"].push_back({{"x", J::array()}, {"v", J::array()}}); })) ==
        "vector: 1 soft (and generic) actors, the scene has 0");
  CHECK(error(edited([](J& j) { j["history"][1]["rigid"].erase(0); })) ==
        "history[1].rigid: 1 rigid actors, the scene has 2");

  // Nothing left to run: the checkpoint is at the run's last step.
  Checkpoint c;
  Error e;
  REQUIRE(ReadCheckpoint(path, &c, &e));
  SceneFile again;
  Load("drop.json", IntegrationMethod::BDF2, &again);
  RunOptions o;
  o.dt = 0.005;
  o.duration = 0.02;
  o.out = "";
  o.resume = &c;
  RunSummary s;
  CHECK_FALSE(RunScene(&again, o, &s, &e));
  CHECK(s.end == RunEnd::InvalidInput);
  CHECK(e.message == "--resume: the checkpoint is at step 4 and the run has 4 steps: nothing is "
                     "left to run");
}

TEST_CASE("checkpoint: superdex run --checkpoint-every and --resume", "[scenes][checkpoint][cli]") {
  auto cli = [](const std::string& args) {
    const std::string cmd = "timeout 120 " + std::string(SUPERDEX_CLI) + " " + args + " --quiet > " +
                            kDir + "cli_out.txt 2> " + kDir + "cli_err.txt";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  const std::string scene = kData + "drop.json --dt 0.005 --integrator BDF3";
  const std::string straight = kDir + "cli_straight.jsonl", part = kDir + "cli_part.jsonl";
  const std::string checkpoint = kDir + "cli.checkpoint";
  REQUIRE(cli("run " + scene + " --duration 0.6 --out " + straight) == 0);
  // Every 7 steps: the last checkpoint is at step 56; the resumed run cuts the trajectory after
  // the frame of step 55 (output.every = 5) and writes step 60's again.
  REQUIRE(cli("run " + scene + " --duration 0.3 --out " + part + " --checkpoint-every 7 "
              "--checkpoint " + checkpoint) == 0);
  REQUIRE(cli("run " + scene + " --duration 0.6 --out " + part + " --resume " + checkpoint) == 0);
  const std::vector<nlohmann::json> x = Frames(straight), y = Frames(part);
  REQUIRE(x.size() == 26);  // header, steps 0, 5, …, 120
  REQUIRE(y.size() == x.size());
  for (size_t i = 0; i < x.size(); ++i) CHECK(x[i] == y[i]);

  // Another scene file (the same scene with another description) is refused with exit code 2.
  std::string other = Read(kData + "drop.json");
  other.replace(other.find("A 1 kg sphere"), 1, "a");
  std::ofstream(kDir + "other.json") << other;
  CHECK(cli("run " + kDir + "other.json --dt 0.005 --integrator BDF3 --duration 0.6 --out " + part +
            " --resume " + checkpoint) == 2);
  CHECK(Read(kDir + "cli_err.txt").find("scene_hash: written for the scene file ") !=
        std::string::npos);
  CHECK(cli("run " + scene + " --checkpoint " + checkpoint) == 2);
  CHECK(Read(kDir + "cli_err.txt") == "error: --checkpoint: needs --checkpoint-every N\n");
  CHECK(cli("run " + scene + " --checkpoint-every 0 --out " + part) == 2);
}
