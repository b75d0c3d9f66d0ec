// Records trajectories for the refactoring regression check (tests/regression/README.md): every
// shipped scene (scenes/data), the sensitivity suite's scenes and the hard-case suite's scenes,
// stepped as their tests step them. Per step one line: the step's Newton iterations, stages,
// closed-form free stages, fallbacks and status, then Scene::PackState() (positions and
// velocities of every dynamic actor) at full precision.
//
//   superdex_regression_record OUTDIR [--quick]
//
// --quick caps every run at 200 steps.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "hard_case_scenes.h"
#include "scenes/scene_file.h"
#include "sensitivity_scenes.h"

using namespace superdex;

namespace {

std::string g_outDir;
bool g_quick = false;

void Record(const std::string& name, Scene& scene, double dt, int steps) {
  if (g_quick) steps = std::min(steps, 200);
  const std::string path = g_outDir + "/" + name + ".txt";
  FILE* f = std::fopen(path.c_str(), "w");
  REQUIRE(f);
  Error e;
  for (int i = 0; i < steps; ++i) {
    StepReport r;
    REQUIRE(scene.Step(dt, &r, &e));
    std::fprintf(f, "%d %d %d %d %d", r.newtonIterations, r.stages, r.freeStages, r.fallbacks,
                 static_cast<int>(r.status));
    const Eigen::VectorXd s = scene.PackState();
    for (int k = 0; k < s.size(); ++k) std::fprintf(f, " %.17g", s[k]);
    std::fprintf(f, "\n");
  }
  std::fclose(f);
  std::cout << name << ": " << steps << " steps" << std::endl;
}

int Steps(double duration, double dt) { return static_cast<int>(std::lround(duration / dt)); }

}  // namespace

TEST_CASE("regression: shipped scenes", "[regression]") {
  const std::string dir = std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data";
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == ".json") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  for (const std::string& path : files) {
    SceneFile sf;
    Error e;
    INFO(path << ": " << e.message);
    REQUIRE(LoadSceneFile(path, &sf, &e));
    const std::string name = "shipped_" + std::filesystem::path(path).stem().string();
    Record(name, *sf.scene, sf.dt, Steps(sf.duration, sf.dt));
  }
}

TEST_CASE("regression: sensitivity scenes", "[regression]") {
  const IntegrationMethod methods[] = {IntegrationMethod::BackwardEuler, IntegrationMethod::BDF2};
  const DissipationMode modes[] = {DissipationMode::ExplicitNormals,
                                   DissipationMode::ReconstructedLoad,
                                   DissipationMode::ImplicitLoad};
  for (IntegrationMethod method : methods) {
    for (int m = 0; m < 3; ++m) {
      const std::string tag = std::string(ToString(method)) + "_" + std::to_string(m);
      {
        Scene s = test::SlidingBox(method, modes[m]);
        Record("sens_sliding_box_" + tag, s, 1e-2, 30);
      }
      {
        Scene s = test::BouncingBox(method, modes[m]);
        Record("sens_bouncing_box_" + tag, s, 5e-3, 60);
      }
      {
        Scene s = test::SoftCubeOnGround(method, modes[m], 0.06, 0.3, 0.5);
        Record("sens_soft_cube_" + tag, s, 1e-2, 20);
      }
      {
        Scene s = test::BoxOnSoftSlab(method, modes[m], 0.2, 0.5);
        Record("sens_box_on_slab_" + tag, s, 1e-2, 20);
      }
      {
        Scene s = test::BoxOnSoftSlab(method, modes[m], 0.2, 0.5, true);
        Record("sens_box_on_slab_collider_" + tag, s, 1e-2, 20);
      }
    }
  }
}

TEST_CASE("regression: hard-case scenes", "[regression]") {
  {
    Scene s = test::MassRatioStack();
    Record("hard_mass_ratio", s, 1e-2, Steps(2.0, 1e-2));
  }
  {
    Scene s = test::SteepIncline();
    Record("hard_steep_incline", s, 1e-2, Steps(1.5, 1e-2));
  }
  {
    Scene s = test::StiffRestingBox();
    Record("hard_stiff_box", s, 5e-3, Steps(1.0, 5e-3));
  }
  {
    Scene s = test::FiveBoxStack();
    Record("hard_coarse_stack", s, 1.0 / 30, Steps(3.0, 1.0 / 30));
  }
  {
    Scene s = test::SpinningBox();
    Record("hard_spinning_box", s, 2e-3, Steps(0.2, 2e-3));
  }
  {
    Scene s = test::SphereAtPlate();
    Record("hard_sphere_at_plate", s, 1e-4, Steps(0.05, 1e-4));
  }
  for (int mode : {0, 1}) {
    Scene s = test::SphereColumn(mode);
    Record("hard_sphere_column_" + std::to_string(mode), s, 0.02, Steps(0.24, 0.02));
  }
}

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: superdex_regression_record OUTDIR [--quick]\n";
    return 2;
  }
  g_outDir = argv[1];
  g_quick = argc > 2 && std::string(argv[2]) == "--quick";
  std::filesystem::create_directories(g_outDir);
  const char* args[] = {argv[0], "[regression]"};
  return Catch::Session().run(2, const_cast<char**>(args));
}
