// Speed against error over the shipped scenes, across time step and integrator.
//   superdex_bench [--scenes drop,box_rest,stack,pile] [--pile-duration S]
// Prints one table: wall seconds per simulated second, Newton iterations per step, stage
// outcomes, and each scene's error metric:
//   drop      max penetration (max of −φ over step ends) [mm]
//   box_rest  |z_end − z*| with z* from k A h h' = m g [µm]
//   stack     |z_top − z*_top| with each interface at its static rest distance [mm]
//             (box-on-box interfaces count twice: two passes, as the spec says)
//   pile      max penetration [mm]
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "energies/penalty_ramp.h"
#include "scenes/runner.h"

using namespace superdex;

namespace {

double RestDistance(double load, double k = 1e9, double area = 0.04, double eps = 0.005,
                    double delta = 0.001) {
  double lo = delta - 2 * eps - 1.0, hi = delta;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    const RampValue r = PenaltyRamp(mid, eps, delta);
    (k * area * r.h * r.dh > load ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

struct Config {
  std::string scene;
  IntegrationMethod method;
  double dt;
  double duration;  // 0: the file's
};

}  // namespace

int main(int argc, char** argv) {
  std::string only;
  double pileDuration = 1.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--scenes" && i + 1 < argc) only = argv[++i];
    else if (a == "--pile-duration" && i + 1 < argc) pileDuration = std::atof(argv[++i]);
    else {
      std::fprintf(stderr, "usage: superdex_bench [--scenes a,b] [--pile-duration S]\n");
      return 2;
    }
  }
  const IntegrationMethod methods[] = {IntegrationMethod::BackwardEuler, IntegrationMethod::BDF2,
                                       IntegrationMethod::SymplecticDIRK12};
  std::vector<Config> configs;
  for (IntegrationMethod m : methods) {
    for (double dt : {1e-3, 5e-4, 2e-4}) configs.push_back({"drop", m, dt, 1.0});
    for (double dt : {1e-2, 5e-3, 2e-3}) configs.push_back({"box_rest", m, dt, 0});
    for (double dt : {1e-2, 5e-3}) configs.push_back({"stack", m, dt, 0});
  }
  for (double dt : {1e-2, 5e-3}) configs.push_back({"pile", IntegrationMethod::BDF2, dt, pileDuration});

  std::printf("%-9s %-17s %8s %7s %12s %10s %8s %14s\n", "scene", "integrator", "dt [s]", "sim [s]",
              "wall/sim s", "Newton/st", "not conv", "error");
  const double g = 9.81;
  const double zRest = 0.1 + RestDistance(g);
  double zTop = -0.1;
  // Box-on-box interfaces act twice (each box is collider and colliding: two passes, summed).
  for (int i = 0; i < 10; ++i) zTop += 0.2 + RestDistance((10 - i) * g, 1e9, i == 0 ? 0.04 : 0.08);
  for (const Config& c : configs) {
    if (!only.empty() && ("," + only + ",").find("," + c.scene + ",") == std::string::npos) continue;
    SceneFile f;
    Error e;
    if (!LoadSceneFile(std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/" + c.scene + ".json", &f, &e) ||
        !f.scene->SetIntegrator(c.method, &e)) {
      std::fprintf(stderr, "error: %s\n", e.message.c_str());
      return 1;
    }
    RunOptions o;
    o.out = "";
    o.dt = c.dt;
    if (c.duration > 0) o.duration = c.duration;
    RunSummary s;
    if (!RunScene(&f, o, &s, &e)) {
      std::fprintf(stderr, "error: %s\n", e.message.c_str());
      return 1;
    }
    std::ostringstream err;
    if (c.scene == "drop" || c.scene == "pile") {
      err << s.maxPenetration * 1e3 << " mm pen";
    } else if (c.scene == "box_rest") {
      err << std::abs(f.scene->State(f.scene->RigidActors()[1]).p.z() - zRest) * 1e6 << " um";
    } else {
      err << std::abs(f.scene->State(f.scene->RigidActors()[10]).p.z() - zTop) * 1e3 << " mm top";
    }
    std::printf("%-9s %-17s %8.0e %7.2f %12.4g %10.2f %8d %14s\n", c.scene.c_str(),
                ToString(c.method), c.dt, s.simulatedSeconds,
                s.wallSeconds / s.simulatedSeconds, double(s.newtonIterations) / s.steps,
                s.stopped + s.diverged, err.str().c_str());
    std::fflush(stdout);
  }
  return 0;
}
