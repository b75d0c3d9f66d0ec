// The trajectory's viewer fields (shapes, soft surfaces, contact samples) and the viewer page
// built from them (scenes/viewer_page.h); the page in a browser: tests/viewer/.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

#include "scenes/runner.h"
#include "scenes/scene_file.h"
#include "scenes/viewer_page.h"

using namespace superdex;
using json = nlohmann::json;

namespace {

// A plane, a sphere, a box, a mesh (a tetrahedron from an OBJ file) and a soft cube resting on
// the plane; the cube's name needs escaping inside the page.
const char* kScene = R"({
  "format": "superdex-scene/1",
  "settings": {"dt": 0.005, "duration": 0.05},
  "actors": [
    {"name": "ground", "dynamic": false, "shape": {"type": "plane"}},
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1.0,
     "position": [0, 0, 0.0995]},
    {"name": "crate", "shape": {"type": "box", "half_extents": [0.1, 0.2, 0.3]}, "mass": 1.0,
     "position": [1, 0, 1]},
    {"name": "tet", "shape": {"type": "mesh", "file": "tet.obj"}, "mass": 1.0,
     "position": [-1, 0, 1]},
    {"name": "</script><!--cube", "type": "soft",
     "mesh": {"type": "box", "size": [0.2, 0.2, 0.2], "cells": [2, 2, 2]},
     "material": {"youngs_modulus": 1e5, "poisson_ratio": 0.3, "density": 1000},
     "position": [0, 1, 0.0995]}
  ]
})";

std::string Dir() {
  const std::string dir = std::string(SUPERDEX_BINARY_DIR) + "/viewer-page-test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/tet.obj") << "v 0 0 0\nv 0.2 0 0\nv 0 0.2 0\nv 0 0 0.2\n"
                                     "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  return dir;
}

// Runs kScene, writing the trajectory (and the page with view); returns the trajectory's lines.
std::vector<json> RunScene(const std::string& traj, bool contacts, bool view, SceneFile* file) {
  Error e;
  REQUIRE(LoadSceneText(kScene, Dir(), file, &e));
  RunOptions o;
  o.out = traj;
  o.contacts = contacts;
  o.view = view;
  RunSummary s;
  REQUIRE(RunScene(file, o, &s, &e));
  CHECK(s.viewerPage == (view ? ViewerPagePath(traj) : std::string()));
  std::ifstream in(traj);
  std::vector<json> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(json::parse(line));
  return lines;
}

std::string Read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The page's embedded data.
json PageData(const std::string& page) {
  const std::string open = "<script type=\"application/json\" id=\"superdex-data\">";
  const size_t begin = page.find(open);
  REQUIRE(begin != std::string::npos);
  const size_t end = page.find("</script>", begin);
  return json::parse(page.substr(begin + open.size(), end - begin - open.size()));
}

std::vector<float> DecodeFloats(const std::string& text) {
  std::vector<unsigned char> bytes;
  uint32_t bits = 0;
  int count = 0;
  for (char c : text) {
    const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const char* at = std::strchr(digits, c);
    if (c == '=' || !at) break;
    bits = (bits << 6) | uint32_t(at - digits);
    if ((count += 6) >= 8) bytes.push_back(static_cast<unsigned char>(bits >> (count -= 8)));
  }
  std::vector<float> out(bytes.size() / 4);
  std::memcpy(out.data(), bytes.data(), 4 * out.size());
  return out;
}

int RunCli(const std::string& args) {
  const int status = std::system((std::string(SUPERDEX_CLI) + " " + args + " > /dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("trajectory: the header carries every actor's shape and soft surface", "[scenes][viewer]") {
  SceneFile file;
  const std::vector<json> lines = RunScene(Dir() + "/shapes.jsonl", false, false, &file);
  const json& actors = lines[0]["actors"];
  CHECK(actors[0]["shape"] == json({{"type", "plane"}, {"normal", {0.0, 0.0, 1.0}}}));
  CHECK(actors[1]["shape"] == json({{"type", "sphere"}, {"radius", 0.1}}));
  CHECK(actors[2]["shape"]["half_extents"] == json({0.1, 0.2, 0.3}));
  const json& tet = actors[3]["shape"];
  CHECK(tet["faces"].size() == 12);
  REQUIRE(tet["vertices"].size() == 12);
  // Body-frame vertices: their mean is the centre of mass of the solid tetrahedron, the origin.
  for (int k = 0; k < 3; ++k) {
    double mean = 0;
    for (int v = 0; v < 4; ++v) mean += tet["vertices"][3 * v + k].get<double>() / 4;
    CHECK(std::abs(mean) < 1e-6);
  }
  const json& surface = actors[4]["surface"];
  const SoftBodyModel& cube = file.scene->SoftModel({4});
  CHECK(surface["faces"].size() == 3 * cube.faces.size());
  CHECK(surface["nodes"].size() == 26);  // a 3 × 3 × 3 grid of nodes less its centre
  CHECK_FALSE(lines[0]["contacts"].get<bool>());
  for (size_t f = 1; f < lines.size(); ++f) CHECK_FALSE(lines[f].contains("contacts"));
  // The last frame's soft surface is the nodes' final positions (to single precision).
  const json& last = lines.back()["actors"][4]["surface"];
  REQUIRE(last.size() == 3 * surface["nodes"].size());
  const Eigen::VectorXd& x = file.scene->SoftState({4}).x;
  double worst = 0;
  for (size_t n = 0; n < surface["nodes"].size(); ++n)
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::abs(last[3 * n + k].get<double>() -
                                       x[3 * surface["nodes"][n].get<int>() + k]));
  CHECK(worst < 1e-6);
}

TEST_CASE("trajectory: contact samples in the frames when asked for", "[scenes][viewer]") {
  SceneFile file;
  const std::vector<json> lines = RunScene(Dir() + "/contacts.jsonl", true, false, &file);
  CHECK(lines[0]["contacts"].get<bool>());
  const json& c = lines.back()["contacts"];
  const std::vector<ContactSampleRecord> samples = file.scene->ContactSamples();
  REQUIRE(c["count"].get<size_t>() == samples.size());
  REQUIRE(samples.size() > 0);  // the ball and the cube rest on the plane
  CHECK(c["p"].size() == 3 * samples.size());
  CHECK(c["f"].size() == 3 * samples.size());
  CHECK(c["pairs"].size() == 2 * samples.size());
  // The scene's own samples at the frame's state, in the same order, to single precision.
  for (size_t s = 0; s < samples.size(); ++s) {
    const ContactSampleRecord& r = samples[s];
    CHECK(c["pairs"][2 * s] == r.colliding);
    CHECK(c["pairs"][2 * s + 1] == r.collider);
    CHECK(c["tn"][s].get<double>() == Approx(r.traction.dot(r.normal)).epsilon(1e-6));
    CHECK(c["tn"][s].get<double>() >= 0);  // 0: a sample with the step's dissipation only
    const Eigen::Vector3d force = r.weight * (r.traction + r.friction + r.damping);
    for (int k = 0; k < 3; ++k) {
      CHECK(c["p"][3 * s + k].get<double>() == Approx(r.position[k]).margin(1e-6));
      CHECK(c["f"][3 * s + k].get<double>() == Approx(force[k]).epsilon(1e-6).margin(1e-9));
    }
  }
}

TEST_CASE("viewer page: run --view writes it; the data is the trajectory's", "[scenes][viewer]") {
  SceneFile file;
  const std::string traj = Dir() + "/page.jsonl";
  const std::vector<json> lines = RunScene(traj, true, true, &file);
  const std::string page = Read(Dir() + "/page.html");
  // The actor's name cannot end the data's <script> element or open a comment.
  CHECK(page.find("</script><!--cube") == std::string::npos);
  CHECK(page.find("three.js") != std::string::npos);        // the vendored library
  CHECK(page.find("OrbitControls") != std::string::npos);
  const json data = PageData(page);
  CHECK(data["actors"][4]["name"] == "</script><!--cube");
  REQUIRE(data["frames"].size() == lines.size() - 1);
  CHECK(data["times"].back() == lines.back()["t"]);
  CHECK(data["energy"]["total"].back() == lines.back()["energy"]["total"]);
  const std::vector<float> pose = DecodeFloats(data["frames"].back()["pose"]);
  REQUIRE(pose.size() == 7 * 5);
  for (int k = 0; k < 3; ++k)
    CHECK(pose[7 * 1 + k] == Approx(lines.back()["actors"][1]["p"][k].get<double>()).margin(1e-6));
  const std::vector<float> samples = DecodeFloats(data["frames"].back()["contacts"]);
  const json& c = lines.back()["contacts"];
  REQUIRE(samples.size() == 4 * c["count"].get<size_t>());
  for (size_t s = 0; s < c["count"].get<size_t>(); ++s) {
    CHECK(samples[4 * s + 2] == Approx(c["p"][3 * s + 2].get<double>()).margin(1e-7));
    CHECK(samples[4 * s + 3] == Approx(c["tn"][s].get<double>()).epsilon(1e-6));
  }
  // One net force per touching pair (ball and cube on the ground): [point, force].
  const std::vector<float> forces = DecodeFloats(data["frames"].back()["forces"]);
  REQUIRE(forces.size() == 12);
  CHECK(data["max_pair_force"].get<double>() > 0);
  Error e;
  ViewerPageInfo info;
  REQUIRE(WriteViewerPage(traj, Dir() + "/again.html", &info, &e));
  CHECK(Read(Dir() + "/again.html") == page);
  CHECK(info.frames == static_cast<int>(lines.size()) - 1);
  CHECK(info.bytes == static_cast<long>(page.size()));
}

TEST_CASE("viewer page: bad trajectories name the line and the field", "[scenes][viewer]") {
  CHECK(ViewerPagePath("out/drop.jsonl") == "out/drop.html");
  CHECK(ViewerPagePath("run") == "run.html");
  const std::string dir = Dir();
  auto error = [&](const std::string& text) {
    std::ofstream(dir + "/bad.jsonl") << text;
    Error e;
    CHECK_FALSE(WriteViewerPage(dir + "/bad.jsonl", dir + "/bad.html", nullptr, &e));
    return e.message;
  };
  const std::string header = R"({"actors": [{"name": "a", "shape": {"type": "sphere", "radius": 1}}]})";
  CHECK(error("") == "view: \"" + dir + "/bad.jsonl\" is empty");
  CHECK(error(header + "\n") == "view: \"" + dir + "/bad.jsonl\" has no frames");
  CHECK(error("{\"format\": 1}\n") == dir + "/bad.jsonl:1: the header line needs \"actors\": "
                                           "[{\"name\": …}, …]");
  CHECK(error(header + "\n{\"t\": 0, \"actors\": []}\n") ==
        dir + "/bad.jsonl:2: a frame needs \"actors\" with one entry per header actor (1)");
  CHECK(error(header + "\n{\"t\": 0, \"actors\": [{\"p\": [1, 2]}]}\n") ==
        dir + "/bad.jsonl:2: actors[0].p: expected 3 numbers");
  CHECK(error(R"({"actors": [{"name": "a", "shape": {"type": "cone"}}]})") ==
        dir + "/bad.jsonl:1: header actors[0].shape.type: unknown shape \"cone\" (sphere, box, "
              "plane, mesh)");
  CHECK(error(header + "\n{\"t\": 0, \"actors\": [{}], \"contacts\": {\"tn\": [1], \"p\": [], "
                       "\"f\": []}}\n") ==
        dir + "/bad.jsonl:2: contacts.p: expected 3 numbers");
  CHECK(error(header + "\nnot json\n").rfind(dir + "/bad.jsonl:2: not valid JSON", 0) == 0);
  // An actor not observed in a frame (null, as in observed trajectories) is allowed.
  std::ofstream(dir + "/observed.jsonl") << header << "\n{\"t\": 0, \"actors\": [null]}\n";
  Error e;
  CHECK(WriteViewerPage(dir + "/observed.jsonl", dir + "/observed.html", nullptr, &e));
  CHECK(RunCli("view " + dir + "/missing.jsonl") == 2);
  CHECK(RunCli("view " + dir + "/observed.jsonl --out " + dir + "/cli.html") == 0);
  CHECK(std::filesystem::exists(dir + "/cli.html"));
}
