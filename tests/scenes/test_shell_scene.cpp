// Shell actors in scene files (scenes/shell_spec.h, docs/scene-format.md).
//
// Expectations:
//   - a "shell" actor (a generated rectangle, clamped along one edge, its material and bending
//     model given) is read into the description built in C++ would be, runs with every stage
//     converged, and is drawn: the trajectory's header has its surface (every node, every
//     triangle) and each frame its nodes' positions; VTK frames hold its triangles;
//   - its point cloud's fields (radius, self-contact, the collider points' rule) are read into the
//     kind (its points then the triangles' P1Q6 points), collider_type None removes them;
//     loads on a region's nodes are read with their keyframes;
//   - generated disks and annuli (with a slit) are read;
//   - bad fields are refused with the JSON path and the rule (thirteen cases).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/model/shell_kind.h"
#include "scene_text.h"
#include "scenes/runner.h"
#include "scenes/scene_file.h"

using namespace superdex;

namespace {

const char* kFlap = R"({
  "settings": {"dt": 0.005, "duration": 0.05, "integrator": "BDF2"},
  "actors": [
    {"name": "flap", "type": "shell", "mesh": {"type": "rectangle", "size": [0.2, 0.1], "cells": [4, 2]},
     "material": {"youngs_modulus": 1e8, "poisson_ratio": 0.3, "density": 1000, "thickness": 0.002},
     "bending": "Midedge", "position": [0, 0, 0.5],
     "clamped": [{"region": {"min": [-0.11, -1, 0], "max": [-0.09, 1, 1]}}]}
  ]
})";

using test::Replace;

using test::LoadError;

// Runs the scene with its trajectory and VTK frames in a fresh temporary directory `name`
// (t.jsonl, vtk/), which it returns.
std::string RunWithOutputs(SceneFile* f, const char* name, RunSummary* r) {
  const std::string dir = (std::filesystem::temp_directory_path() / name).string();
  std::filesystem::remove_all(dir);
  RunOptions options;
  options.out = dir + "/t.jsonl";
  options.vtk = dir + "/vtk";
  Error e;
  if (!RunScene(f, options, r, &e)) FAIL(e.message);
  return dir;
}

}  // namespace

TEST_CASE("a shell actor in a scene file runs and is drawn", "[scenes][shell]") {
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneText(kFlap, ".", &f, &e));
  REQUIRE(f.scene->NumActors() == 1);
  const auto* shell = dynamic_cast<const ShellKind*>(&f.scene->Kind({0}));
  REQUIRE(shell);
  const ShellModel& m = shell->Model();
  CHECK(m.NumNodes() == 15);
  CHECK(m.faces.size() == 16);
  CHECK(m.material.thickness == 0.002);
  CHECK(m.bending == ShellBendingModel::Midedge);
  int clamped = 0;
  for (int i = 0; i < m.NumNodes(); ++i) clamped += m.freeIndex[i] < 0;
  CHECK(clamped == 3);  // the edge x = −0.1
  RunSummary r;
  const std::string dir = RunWithOutputs(&f, "superdex_shell_scene", &r);
  CHECK(r.converged == r.steps);
  std::ifstream in(dir + "/t.jsonl");
  std::string line;
  REQUIRE(std::getline(in, line));
  const nlohmann::json header = nlohmann::json::parse(line);
  const nlohmann::json& a = header.at("actors").at(0);
  CHECK(a.at("type") == "shell");
  CHECK(a.at("surface").at("nodes").size() == 15);
  CHECK(a.at("surface").at("faces").size() == 3 * 16);
  REQUIRE(std::getline(in, line));
  const nlohmann::json frame = nlohmann::json::parse(line);
  CHECK(frame.at("actors").at(0).at("surface").size() == 3 * 15);
  std::ifstream vtk(dir + "/vtk/frame_000000.vtk");
  REQUIRE(vtk.good());
  std::string text((std::istreambuf_iterator<char>(vtk)), std::istreambuf_iterator<char>());
  CHECK(text.find("POLYGONS 16 ") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("a shell's point cloud in a scene file", "[scenes][shell][point_cloud]") {
  SceneFile f;
  Error e;
  const std::string text = Replace(kFlap, R"("bending": "Midedge",)",
                                   R"("bending": "Midedge", "point_cloud": {"radius": 0.02,
                                   "self_contact": true, "self_contact_exclusion_ratio": 2,
                                   "collider_triangle_element_type": "P1Q6"},)");
  REQUIRE(LoadSceneText(text, ".", &f, &e));
  const ActorKind& k = f.scene->Kind({0});
  REQUIRE(k.PointCloud());
  CHECK(k.PointCloud()->radius == 0.02);
  CHECK(k.PointCloud()->selfContact);
  CHECK(k.PointCloud()->selfContactExclusionRatio == 2.0);
  CHECK(k.NumCloudPoints() == 6 * 16);
  // Loads on a region of nodes, keyframed.
  SceneFile h;
  REQUIRE(LoadSceneText(Replace(kFlap, R"("bending": "Midedge",)",
                                R"("bending": "Midedge", "loads": [{"region": {"min": [0.09, -1, 0],
                                "max": [0.11, 1, 1]}, "force": [[0, 0, 0, 0], [1, 0, 0, 2]]}],)"),
                        ".", &h, &e));
  const ShellModel& m = static_cast<const ShellKind&>(h.scene->Kind({0})).Model();
  REQUIRE(m.loads.size() == 1);
  CHECK(m.loads[0].nodes.size() == 3);  // the edge x = 0.1
  CHECK(m.loads[0].force.back().second.z() == 2.0);
  SceneFile g;
  REQUIRE(LoadSceneText(Replace(kFlap, R"("bending": "Midedge",)",
                                R"("bending": "Midedge", "collider_type": "None",)"),
                        ".", &g, &e));
  CHECK_FALSE(g.scene->Kind({0}).PointCloud());
}

TEST_CASE("bad shell fields name the JSON path and the rule", "[scenes][shell]") {
  CHECK(LoadError(Replace(kFlap, R"("bending": "Midedge",)",
                          R"("bending": "Midedge", "loads": [{"nodes": [0], "force": [[0, 1, 2]]}],)")) ==
        "actors[0].loads[0].force[0]: must be [t, fx, fy, fz]");
  CHECK(LoadError(Replace(kFlap, R"("bending": "Midedge",)",
                          R"("bending": "Midedge", "loads": [{"nodes": [0]}],)")) ==
        "actors[0].loads[0].force: missing required field");
  CHECK(LoadError(Replace(kFlap, R"("bending": "Midedge",)",
                          R"("bending": "Midedge", "point_cloud": {"self_contact_exclusion_ratio": 1},)")) ==
        "actors[0].point_cloud.self_contact_exclusion_ratio: must be > 1, got 1");
  CHECK(LoadError(Replace(kFlap, R"("bending": "Midedge",)",
                          R"("bending": "Midedge", "point_cloud": {"radius": 0},)")) ==
        "actors[0].point_cloud.radius: must be > 0, got 0");
  CHECK(LoadError(Replace(kFlap, R"("bending": "Midedge",)",
                          R"("bending": "Midedge", "collider_type": "Box",)"))
            .rfind("actors[0].collider_type: Box is not available for shell actors", 0) == 0);
  CHECK(LoadError(Replace(kFlap, R"("bending": "Midedge")", R"("bending": "Soft")"))
            .rfind("actors[0].bending: unknown value \"Soft\"", 0) == 0);
  CHECK(LoadError(Replace(kFlap, R"({"type": "rectangle",)", R"({"type": "sphere",)")) ==
        "actors[0].mesh.type: unknown value \"sphere\" (expected one of: file, rectangle, disk, "
        "annulus)");
  CHECK(LoadError(Replace(kFlap, R"({"type": "rectangle", "size": [0.2, 0.1], "cells": [4, 2]})",
                          R"({"type": "annulus", "inner_radius": 0.2, "outer_radius": 0.1})")) ==
        "actors[0].mesh.outer_radius: must be > inner_radius");
  CHECK(LoadError(Replace(kFlap, R"("cells": [4, 2])", R"("cells": [4, 0])")) ==
        "actors[0].mesh.cells: must be two integers in [1, 1000]");
  CHECK(LoadError(Replace(kFlap, R"("thickness": 0.002)", R"("thickness": -1)"))
            .rfind("actors[0].material.thickness: must be finite and > 0", 0) == 0);
  CHECK(LoadError(Replace(kFlap, R"("max": [-0.09, 1, 1]}})", R"("max": [-0.09, 1, 1]}, "path": [[0, 0, 0, 1]]})")) ==
        "actors[0].clamped[0].path: a clamped edge does not move");
  CHECK(LoadError(Replace(kFlap, R"("position": [0, 0, 0.5])", R"("position": [0, 0, 0.5], "colour": 1)"))
            .rfind("actors[0].colour: unknown field", 0) == 0);
  CHECK(LoadError(Replace(kFlap, R"({"type": "rectangle", "size": [0.2, 0.1], "cells": [4, 2]})",
                          R"({"type": "file", "file": "no_such.obj"})"))
            .rfind("actors[0].mesh.file: ", 0) == 0);
}

TEST_CASE("generated disk and annulus meshes in a scene file", "[scenes][shell]") {
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneText(Replace(kFlap, R"({"type": "rectangle", "size": [0.2, 0.1], "cells": [4, 2]})",
                                R"({"type": "disk", "radius": 0.1, "rings": 3})"),
                        ".", &f, &e));
  const ShellModel& disk = static_cast<const ShellKind&>(f.scene->Kind({0})).Model();
  CHECK(disk.NumNodes() == 1 + 6 + 12 + 18);
  CHECK(disk.faces.size() == 6 * 9);
  SceneFile g;
  REQUIRE(LoadSceneText(Replace(kFlap, R"({"type": "rectangle", "size": [0.2, 0.1], "cells": [4, 2]})",
                                R"({"type": "annulus", "inner_radius": 0.05, "outer_radius": 0.1,
                                "angle_deg": 360, "cells": [2, 12]})"),
                        ".", &g, &e));
  const ShellModel& ring = static_cast<const ShellKind&>(g.scene->Kind({0})).Model();
  CHECK(ring.NumNodes() == 3 * 13);  // the slit's two sides are separate nodes
  CHECK(ring.faces.size() == 2 * 2 * 12);
}

TEST_CASE("a shell's VTK frames carry its contact tractions", "[scenes][shell]") {
  // A 0.2 m sheet (1 kg/m²) settled on the ground: its faces' tractions times their areas add
  // up to its weight, 0.04 × 9.81 N.
  const char* text = R"({
    "settings": {"dt": 0.01, "duration": 0.5, "integrator": "BackwardEuler"},
    "actors": [
      {"name": "ground", "dynamic": false, "shape": {"type": "plane", "normal": [0, 0, 1]}},
      {"name": "sheet", "type": "shell", "mesh": {"type": "rectangle", "size": [0.2, 0.2], "cells": [4, 4]},
       "material": {"youngs_modulus": 1e7, "density": 1000, "thickness": 0.001},
       "position": [0, 0, 0.0008], "contact": {"normal_viscous_damping_coefficient": 1.0}}
    ]})";
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneText(text, ".", &f, &e));
  RunSummary r;
  const std::string dir = RunWithOutputs(&f, "superdex_shell_vtk", &r);
  std::string last;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/vtk"))
    last = std::max(last, entry.path().string());
  std::ifstream vtk(last);
  std::string line;
  while (std::getline(vtk, line) && line.rfind("VECTORS traction", 0) != 0) {
  }
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  const double area = 0.04 / 32;  // 32 equal triangles
  for (int k = 0; k < 32; ++k) {
    Eigen::Vector3d t;
    vtk >> t.x() >> t.y() >> t.z();
    force += area * t;
  }
  INFO("contact force " << force.transpose() << " N in " << last);
  CHECK(force.z() == Approx(0.04 * 9.81).epsilon(0.01));
  CHECK(std::abs(force.x()) + std::abs(force.y()) < 1e-6);
  std::filesystem::remove_all(dir);
}
