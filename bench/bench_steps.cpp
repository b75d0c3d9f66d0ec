// Newton iterations per step of one scene file, step by step and per time window.
//   superdex_bench_steps SCENE.json [--dt S] [--duration S] [--window S] [--every-step]
//                        [--one-step-length]
// Prints, per window of simulated time: steps, the median / mean / max Newton iterations per
// step, rejected line-search trials, explicit-normals fallbacks, non-converged stages, max
// penetration and wall seconds; then the same over the whole run. --every-step also prints one
// line per step (time, iterations, line-search trials, status, active samples, wall ms).
// --one-step-length turns the solvers' line search by independent parts off
// (NonlinearSolverParams::partLineSearch), for comparison.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "scenes/runner.h"

using namespace superdex;

namespace {

struct StepRow {
  double time = 0.0;
  int newton = 0;
  int lineSearch = 0;
  int fallbacks = 0;
  bool converged = true;
  double penetration = 0.0;  // [m]
  double wall = 0.0;         // [s]
};

double Median(std::vector<int> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void PrintWindow(const char* label, const std::vector<StepRow>& rows, size_t begin, size_t end) {
  std::vector<int> iters;
  long sum = 0, ls = 0;
  int maxIt = 0, fb = 0, bad = 0;
  double pen = 0.0, wall = 0.0;
  for (size_t i = begin; i < end; ++i) {
    const StepRow& r = rows[i];
    iters.push_back(r.newton);
    sum += r.newton;
    ls += r.lineSearch;
    maxIt = std::max(maxIt, r.newton);
    fb += r.fallbacks;
    bad += r.converged ? 0 : 1;
    pen = std::max(pen, r.penetration);
    wall += r.wall;
  }
  const size_t n = end - begin;
  std::printf("%-17s %6zu %7.1f %7.2f %5d %9ld %5d %5d %9.3f %9.3f\n", label, n, Median(iters),
              n ? double(sum) / n : 0.0, maxIt, ls, fb, bad, pen * 1e3, wall);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: superdex_bench_steps SCENE.json [--dt S] [--duration S] [--window S] "
                 "[--every-step] [--one-step-length]\n");
    return 2;
  }
  const std::string path = argv[1];
  RunOptions o;
  o.out = "";
  o.vtk = "";
  double window = 0.5;
  bool everyStep = false;
  bool oneStepLength = false;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--dt" && i + 1 < argc) o.dt = std::atof(argv[++i]);
    else if (a == "--duration" && i + 1 < argc) o.duration = std::atof(argv[++i]);
    else if (a == "--window" && i + 1 < argc) window = std::atof(argv[++i]);
    else if (a == "--every-step") everyStep = true;
    else if (a == "--one-step-length") oneStepLength = true;
    else {
      std::fprintf(stderr, "superdex_bench_steps: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (!(window > 0)) {
    std::fprintf(stderr, "superdex_bench_steps: --window must be > 0\n");
    return 2;
  }
  SceneFile f;
  Error e;
  if (!LoadSceneFile(path, &f, &e)) {
    std::fprintf(stderr, "error: %s\n", e.message.c_str());
    return 1;
  }
  if (oneStepLength) {
    NonlinearSolverParams p = f.scene->Settings().solver;
    p.partLineSearch = false;
    if (!f.scene->SetSolverParams(p, &e)) {
      std::fprintf(stderr, "error: %s\n", e.message.c_str());
      return 1;
    }
  }
  std::vector<StepRow> rows;
  o.progress = [&](const StepReport& r, double) {
    StepRow row;
    row.time = r.time;
    row.newton = r.newtonIterations;
    row.lineSearch = r.lineSearchSteps;
    row.fallbacks = r.fallbacks;
    row.converged = r.status == StageStatus::Converged;
    row.penetration = std::max(0.0, -r.contact.minSignedDistance);
    row.wall = r.wallSeconds;
    rows.push_back(row);
    if (everyStep) {
      std::printf("step t=%.5f newton=%d ls=%d status=%s active=%d wall_ms=%.3f\n", r.time,
                  r.newtonIterations, r.lineSearchSteps, ToString(r.status),
                  r.contact.activeSamples, r.wallSeconds * 1e3);
      std::fflush(stdout);
    }
  };
  RunSummary s;
  if (!RunScene(&f, o, &s, &e)) {
    std::fprintf(stderr, "error: %s\n", e.message.c_str());
    return 1;
  }
  std::printf("%s: %d steps, %.3f s simulated, %.2f wall s per simulated second\n", path.c_str(),
              s.steps, s.simulatedSeconds, s.wallSeconds / std::max(s.simulatedSeconds, 1e-300));
  std::printf("%-17s %6s %7s %7s %5s %9s %5s %5s %9s %9s\n", "window [s]", "steps", "median",
              "mean", "max", "ls trials", "fallb", "!conv", "pen [mm]", "wall [s]");
  size_t begin = 0;
  const double t0 = rows.empty() ? 0.0 : rows.front().time - 1e-12;
  for (int w = 0; begin < rows.size(); ++w) {
    const double hi = t0 + (w + 1) * window;
    size_t end = begin;
    while (end < rows.size() && rows[end].time <= hi + 1e-9) ++end;
    if (end == begin) continue;
    char label[64];
    std::snprintf(label, sizeof label, "%.2f-%.2f", hi - window, hi);
    PrintWindow(label, rows, begin, end);
    begin = end;
  }
  PrintWindow("all", rows, 0, rows.size());
  return 0;
}
