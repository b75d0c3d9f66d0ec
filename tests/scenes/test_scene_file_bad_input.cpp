// Bad scene files: each is refused with one message naming the JSON path (and the line and
// column for the parser's errors) and the rule, before any large allocation or meshing;
// regression tests for the findings of issue 38.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "scene_text.h"
#include "scenes/scene_file.h"

using namespace superdex;

namespace {

const char* kScene = R"({
  "settings": {"dt": 0.001, "duration": 0.01},
  "actors": [
    {"name": "ground", "dynamic": false, "shape": {"type": "plane"}},
    {"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1, "position": [0, 0, 0.5]}
  ]
})";

std::string LoadError(const std::string& text) {
  return test::LoadError(text, std::string(SUPERDEX_BINARY_DIR));
}

using test::Replace;

// kScene with its ball replaced by `actor` (a JSON object).
std::string WithActor(const std::string& actor) {
  return Replace(kScene, R"({"name": "ball", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1, "position": [0, 0, 0.5]})",
                 actor);
}

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = std::string(SUPERDEX_BINARY_DIR) + "/bad_scene_" + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("bad input: numbers out of range name the JSON path, line and column",
          "[scenes][bad_input]") {
  // These said "(file): [json.exception.out_of_range.406] number overflow parsing '1e999'".
  CHECK(LoadError(Replace(kScene, R"("dt": 0.001)", R"("dt": 1e999)")) ==
        "settings.dt: number 1e999 is out of range (line 2, column 22)");
  CHECK(LoadError(Replace(kScene, "[0, 0, 0.5]", "[0, -1e400, 0.5]")) ==
        "actors[1].position[1]: number -1e400 is out of range (line 5, column 93)");
  CHECK(LoadError(Replace(kScene, R"("radius": 0.1)", R"("radius": 2e308)")) ==
        "actors[1].shape.radius: number 2e308 is out of range (line 5, column 60)");
  CHECK(LoadError("[" + std::string(100, '[') + std::string(101, ']')) ==
        "(file): nested deeper than 64 levels (line 1, column 65)");
  CHECK(LoadError("{\"settings\": }").rfind("(file): not valid JSON: [json.exception.parse_error", 0) == 0);
}

TEST_CASE("bad input: sizes beyond the scene size limit", "[scenes][bad_input]") {
  // Soft spheres of radius 1e155 crashed in GMP (SIGFPE); radius 1e10 ran for minutes.
  for (const char* r : {"1e155", "1e10"}) {
    CHECK(LoadError(WithActor(R"({"name": "s", "type": "soft", "mesh": {"type": "sphere", "radius": )" +
                              std::string(r) + R"(, "edge_length": 1}})")) ==
          "actors[1].mesh.radius: must be at most 1e+06 m (the scene size limit), got " +
              std::string(r == std::string("1e155") ? "1e+155" : "1e+10"));
  }
  CHECK(LoadError(WithActor(R"({"name": "b", "shape": {"type": "box", "size": [1, 1e7, 1]}})")) ==
        "actors[1].shape.size[1]: must be at most 1e+06 m (the scene size limit), got 1e+07");
  CHECK(LoadError(Replace(kScene, "[0, 0, 0.5]", "[0, 0, 5e8]")) ==
        "actors[1].position[2]: must be at most 1e+06 m (the scene size limit), got 5e+08");
  // A surface scaled to 1e155 m crashed in GMP; so did an OBJ with coordinates of 1e299.
  const std::string cube = WriteFile("cube.obj",
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
      "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 3 7 4\nf 4 7 8\nf 1 5 3\n"
      "f 3 5 7\nf 2 4 6\nf 4 8 6\n");
  CHECK(LoadError(WithActor(R"({"name": "s", "type": "soft", "mesh": {"type": "surface", "file": ")" +
                            cube + R"(", "scale": 1e155, "edge_length": 1e154}})")) ==
        "actors[1].mesh.scale: the mesh's coordinates (after scale) must be at most 1e+06 m (the "
        "scene size limit), got 1e+155");
  const std::string huge = WriteFile("huge.obj",
      "v -1e299 -1e299 -1e299\nv 1e299 -1e299 -1e299\nv 0 1e299 -1e299\nv 0 0 1e299\n"
      "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  CHECK(LoadError(WithActor(R"({"name": "s", "type": "soft", "mesh": {"type": "surface", "file": ")" +
                            huge + R"(", "edge_length": 0.5}})")) ==
        "actors[1].mesh.file: the mesh's coordinates (after scale) must be at most 1e+06 m (the "
        "scene size limit), got 1e+299");
  // A rigid mesh with a grid SDF padding of 1e308 crashed in GMP.
  CHECK(LoadError(WithActor(R"({"name": "m", "dynamic": false, "shape": {"type": "mesh", "file": ")" +
                            cube + R"("}, "grid_sdf": {"boundary_padding_dist": 1e308}})")) ==
        "actors[1].grid_sdf.boundary_padding_dist: must be at most 1e+06 m (the scene size "
        "limit), got 1e+308");
  CHECK(LoadError(Replace(kScene, R"("duration": 0.01)", R"("penetration_bound": -1)")) ==
        "settings.penetration_bound: must be > 0, got -1");
}

TEST_CASE("bad input: grids of actors", "[scenes][bad_input]") {
  // Grids of up to 1e9 actors were accepted.
  CHECK(LoadError(WithActor(R"({"name": "b", "shape": {"type": "sphere", "radius": 0.1}, "grid": {"count": [1000, 1000, 1000], "spacing": [1, 1, 1]}})")) ==
        "actors[1].grid.count: makes 1e+09 actors, 1e+09 in the scene: beyond the limit of "
        "100000 actors per scene (about 2600 GB to load)");
  // An overflow from the spacing was reported at actors[1].position.
  CHECK(LoadError(WithActor(R"({"name": "b", "shape": {"type": "sphere", "radius": 0.1}, "grid": {"count": [3, 1, 1], "spacing": [1e308, 0, 0]}})")) ==
        "actors[1].grid.spacing: places actor b_1 at a coordinate that must be at most 1e+06 m "
        "(the scene size limit), got 1e+308");
  CHECK(LoadError(WithActor(R"({"name": "b", "shape": {"type": "sphere", "radius": 0.1}, "grid": {"count": [2, 1, 1], "jitter": 1e300}})"))
            .rfind("actors[1].grid.jitter: places actor b_0 at a coordinate that must be at most "
                   "1e+06 m (the scene size limit), got ", 0) == 0);
}

TEST_CASE("bad input: soft meshes beyond the tet limit or degenerate", "[scenes][bad_input]") {
  // A 200³-cell soft box allocated 5.7 GB and ended in bad_alloc.
  CHECK(LoadError(WithActor(R"({"name": "s", "type": "soft", "mesh": {"type": "box", "size": [1, 1, 1], "cells": [200, 200, 200]}})")) ==
        "actors[1].mesh.cells: the box (6 tets per cell) has 48000000 tets, beyond the 300000 "
        "left of the scene's soft-tet limit 300000 (about 480 GB to simulate at 10 KB per tet)");
  CHECK(LoadError(WithActor(R"({"name": "s", "type": "soft", "mesh": {"type": "sphere", "radius": 1, "edge_length": 0.03}})")) ==
        "actors[1].mesh.edge_length: the sphere has about 1316367 tets, beyond the 300000 left of "
        "the scene's soft-tet limit 300000 (about 13.1637 GB to simulate at 10 KB per tet)");
  // Surfaces that used to hang the mesher.
  const std::string same = WriteFile("same.obj",
      "v 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const std::string error = LoadError(WithActor(
      R"({"name": "s", "type": "soft", "mesh": {"type": "surface", "file": ")" + same +
      R"(", "edge_length": 0.3}})"));
  CHECK(error == "actors[1].mesh: " + same +
                     ": MeshTetsFromSurface: the surface's vertices all coincide: it encloses no "
                     "volume");
  // A node index beyond int used to wrap to an existing node.
  CHECK(LoadError(WithActor(R"({"name": "s", "type": "soft", "mesh": {"type": "box", "size": [1, 1, 1], "cells": [1, 1, 1]}, "constraints": [{"nodes": [4294967296]}]})")) ==
        "actors[1].constraints[0].nodes[0]: node 4294967296 does not exist (the mesh has 8 nodes)");
  CHECK(LoadError(WithActor(R"({"name": "s", "type": "soft", "mesh": {"type": "box", "size": [1, 1, 1], "cells": [1, 1, 1]}, "constraints": [{"nodes": [0], "path": [[0, 0, 0, 1e300]]}]})")) ==
        "actors[1].constraints[0].path[0]: the displacement must be at most 1e+06 m (the scene "
        "size limit), got 1e+300");
  CHECK(LoadError(WithActor(R"({"name": "s", "type": "soft", "mesh": {"type": "box", "size": [0.2, 0.2, 0.2]}, "material": {"poisson_ratio": 0.5}})")) ==
        "actors[1].material.poisson_ratio: must be in (-1, 0.5), got 0.5");
}

TEST_CASE("bad input: integers and files beyond their range", "[scenes][bad_input]") {
  CHECK(LoadError(Replace(kScene, R"("radius": 0.1})", R"("radius": 0.1, "surface_resolution": 18446744073709551615})")) ==
        "actors[1].shape.surface_resolution: must be in [0, 7], got 18446744073709551615");
  const std::string big = std::string(SUPERDEX_BINARY_DIR) + "/bad_scene_big.json";
  std::ofstream(big) << kScene;
  std::filesystem::resize_file(big, 65 << 20);  // sparse: no disk used
  SceneFile f;
  Error e;
  CHECK_FALSE(LoadSceneFile(big, &f, &e));
  CHECK(e.message == big + ": the file holds 6.81574e+07 bytes, beyond the limit of 6.71089e+07 "
                           "bytes per scene file");
  std::filesystem::remove(big);
}

TEST_CASE("bad input: kinematic paths and applied loads", "[scenes][bad_input]") {
  const std::string sphere = R"("shape": {"type": "sphere", "radius": 0.1})";
  CHECK(LoadError(WithActor(R"({"name": "b", )" + sphere + R"(, "applied_force": [1, 2]})")) ==
        "actors[1].applied_force: must be [fx, fy, fz] or keyframes [[t, x, y, z], ...]");
  CHECK(LoadError(WithActor(R"({"name": "b", )" + sphere +
                            R"(, "applied_torque": [[0, 1, 2, 3], [1, 1, 2]]})")) ==
        "actors[1].applied_torque[1]: must be [tx, ty, tz] or keyframes [[t, x, y, z], ...]");
  CHECK(LoadError(WithActor(R"({"name": "b", )" + sphere +
                            R"(, "applied_force": [[1, 0, 0, 0], [0, 0, 0, 0]]})")) ==
        "actors[1].applied_force: keyframe times must increase");
  CHECK(LoadError(WithActor(R"({"name": "b", "dynamic": false, )" + sphere +
                            R"(, "applied_force": [0, 0, 1]})")) ==
        "actors[1].applied_force: only a dynamic actor takes applied loads");
  CHECK(LoadError(WithActor(R"({"name": "b", "kinematic": true, "dynamic": true, )" + sphere + "}")) ==
        "actors[1].kinematic: a kinematic actor is not dynamic (dynamic must be false)");
  CHECK(LoadError(WithActor(R"({"name": "b", )" + sphere + R"(, "path": [{"t": 0, "position": [0, 0, 0]}]})")) ==
        "actors[1].path: only a kinematic actor follows a path");
  CHECK(LoadError(WithActor(R"({"name": "b", "kinematic": true, )" + sphere +
                            R"(, "path": [{"t": 0}]})")) ==
        "actors[1].path[0].position: missing required field");
  CHECK(LoadError(WithActor(R"({"name": "b", "kinematic": true, )" + sphere +
                            R"(, "path": [{"t": 0, "position": [0, 0, 0]}, {"t": 0, "position": [1, 0, 0]}]})")) ==
        "actors[1].path[1].t: keyframe times must increase");
  CHECK(LoadError(WithActor(R"({"name": "b", "kinematic": true, )" + sphere +
                            R"(, "path": [{"t": 0, "position": [0, 0, 0], "speed": 1}]})"))
            .rfind("actors[1].path[0].speed: unknown field", 0) == 0);
  CHECK(LoadError(WithActor(R"({"name": "b", "kinematic": true, )" + sphere +
                            R"(, "path": [{"t": 0, "position": [0, 0, 0]}], "grid": {"count": [2, 1, 1], "spacing": 1}})")) ==
        "actors[1].grid: an actor with a path cannot be replicated");
  // A kinematic actor with a path loads and its path is kept.
  CHECK(LoadError(WithActor(R"({"name": "b", "kinematic": true, )" + sphere +
                            R"(, "path": [{"t": 0, "position": [0, 0, 1]}, {"t": 1, "position": [1, 0, 1], "euler_deg": [0, 0, 90]}]})")) ==
        "<loaded>");
}
