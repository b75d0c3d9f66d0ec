// The `superdex` command-line tool.
//   superdex run SCENE.json [--dt S] [--duration S] [--integrator NAME] [--solver NAME]
//                [--out FILE] [--vtk DIR] [--contacts] [--view] [--quiet]
//                [--checkpoint-every N [--checkpoint FILE]] [--resume FILE]
//   superdex view RUN.jsonl [--out PAGE.html]
//   superdex fit SCENE.json --observed TRAJ.jsonl --params ACTOR.NAME,... [--dt S]
//                [--method lm|lbfgs] [--max-iterations N] [--out FITTED.json]
//   superdex gradient SCENE.json --observed TRAJ.jsonl --params ACTOR.NAME,... [--dt S]
//   superdex params --markdown     (every parameter table; docs/parameters.md is its output)
//   superdex sweep SCENE.json --set ACTOR.FIELD=v1,v2,... [--workers N | --scheduler ADDRESS] ...
//   superdex fit-batch SCENE.json --observed T1.jsonl,T2.jsonl,... --params ACTOR.NAME,... ...
//                                  (both run `python3 -m superdex`: Dask, docs/sweeps.md)
// Exit codes (kExitCodes below, docs/reliability.md): 0 success; 1 an internal error; 2 invalid
// input (scene file, options, a resource limit); 3 a stage or the fit did not converge; 4 a scene
// expectation failed; 5 the run turned unphysical (non-finite state, inverted tet, penetration
// beyond its bound) or the fit's cost is not finite; 6 an output could not be written;
// 128 + N stopped by signal N (130 SIGINT, 143 SIGTERM) after finishing the current step.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>

#include "scenes/fit.h"
#include "scenes/parameter_docs.h"
#include "scenes/runner.h"
#include "scenes/version.h"
#include "scenes/viewer_page.h"

namespace {

using superdex::StepReport;

constexpr int kExitInternal = 1, kExitInput = 2, kExitNotConverged = 3, kExitExpectation = 4,
              kExitUnphysical = 5, kExitOutput = 6;
const char* kExitCodes =
    "Exit codes: 0 success; 1 internal error; 2 invalid input (the message names the JSON path "
    "or file:line and the rule; also a resource limit); 3 a stage or the fit did not converge; "
    "4 a scene expectation failed; 5 the run turned unphysical (non-finite state, inverted soft "
    "tet, penetration beyond its bound) or the fit's cost is not finite; 6 an output file could "
    "not be written; 130 / 143 stopped by SIGINT / SIGTERM after the current step (its frame, "
    "the summary and the files are complete).";

// The signal that asked the run or fit to stop (0: none). SIGINT and SIGTERM finish the current
// step; a second signal ends the process at once (the handler is reset after the first).
volatile std::sig_atomic_t g_signal = 0;

extern "C" void OnSignal(int signal) { g_signal = signal; }

void CatchStopSignals() {
  for (int signal : {SIGINT, SIGTERM}) {
    struct sigaction current {};
    sigaction(signal, nullptr, &current);
    if (current.sa_handler == SIG_IGN) continue;  // e.g. SIGINT of a background job
    struct sigaction action {};
    action.sa_handler = OnSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;
    sigaction(signal, &action, nullptr);
  }
}

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
  for (const std::string& n : observed->notes) std::cerr << "note: " << n << "\n";
  return true;
}

// Parses an enum option's value and applies it; false (message printed) on a bad value or a
// refusal.
template <typename E, typename Apply>
bool SetFromOption(const char* option, const std::string& value, Apply apply) {
  E v;
  superdex::Error error;
  if (!superdex::ParseName(value, &v)) {
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

// An option's value that must be a positive finite number: false (message printed) otherwise.
bool PositiveOption(const CLI::App* command, const char* option, double value) {
  if (!command->count(option) || (value > 0 && std::isfinite(value))) return true;
  std::cerr << "error: " << option << ": must be > 0 and finite, got " << value << "\n";
  return false;
}

int ExitCodeFor(const superdex::Error& error, superdex::FitFailure failure) {
  std::cerr << "error: " << error.message << "\n";
  switch (failure) {
    case superdex::FitFailure::Simulation: return kExitNotConverged;
    case superdex::FitFailure::NonFinite: return kExitUnphysical;
    default: return kExitInput;
  }
}

int RunGradient(const std::string& scenePath, const std::string& observedPath,
                const std::vector<std::string>& params, std::optional<double> dt) {
  superdex::SceneFile file;
  superdex::ObservedTrajectory observed;
  if (!LoadFitInput(scenePath, observedPath, &file, &observed)) return kExitInput;
  superdex::FitOptions options;
  options.parameters = params;
  options.dt = dt;
  superdex::TrajectoryGradient g;
  superdex::Error error;
  superdex::FitFailure failure;
  if (!superdex::ComputeTrajectoryGradient(file, observed, options, &g, &error, &failure))
    return ExitCodeFor(error, failure);
  std::printf("%-45s %14s %16s\n", "parameter", "value", "d cost / d value");
  for (size_t j = 0; j < g.names.size(); ++j)
    std::printf("%-45s %14.6g %16.6g\n", g.names[j].c_str(), g.values[j], g.gradient[j]);
  std::printf("cost ½Σr²: %.6g m² over %d residuals, %d steps\n", g.cost, g.residuals, g.steps);
  std::printf("simulation %.2f s, adjoint pass %.2f s (%d colours, %.0f residual runs per step)\n",
              g.simulationSeconds, g.gradientSeconds, g.colors, g.runsPerStep);
  return 0;
}

int RunFit(const std::string& scenePath, const std::string& observedPath,
           const std::vector<std::string>& params, std::optional<double> dt,
           superdex::FitMethod method, int maxIterations, const std::string& outPath,
           const std::string& sceneOutPath) {
  superdex::SceneFile file;
  superdex::ObservedTrajectory observed;
  if (!LoadFitInput(scenePath, observedPath, &file, &observed)) return kExitInput;
  superdex::Error error;
  superdex::FitOptions options;
  options.parameters = params;
  options.dt = dt;
  options.maxIterations = maxIterations;
  options.method = method;
  superdex::FitResult r;
  // --out holds the values at every iteration (status "running"), so a killed fit leaves its
  // last iterate; it is written before the fit starts, so an unwritable path fails at once.
  auto write = [&](const superdex::FitResult& result, const char* status) {
    if (outPath.empty() || superdex::WriteFitJson(outPath, result, status, &error)) return true;
    std::cerr << "error: " << error.message << "\n";
    return false;
  };
  superdex::FitResult start;
  start.names = params;
  start.initial.assign(params.size(), NAN);
  if (!write(start, "running")) return kExitOutput;
  bool writeFailed = false;
  options.iteration = [&](const superdex::FitProgress& p) {
    superdex::FitResult now = r;
    now.fitted = p.values;
    now.finalCost = p.cost;
    now.iterations = p.iteration;
    writeFailed = writeFailed || !write(now, "running");
    return g_signal == 0 && !writeFailed;
  };
  std::cerr << "fitting " << params.size() << " parameters to " << observed.frames.size()
            << " observed frames ...\n";
  CatchStopSignals();
  superdex::FitFailure failure;
  if (!superdex::FitSceneParameters(file, observed, options, &r, &error, &failure))
    return ExitCodeFor(error, failure);
  std::printf("%-45s %14s %14s %12s\n", "parameter", "initial", "fitted", "std. error");
  for (size_t j = 0; j < r.names.size(); ++j)
    std::printf("%-45s %14.6g %14.6g %12.3g\n", r.names[j].c_str(), r.initial[j], r.fitted[j],
                r.standardError[j]);
  std::printf("cost ½Σr²: %.4g -> %.4g m²; rms residual %.3g m over %d residuals\n",
              r.initialCost, r.finalCost, r.rmsResidual, r.residuals);
  std::printf("%d iterations, %d simulations, %.1f s; %s\n", r.iterations, r.simulations,
              r.wallSeconds, r.message.c_str());
  std::fflush(stdout);
  const char* status = g_signal ? "interrupted" : r.converged ? "converged" : "not converged";
  if (writeFailed || !write(r, status)) return kExitOutput;
  if (g_signal) {
    std::cerr << "error: the fit was stopped by signal " << g_signal << " after iteration "
              << r.iterations << "; --out holds its last values\n";
    return 128 + g_signal;
  }
  if (!r.converged) {
    std::cerr << "error: the fit did not converge: " << r.message << "\n";
    return kExitNotConverged;
  }
  if (!sceneOutPath.empty()) {
    if (!superdex::WriteFittedScene(file, r, sceneOutPath, &error)) {
      std::cerr << "error: --scene-out: " << error.message << "\n";
      return kExitOutput;
    }
    std::printf("fitted scene: %s\n", sceneOutPath.c_str());
  }
  return 0;
}

// `superdex run` after loading: runs, prints the summary, maps the end to the exit code.
int RunAndReport(superdex::SceneFile& file, superdex::RunOptions options, bool quiet) {
  ProgressBar bar(!quiet);
  options.progress = [&](const StepReport& r, double f) { bar.Update(r, f); };
  options.interrupted = [] { return static_cast<int>(g_signal); };
  superdex::RunSummary summary;
  superdex::Error error;
  CatchStopSignals();
  superdex::RunScene(&file, options, &summary, &error);
  if (summary.end == superdex::RunEnd::InvalidInput) {
    std::cerr << "error: " << error.message << "\n";
    return kExitInput;
  }
  if (summary.steps > 0 || summary.end != superdex::RunEnd::OutputFailed) {
    if (!quiet && summary.end != superdex::RunEnd::Completed) std::fputc('\n', stderr);
    superdex::PrintSummary(file, summary, std::cout);
    std::cout.flush();
  }
  switch (summary.end) {
    case superdex::RunEnd::OutputFailed:
      std::cerr << "error: " << summary.endMessage << "\n";
      return kExitOutput;
    case superdex::RunEnd::Unphysical:
      std::cerr << "error: " << summary.endMessage << "\n";
      return kExitUnphysical;
    case superdex::RunEnd::Interrupted:
      std::cerr << "error: " << summary.endMessage << "\n";
      return 128 + summary.signal;
    default: break;
  }
  if (summary.stopped > 0 || summary.diverged > 0) {
    std::cerr << "error: " << summary.stopped + summary.diverged
              << " stages did not converge (see the summary)\n";
    return kExitNotConverged;
  }
  return summary.expectationFailures.empty() ? 0 : kExitExpectation;
}

// The options of `superdex run`.
struct RunArgs {
  std::string scene, integrator, out, vtk, solver, checkpoint, resume;
  double dt = 0.0, duration = 0.0;
  long long checkpointEvery = 0;
  bool quiet = false, contacts = false, view = false;
};

CLI::App* AddRunCommand(CLI::App* app, RunArgs* a) {
  CLI::App* run = app->add_subcommand("run", "Run a scene file and write its trajectory");
  run->add_option("scene", a->scene, "Scene file (JSON)")->required();
  run->add_option("--dt", a->dt, "Time step [s] (overrides settings.dt)");
  run->add_option("--duration", a->duration, "Simulated time [s] (overrides settings.duration)");
  using superdex::SceneSettings;
  const auto settingsKey = [](auto member) {  // "settings.<the table's name of member>"
    return std::string("settings.") + superdex::FieldName(superdex::kSceneSettingsFields, member);
  };
  run->add_option("--integrator", a->integrator,
                  "IntegrationMethod (overrides " + settingsKey(&SceneSettings::integrator) +
                      "): " + superdex::AllNames(superdex::IntegrationMethod()));
  run->add_option("--out", a->out, "Trajectory file (JSON Lines); overrides output.path");
  run->add_option("--vtk", a->vtk, "Directory for VTK frames (surfaces with contact tractions); "
                                   "overrides output.vtk");
  run->add_option("--solver", a->solver,
                  "Stage solver (overrides " + settingsKey(&SceneSettings::stageSolver) + "): " +
                      superdex::AllNames(superdex::StageSolverKind()) +
                      "; ipopt (potential stages only) and ceres are dense checks for small "
                      "scenes");
  run->add_flag("--contacts", a->contacts,
                "Record the contact samples in the trajectory frames (sets output.contacts)");
  run->add_flag("--view", a->view,
                "At the end, write the viewer page next to the trajectory (as `superdex view`)");
  run->add_flag("--quiet", a->quiet, "No progress bar");
  run->add_option("--checkpoint-every", a->checkpointEvery,
                  "Write a checkpoint after every N-th step (and when a signal stops the run)");
  run->add_option("--checkpoint", a->checkpoint,
                  "The checkpoint file (default: the trajectory's path with .checkpoint, or the "
                  "--resume file)");
  run->add_option("--resume", a->resume,
                  "Continue the run from a checkpoint of this scene file (docs/reliability.md)");
  return run;
}

// --checkpoint-every, --checkpoint and --resume into `options` (after every other override:
// the checkpoint must fit the scene as it will run); false after printing the error.
bool CheckpointOptions(const RunArgs& a, const CLI::App& run, const superdex::SceneFile& file,
                       superdex::Checkpoint* resume, superdex::RunOptions* options) {
  superdex::Error error;
  if (run.count("--resume")) {
    if (!superdex::ReadCheckpoint(a.resume, resume, &error) ||
        !superdex::CheckpointFits(*resume, a.resume, *file.scene, file.textHash,
                                  options->dt.value_or(file.dt), &error)) {
      std::cerr << "error: " << error.message << "\n";
      return false;
    }
    options->resume = resume;
  }
  if (!run.count("--checkpoint-every")) {
    if (!run.count("--checkpoint")) return true;
    std::cerr << "error: --checkpoint: needs --checkpoint-every N\n";
    return false;
  }
  if (a.checkpointEvery < 1) {
    std::cerr << "error: --checkpoint-every: must be >= 1, got " << a.checkpointEvery << "\n";
    return false;
  }
  options->checkpointEvery = a.checkpointEvery;
  const std::string trajectory = options->out.value_or(file.output.path);
  options->checkpointPath = run.count("--checkpoint") ? a.checkpoint
                            : run.count("--resume")   ? a.resume
                            : trajectory.empty()      ? std::string()
                                                      : trajectory + ".checkpoint";
  if (options->checkpointPath.empty()) {
    std::cerr << "error: --checkpoint-every: give --checkpoint FILE (the run writes no "
                 "trajectory to put it next to)\n";
    return false;
  }
  return true;
}

int RunCommand(const RunArgs& a, const CLI::App& run) {
  superdex::SceneFile file;
  superdex::Error error;
  if (!superdex::LoadSceneFile(a.scene, &file, &error)) {
    std::cerr << "error: " << error.message << "\n";
    return kExitInput;
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
      !SetFromOption<superdex::IntegrationMethod>("--integrator", a.integrator,
                     [&](auto m, superdex::Error* e) { return scene.SetIntegrator(m, e); }))
    return kExitInput;
  if (run.count("--solver") &&
      !SetFromOption<superdex::StageSolverKind>("--solver", a.solver,
                     [&](auto k, superdex::Error* e) { return scene.SetStageSolver(k, e); }))
    return kExitInput;
  superdex::Checkpoint resume;
  if (!CheckpointOptions(a, run, file, &resume, &options)) return kExitInput;
  for (const auto& n : file.scene->Notices()) std::cerr << "note: " << n << "\n";
  return RunAndReport(file, options, a.quiet);
}

int ViewCommand(const std::string& trajectory, const std::string& out) {
  superdex::ViewerPageInfo info;
  superdex::Error error;
  const std::string page = out.empty() ? superdex::ViewerPagePath(trajectory) : out;
  if (!superdex::WriteViewerPage(trajectory, page, &info, &error)) {
    std::cerr << "error: " << error.message << "\n";
    return error.message.rfind("view: cannot write", 0) == 0 ? kExitOutput : kExitInput;
  }
  for (const std::string& n : info.notes) std::cerr << "note: " << n << "\n";
  std::printf("viewer page %s: %d frames, %d actors, %ld contact samples, %.2f MB (open it in a "
              "browser)\n", info.path.c_str(), info.frames, info.actors, info.contactSamples,
              info.bytes / 1e6);
  return 0;
}

int Main(int argc, char** argv) {
  CLI::App app{"superdex: compliant-contact simulation by incremental potentials"};
  app.footer(kExitCodes);
  app.set_version_flag("--version", superdex::kVersion, "Print the version and exit");
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
  std::string fitSceneOut;
  fit->add_option("--scene-out", fitSceneOut,
                  "Write the scene file with the fitted values (meshes beside it) once the fit "
                  "converged");
  CLI::App* params = app.add_subcommand(
      "params", "Print every parameter table: names, types, units, defaults and rules");
  params->add_flag("--markdown", "As markdown, the only format (docs/parameters.md is this output)");
  // Listed for --help only: main() hands them to Python before parsing.
  app.add_subcommand("sweep", "Run variants of a scene file on Dask workers: one CSV row per run "
                              "and a PNG plot (`superdex sweep --help`)");
  app.add_subcommand("fit-batch", "Fit parameters to several observed trajectories on Dask "
                                  "workers (`superdex fit-batch --help`)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitInput;
  }

  if (params->parsed()) {
    superdex::PrintParameterMarkdown(std::cout);
    return 0;
  }
  if (!PositiveOption(run, "--dt", runArgs.dt) ||
      !PositiveOption(run, "--duration", runArgs.duration) ||
      !PositiveOption(fit, "--dt", fitDt) || !PositiveOption(gradient, "--dt", fitDt))
    return kExitInput;
  const std::optional<double> fitDtOption =
      (fit->parsed() ? fit : gradient)->count("--dt") ? std::optional<double>(fitDt) : std::nullopt;
  if (gradient->parsed()) return RunGradient(fitScene, observedPath, fitParams, fitDtOption);
  if (fit->parsed()) {
    superdex::FitMethod method;
    if (!superdex::ParseFitMethod(fitMethod, &method)) {
      std::cerr << "error: --method: unknown value \"" << fitMethod
                << "\" (expected one of: " << superdex::AllNames(method) << ")\n";
      return kExitInput;
    }
    return RunFit(fitScene, observedPath, fitParams, fitDtOption, method, maxIterations, fitOut,
                  fitSceneOut);
  }
  if (view->parsed()) return ViewCommand(viewTrajectory, viewOut);
  return RunCommand(runArgs, *run);
}

// `superdex sweep` and `superdex fit-batch` are the Python package's (python/superdex/__main__.py,
// on dask.distributed): replaces this process by `python3 -m superdex ARGS...` with the build's
// package first on PYTHONPATH (an installed package is found without it).
int ExecPython(int argc, char** argv) {
#ifdef SUPERDEX_PYTHON
  const std::string python = SUPERDEX_PYTHON, packageDir = SUPERDEX_PYTHON_DIR;
#else
  const std::string python = "python3", packageDir;
#endif
  if (!packageDir.empty() && access((packageDir + "/superdex/__init__.py").c_str(), R_OK) == 0) {
    const char* old = std::getenv("PYTHONPATH");
    const std::string path = packageDir + (old && *old ? ":" + std::string(old) : "");
    setenv("PYTHONPATH", path.c_str(), 1);
  }
  std::vector<std::string> words = {python, "-m", "superdex"};
  for (int i = 1; i < argc; ++i) words.emplace_back(argv[i]);
  std::vector<char*> args;
  for (auto& w : words) args.push_back(w.data());
  args.push_back(nullptr);
  execvp(python.c_str(), args.data());
  std::cerr << "error: " << argv[1] << " runs " << python << " -m superdex: " << std::strerror(errno)
            << "\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && (std::strcmp(argv[1], "sweep") == 0 || std::strcmp(argv[1], "fit-batch") == 0))
    return ExecPython(argc, argv);
  try {
    return Main(argc, argv);
  } catch (const std::bad_alloc&) {
    std::cerr << "error: out of memory\n";
  } catch (const std::exception& e) {
    std::cerr << "error: internal error: " << e.what() << "\n";
  }
  return kExitInternal;
}
