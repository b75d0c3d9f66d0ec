// The command line's exit codes and messages for bad input, unphysical runs, failed writes and
// signals (docs/reliability.md); each reproducer of issue 38 that ended in a crash, a hang or
// exit code 0 now ends with its documented code and a message naming the place.
#include <catch2/catch.hpp>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

using namespace std::chrono_literals;

namespace {

const std::string kData = std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/";
const std::string kDir = std::string(SUPERDEX_BINARY_DIR) + "/cli_failures_";

std::string Read(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string Write(const std::string& name, const std::string& text) {
  std::ofstream(kDir + name, std::ios::binary) << text;
  return kDir + name;
}

struct Result {
  int code = -1;
  std::string out, err;
};

// Runs `superdex ARGS` under a 60 s timeout (a hang fails as code 124). Its output goes to files
// of this test process's own (ctest runs the test cases as parallel processes).
Result Cli(const std::string& args) {
  const std::string own = kDir + std::to_string(getpid()) + "_";
  const std::string cmd = "timeout 60 " + std::string(SUPERDEX_CLI) + " " + args + " > " + own +
                          "out.txt 2> " + own + "err.txt";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, Read(own + "out.txt"),
          Read(own + "err.txt")};
}

std::string Observed(const std::string& name, const std::string& frame) {
  return Write(name, R"({"format": "superdex-trajectory/1", "actors": [{"name": "ground"}, {"name": "box"}]})"
                     "\n" + frame + "\n");
}

const std::string kFit = "fit " + kData + "fit_throw.json --params box.coulomb_friction_coefficient";
const std::string kGradient =
    "gradient " + kData + "fit_throw.json --params box.coulomb_friction_coefficient";

// Starts `superdex run` on a long scene, sends `signal` once its trajectory has 5 frames, and
// returns the exit code (−1 if it did not end within 60 s of the signal).
int InterruptRun(int signal, const std::string& traj, const std::string& vtk) {
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    const int out = open((kDir + "sig_out.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open((kDir + "sig_err.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, 1);
    dup2(err, 2);
    execl(SUPERDEX_CLI, SUPERDEX_CLI, "run", (kData + "soft_ball_drop.json").c_str(),
          "--duration", "1000", "--quiet", "--out", traj.c_str(), "--vtk", vtk.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    const std::string text = Read(traj);
    if (std::count(text.begin(), text.end(), '\n') >= 6) break;
    std::this_thread::sleep_for(50ms);
  }
  kill(pid, signal);
  for (int i = 0; i < 1200; ++i) {
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::this_thread::sleep_for(50ms);
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

}  // namespace

TEST_CASE("command line: exit codes are in the help", "[scenes][cli][bad_input]") {
  const Result r = Cli("--help");
  CHECK(r.code == 0);
  CHECK(r.out.find("Exit codes: 0 success; 1 internal error; 2 invalid input") != std::string::npos);
  CHECK(r.out.find("130 / 143 stopped by SIGINT / SIGTERM") != std::string::npos);
}

TEST_CASE("command line: --version prints the CMake project's version", "[scenes][cli]") {
  const std::string cmake = Read(std::string(SUPERDEX_SOURCE_DIR) + "/CMakeLists.txt");
  const std::string key = "project(superdex VERSION ";
  const size_t at = cmake.find(key);
  REQUIRE(at != std::string::npos);
  const std::string version = cmake.substr(at + key.size(), cmake.find(' ', at + key.size()) -
                                                                (at + key.size()));
  const Result r = Cli("--version");
  CHECK(r.code == 0);
  CHECK(r.out == version + "\n");
}

TEST_CASE("command line: bad options and limits exit with code 2", "[scenes][cli][bad_input]") {
  Result r = Cli("run " + kData + "drop.json --quiet --duration 1e9");
  CHECK(r.code == 2);
  CHECK(r.err == "error: duration / dt: 1e+09 s / 0.0002 s = 5e+12 steps, beyond the limit of "
                 "1e+08 steps per run\n");
  r = Cli("run " + kData + "drop.json --quiet --dt 0");
  CHECK(r.code == 2);
  CHECK(r.err == "error: --dt: must be > 0 and finite, got 0\n");
  // `fit --dt 0|-1|nan` used to be ignored.
  for (const char* dt : {"0", "-1", "nan"}) {
    r = Cli(kFit + " --observed " + kData + "fit_throw_observed.jsonl --dt " + dt);
    CHECK(r.code == 2);
    CHECK(r.err == "error: --dt: must be > 0 and finite, got " + std::string(dt) + "\n");
  }
  // A frame at t = 1e7 made `gradient` crash (SIGSEGV) and `fit` exit 3 on garbage.
  const std::string far = Observed("far.jsonl", R"({"t": 10000000.0, "actors": [null, {"p": [0, 0, 0.1]}]})");
  for (const std::string& command : {kGradient, kFit}) {
    r = Cli(command + " --observed " + far);
    CHECK(r.code == 2);
    CHECK(r.err.find("error: observed frame 0: t = 1e+07 s is step 5e+09 at dt = 0.002 s, "
                     "beyond the limit of 1e+06 steps per fit") != std::string::npos);
  }
  // A surface that used to hang the mesher.
  const std::string same = Write("same.obj", "v 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\n"
                                             "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const std::string scene = Write("same.json",
      R"({"actors": [{"name": "s", "type": "soft", "mesh": {"type": "surface", "file": ")" + same +
      R"(", "edge_length": 0.3}}]})");
  r = Cli("run " + scene + " --quiet");
  CHECK(r.code == 2);
  CHECK(r.err.find("actors[0].mesh: " + same + ": MeshTetsFromSurface: the surface's vertices "
                   "all coincide") != std::string::npos);
}

TEST_CASE("command line: unphysical runs and costs exit with code 5", "[scenes][cli][bad_input]") {
  const std::string jelly = Write("jelly.json", R"({"settings": {"dt": 0.01, "duration": 1.0},
    "actors": [{"name": "ground", "dynamic": false, "shape": {"type": "plane"}},
               {"name": "jelly", "type": "soft", "material": {"youngs_modulus": 1},
                "mesh": {"type": "box", "size": [0.2, 0.2, 0.2], "cells": [2, 2, 2]},
                "position": [0, 0, 0.1]}]})");
  Result r = Cli("run " + jelly + " --quiet --out " + kDir + "jelly.jsonl");
  CHECK(r.code == 5);
  CHECK(r.out.find("RUN FAILED        step ") != std::string::npos);  // the summary is printed
  CHECK(r.err.find("a tet of soft actor 'jelly' inverted") != std::string::npos);
  const std::string far = Observed("p308.jsonl", R"({"t": 0.02, "actors": [null, {"p": [1e308, 0, 0.1]}]})");
  r = Cli(kGradient + " --observed " + far);
  CHECK(r.code == 5);
  CHECK(r.err.find("error: the cost (inf m^2) or its gradient is not finite") != std::string::npos);
}

TEST_CASE("command line: failed writes exit with code 6", "[scenes][cli][bad_input]") {
  Result r = Cli("run " + kData + "drop.json --quiet --out /dev/full");
  CHECK(r.code == 6);
  CHECK(r.err == "error: output.path: writing \"/dev/full\" failed: No space left on device\n");
  // `fit --out /proc/nope/x.json` exited 0 without writing; now it fails before fitting.
  r = Cli(kFit + " --observed " + kData + "fit_throw_observed.jsonl --out /proc/nope/x.json");
  CHECK(r.code == 6);
  CHECK(r.err == "error: --out: cannot write \"/proc/nope/x.json\": No such file or directory\n");
  CHECK(r.out.empty());
}

TEST_CASE("command line: a truncated last line of an observed trajectory is skipped",
          "[scenes][cli]") {
  const std::string text = Read(kData + "fit_throw_observed.jsonl");
  const std::string path = Write("truncated.jsonl", text + R"({"t": 0.42, "actors": [null, {"p": [0.3)");
  const Result r = Cli(kGradient + " --observed " + path);
  CHECK(r.code == 0);
  CHECK(r.err == "note: " + path + ":23: the last line is truncated (no newline, not valid "
                                   "JSON): skipped\n");
  CHECK(r.out.find("over 63 residuals, 200 steps") != std::string::npos);
}

TEST_CASE("command line: SIGINT and SIGTERM finish the step, the files and the summary",
          "[scenes][cli][signal]") {
  for (const int signal : {SIGINT, SIGTERM}) {
    INFO("signal " << signal);
    const std::string traj = kDir + "sig.jsonl", vtk = kDir + "sig_vtk";
    std::remove(traj.c_str());
    std::system(("rm -rf " + vtk).c_str());
    CHECK(InterruptRun(signal, traj, vtk) == 128 + signal);
    const std::string text = Read(traj);
    REQUIRE(!text.empty());
    CHECK(text.back() == '\n');
    const size_t lastStart = text.rfind('\n', text.size() - 2) + 1;
    const std::string last = text.substr(lastStart);
    const size_t at = last.find("\"step\":");
    REQUIRE(at != std::string::npos);
    const long step = std::atol(last.c_str() + at + 7);
    CHECK(step > 0);
    // The interrupted step's VTK frame is complete (renamed into place), none is partial.
    char name[40];
    std::snprintf(name, sizeof name, "/frame_%06ld.vtk", step);
    const std::string frame = Read(vtk + name);
    CHECK(frame.find("POINT_DATA") != std::string::npos);
    CHECK(frame.back() == '\n');
    const std::string out = Read(kDir + "sig_out.txt");
    CHECK(out.find("INTERRUPTED       stopped by signal " + std::to_string(signal) +
                   " after step " + std::to_string(step) + " of 200000") != std::string::npos);
    CHECK(out.find("expectations      not checked (the run ended early)") != std::string::npos);
  }
}

TEST_CASE("command line: the viewer page skips a truncated last line and is written whole",
          "[scenes][cli][bad_input]") {
  const std::string traj = kDir + "view.jsonl";
  REQUIRE(Cli("run " + kData + "drop.json --quiet --duration 0.01 --out " + traj).code == 0);
  std::ofstream(traj, std::ios::app) << R"({"t": 0.0102, "actors": [{"p": [0, 0)";
  Result r = Cli("view " + traj + " --out " + kDir + "view.html");
  CHECK(r.code == 0);
  CHECK(r.err.find(traj + ":") != std::string::npos);
  CHECK(r.err.find(": the last line is truncated (no newline, not valid JSON): skipped\n") !=
        std::string::npos);
  CHECK(Read(kDir + "view.html").find("</html>") != std::string::npos);
  r = Cli("view " + traj + " --out /proc/nope/view.html");
  CHECK(r.code == 6);
  CHECK(r.err == "error: view: cannot write \"/proc/nope/view.html\": No such file or "
                 "directory\n");
}
