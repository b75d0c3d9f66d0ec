// The `superdex` command-line tool.
//   superdex run SCENE.json [--dt S] [--duration S] [--integrator NAME] [--solver NAME]
//                [--out FILE] [--vtk DIR] [--contacts] [--view] [--quiet]
//   superdex view RUN.jsonl [--out PAGE.html]
//   superdex fit SCENE.json --observed TRAJ.jsonl --params ACTOR.NAME,... [--dt S]
//                [--method lm|lbfgs] [--max-iterations N] [--out FITTED.json]
//   superdex gradient SCENE.json --observed TRAJ.jsonl --params ACTOR.NAME,... [--dt S]
//   superdex params --markdown     (every parameter table; docs/parameters.md is its output)
// Exit codes: 0 success; 2 invalid input (scene file, options); 3 a stage did not converge
// (Stopped or Diverged) or the fit did not converge; 4 a scene expectation failed.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <iostream>

#include <fstream>
#include <nlohmann/json.hpp>

#include "scenes/fit.h"
#include "scenes/parameter_docs.h"
#include "scenes/runner.h"
#include "scenes/viewer_page.h"

namespace {

using superdex::StepReport;

// A one-line progress bar on stderr, redrawn at most ten times a second.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), start_(Clock::now()), last_(start_) {}
  void Update(const StepReport& r, double fraction) {
    ++steps_;
    iterations_ += r.newtonIterations;
    if (!enabled_) return;
    const auto now = Clock::now();
    if (fraction < 1.0 && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    const double wall = std::chrono::duration<double>(now - start_).count();
    const int width = 30;
    const int filled = static_cast<int>(fraction * width);
    std::fprintf(stderr, "\r[%s%s] %3.0f%%  t = %.4g s  step %d  %.1f Newton/step  %.1f s%s",
                 std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(),
                 100.0 * fraction, r.time, steps_, double(iterations_) / steps_, wall,
                 fraction >= 1.0 ? "\n" : "");
    std::fflush(stderr);
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  Clock::time_point start_, last_;
  int steps_ = 0;
  long iterations_ = 0;
};

// The scene file and the observed trajectory of `fit` and `gradient`; false (message printed)
// on bad input.
bool LoadFitInput(const std::string& scenePath, const std::string& observedPath,
                  superdex::SceneFile* file, superdex::ObservedTrajectory* observed) {
  superdex::Error error;
  if (!superdex::LoadSceneFile(scenePath, file, &error) ||
      !superdex::ReadObservedTrajectory(observedPath, observed, &error)) {
    std::cerr << "error: " << error.message << "\n";
    return false;
  }
  return true;
}

// Parses an enum option's value and applies it; false (message printed) on a bad value or a
// refusal.
template <typename E, typename Apply>
bool SetFromOption(const char* option, const std::string& value,
                   bool (*parse)(const std::string&, E*), Apply apply) {
  E v;
  superdex::Error error;
  if (!parse(value, &v)) {
    std::cerr << "error: " << option << ": unknown value \"" << value
              << "\" (expected one of: " << superdex::AllNames(v) << ")\n";
    return false;
  }
  if (!apply(v, &error)) {
    std::cerr << "error: " << option << ": " << error.message << "\n";
    return false;
  }
  return true;
}

int ExitCodeFor(const superdex::Error& error) {
  std::cerr << "error: " << error.message << "\n";
  return error.message.find("converge") != std::string::npos ? 3 : 2;
}

int RunGradient(const std::string& scenePath, const std::string& observedPath,
                const std::vector<std::string>& params, double dt) {
  superdex::SceneFile file;
  superdex::ObservedTrajectory observed;
  if (!LoadFitInput(scenePath, observedPath, &file, &observed)) return 2;
  superdex::FitOptions options;
  options.parameters = params;
  if (dt > 0) options.dt = dt;
  superdex::TrajectoryGradient g;
  superdex::Error error;
  if (!superdex::ComputeTrajectoryGradient(file, observed, options, &g, &error))
    return ExitCodeFor(error);
  std::printf("%-45s %14s %16s\n", "parameter", "value", "d cost / d value");
  for (size_t j = 0; j < g.names.size(); ++j)
    std::printf("%-45s %14.6g %16.6g\n", g.names[j].c_str(), g.values[j], g.gradient[j]);
  std::printf("cost ½Σr²: %.6g m² over %d residuals, %d steps\n", g.cost, g.residuals, g.steps);
  std::printf("simulation %.2f s, adjoint pass %.2f s (%d colours, %.0f residual runs per step)\n",
              g.simulationSeconds, g.gradientSeconds, g.colors, g.runsPerStep);
  return 0;
}

int RunFit(const std::string& scenePath, const std::string& observedPath,
           const std::vector<std::string>& params, double dt, superdex::FitMethod method,
           int maxIterations, const std::string& outPath) {
  superdex::SceneFile file;
  superdex::ObservedTrajectory observed;
  if (!LoadFitInput(scenePath, observedPath, &file, &observed)) return 2;
  superdex::Error error;
  superdex::FitOptions options;
  options.parameters = params;
  if (dt > 0) options.dt = dt;
  options.maxIterations = maxIterations;
  options.method = method;
  superdex::FitResult r;
  std::cerr << "fitting " << params.size() << " parameters to " << observed.frames.size()
            << " observed frames ...\n";
  if (!superdex::FitSceneParameters(file, observed, options, &r, &error)) return ExitCodeFor(error);
  std::printf("%-45s %14s %14s %12s\n", "parameter", "initial", "fitted", "std. error");
  for (size_t j = 0; j < r.names.size(); ++j)
    std::printf("%-45s %14.6g %14.6g %12.3g\n", r.names[j].c_str(), r.initial[j], r.fitted[j],
                r.standardError[j]);
  std::printf("cost ½Σr²: %.4g -> %.4g m²; rms residual %.3g m over %d residuals\n",
              r.initialCost, r.finalCost, r.rmsResidual, r.residuals);
  std::printf("%d iterations, %d simulations, %.1f s; %s\n", r.iterations, r.simulations,
              r.wallSeconds, r.message.c_str());
  if (!outPath.empty()) {
    nlohmann::json j;
    for (size_t k = 0; k < r.names.size(); ++k)
      j["parameters"][r.names[k]] = {{"initial", r.initial[k]}, {"fitted", r.fitted[k]},
                                     {"standard_error", r.standardError[k]}};
    j["final_cost"] = r.finalCost;
    j["rms_residual"] = r.rmsResidual;
    j["converged"] = r.converged;
    std::ofstream(outPath) << j.dump(2) << "\n";
  }
  if (!r.converged) {
    std::cerr << "error: the fit did not converge: " << r.message << "\n";
    return 3;
  }
  return 0;
}


// The options of `superdex run`.
struct RunArgs {
  std::string scene, integrator, out, vtk, solver;
  double dt = 0.0, duration = 0.0;
  bool quiet = false, contacts = false, view = false;
};

CLI::App* AddRunCommand(CLI::App* app, RunArgs* a) {
  CLI::App* run = app->add_subcommand("run", "Run a scene file and write its trajectory");
  run->add_option("scene", a->scene, "Scene file (JSON)")->required();
  run->add_option("--dt", a->dt, "Time step [s] (overrides settings.dt)");
  run->add_option("--duration", a->duration, "Simulated time [s] (overrides settings.duration)");
  run->add_option("--integrator", a->integrator,
                  "IntegrationMethod (overrides settings.integrator): " +
                      superdex::AllNames(superdex::IntegrationMethod()));
  run->add_option("--out", a->out, "Trajectory file (JSON Lines); overrides output.path");
  run->add_option("--vtk", a->vtk, "Directory for VTK frames (surfaces with contact tractions); "
                                   "overrides output.vtk");
  run->add_option("--solver", a->solver,
                  "Stage solver (overrides settings.stage_solver): " +
                      superdex::AllNames(superdex::StageSolverKind()) +
                      "; ipopt (potential stages only) and ceres are dense checks for small "
                      "scenes");
  run->add_flag("--contacts", a->contacts,
                "Record the contact samples in the trajectory frames (sets output.contacts)");
  run->add_flag("--view", a->view,
                "At the end, write the viewer page next to the trajectory (as `superdex view`)");
  run->add_flag("--quiet", a->quiet, "No progress bar");
  return run;
}

int RunCommand(const RunArgs& a, const CLI::App& run) {
  superdex::SceneFile file;
  superdex::Error error;
  if (!superdex::LoadSceneFile(a.scene, &file, &error)) {
    std::cerr << "error: " << error.message << "\n";
    return 2;
  }
  superdex::RunOptions options;
  if (run.count("--dt")) options.dt = a.dt;
  if (run.count("--duration")) options.duration = a.duration;
  if (run.count("--out")) options.out = a.out;
  if (run.count("--vtk")) options.vtk = a.vtk;
  if (a.contacts) options.contacts = true;
  options.view = a.view;
  superdex::Scene& scene = *file.scene;
  if (run.count("--integrator") &&
      !SetFromOption<superdex::IntegrationMethod>("--integrator", a.integrator, superdex::Parse,
                     [&](auto m, superdex::Error* e) { return scene.SetIntegrator(m, e); }))
    return 2;
  if (run.count("--solver") &&
      !SetFromOption<superdex::StageSolverKind>("--solver", a.solver, superdex::ParseStageSolver,
                     [&](auto k, superdex::Error* e) { return scene.SetStageSolver(k, e); }))
    return 2;
  for (const auto& n : file.scene->Notices()) std::cerr << "note: " << n << "\n";

  ProgressBar bar(!a.quiet);
  options.progress = [&](const StepReport& r, double f) { bar.Update(r, f); };
  superdex::RunSummary summary;
  if (!superdex::RunScene(&file, options, &summary, &error)) {
    std::cerr << "error: " << error.message << "\n";
    return 2;
  }
  superdex::PrintSummary(file, summary, std::cout);
  if (summary.stopped > 0 || summary.diverged > 0) {
    std::cerr << "error: " << summary.stopped + summary.diverged
              << " stages did not converge (see the summary)\n";
    return 3;
  }
  return summary.expectationFailures.empty() ? 0 : 4;
}

int ViewCommand(const std::string& trajectory, const std::string& out) {
  superdex::ViewerPageInfo info;
  superdex::Error error;
  const std::string page = out.empty() ? superdex::ViewerPagePath(trajectory) : out;
  if (!superdex::WriteViewerPage(trajectory, page, &info, &error)) {
    std::cerr << "error: " << error.message << "\n";
    return 2;
  }
  std::printf("viewer page %s: %d frames, %d actors, %ld contact samples, %.2f MB (open it in a "
              "browser)\n", info.path.c_str(), info.frames, info.actors, info.contactSamples,
              info.bytes / 1e6);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"superdex: compliant-contact simulation by incremental potentials"};
  app.require_subcommand(1);
  RunArgs runArgs;
  CLI::App* run = AddRunCommand(&app, &runArgs);
  CLI::App* view = app.add_subcommand(
      "view", "Write the viewer page of a trajectory: one HTML file next to it (RUN.html) that "
              "plays the run in a browser, from disk, without a network");
  std::string viewTrajectory, viewOut;
  view->add_option("trajectory", viewTrajectory, "Trajectory file (JSON Lines)")->required();
  view->add_option("--out", viewOut, "The page (default: the trajectory's path with .html)");
  CLI::App* fit = app.add_subcommand(
      "fit", "Fit scene parameters to an observed trajectory (Ceres on the centres of mass: "
             "Levenberg-Marquardt with forward sensitivities, or L-BFGS with adjoint gradients)");
  CLI::App* gradient = app.add_subcommand(
      "gradient", "The fitting cost ½Σr² of an observed trajectory and its gradient in the "
                  "parameters, by one simulation and one adjoint pass");
  std::string fitScene, observedPath, fitOut, fitMethod = "lm";
  std::vector<std::string> fitParams;
  double fitDt = 0.0;
  int maxIterations = 50;
  for (CLI::App* sub : {fit, gradient}) {
    sub->add_option("scene", fitScene, "Scene file (JSON): the model and the initial guess")
        ->required();
    sub->add_option("--observed", observedPath,
                    "Observed trajectory (the trajectory format: header, frames with t and "
                    "actors' p)")
        ->required();
    sub->add_option("--params", fitParams,
                    "Parameters ACTOR.NAME, comma-separated: " + superdex::SceneParameterNames())
        ->required()
        ->delimiter(',');
    sub->add_option("--dt", fitDt, "Time step [s] (overrides settings.dt)");
  }
  std::string methods;
  for (const auto& n : superdex::NamesOf(superdex::FitMethod()))
    methods += (methods.empty() ? "" : "; ") + std::string(n.name) + ": " + n.doc;
  fit->add_option("--method", fitMethod, methods + " (default lm)");
  fit->add_option("--max-iterations", maxIterations, "Solver iterations (default 50)");
  fit->add_option("--out", fitOut, "Write the fitted values as JSON");
  CLI::App* params = app.add_subcommand(
      "params", "Print every parameter table: names, types, units, defaults and rules");
  params->add_flag("--markdown", "As markdown, the only format (docs/parameters.md is this output)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  if (params->parsed()) {
    superdex::PrintParameterMarkdown(std::cout);
    return 0;
  }
  if (gradient->parsed())
    return RunGradient(fitScene, observedPath, fitParams, gradient->count("--dt") ? fitDt : 0.0);
  if (fit->parsed()) {
    superdex::FitMethod method;
    if (!superdex::ParseFitMethod(fitMethod, &method)) {
      std::cerr << "error: --method: unknown value \"" << fitMethod
                << "\" (expected one of: " << superdex::AllNames(method) << ")\n";
      return 2;
    }
    return RunFit(fitScene, observedPath, fitParams, fit->count("--dt") ? fitDt : 0.0, method,
                  maxIterations, fitOut);
  }
  if (view->parsed()) return ViewCommand(viewTrajectory, viewOut);
  return RunCommand(runArgs, *run);
}
