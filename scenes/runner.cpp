#include "scenes/runner.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "geometry/number_text.h"
#include "scenes/limits.h"
#include "scenes/run_checks.h"
#include "scenes/trajectory_writer.h"
#include "scenes/viewer_page.h"
#include "scenes/vtk_writer.h"

namespace superdex {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

void Accumulate(const StepReport& rep, RunSummary* s) {
  ++s->steps;
  s->newtonIterations += rep.newtonIterations;
  s->fallbacks += rep.fallbacks;
  s->stages += rep.stages;
  s->freeStages += rep.freeStages;
  s->krylovIterations += rep.krylovIterations;
  s->krylovFallbacks += rep.krylovFallbacks;
  s->assemblySeconds += rep.assemblySeconds;
  s->factorizationSeconds += rep.factorizationSeconds;
  s->lineSearchSeconds += rep.lineSearchSeconds;
  s->maxNewtonIterations = std::max(s->maxNewtonIterations, rep.newtonIterations);
  (rep.status == StageStatus::Converged ? s->converged
   : rep.status == StageStatus::Stopped ? s->stopped
                                        : s->diverged) += 1;
  s->minDetF = std::min(s->minDetF, rep.minDetF);
  if (std::isfinite(rep.contact.minSignedDistance))
    s->maxPenetration = std::max(s->maxPenetration, -rep.contact.minSignedDistance);
}

// The run's files: the trajectory (a line per output frame) and the VTK frames.
class RunOutputs {
 public:
  // Opens the files and writes the first frame; a resumed run (`resume`) continues the
  // checkpoint's trajectory when it is the same file.
  bool Open(const SceneFile& file, const TrajectoryOptions& content, Scene& scene, double dt,
            const Checkpoint* resume, RunSummary* s, Error* error) {
    every_ = file.output.every;
    vtkEvery_ = file.output.vtkEvery;
    if (s->trajectoryPath.empty()) return resume || Write(scene, 0, nullptr, true, s, error);
    if (resume && resume->run.trajectoryPath == s->trajectoryPath) {
      if (!writer_.Reopen(s->trajectoryPath, resume->run.trajectoryBytes, scene, file.actorNames,
                          dt, error, content))
        return false;
      scheduledBytes_ = resume->run.trajectoryBytes;
      return true;
    }
    if (!writer_.Open(s->trajectoryPath, scene, file.actorNames, dt, error, content)) return false;
    scheduledBytes_ = writer_.Bytes();
    return resume || Write(scene, 0, nullptr, true, s, error);
  }
  // The frames due after `step` (all of them when `force`, e.g. at the last step).
  bool Write(Scene& scene, long long step, const StepReport* rep, bool force, RunSummary* s,
             Error* error) {
    const bool due = step % every_ == 0;
    if (writer_.IsOpen() && (force || due) && !writer_.WriteFrame(scene, step, rep, error))
      return false;
    if (due) scheduledBytes_ = writer_.Bytes();
    if (s->vtkDirectory.empty() || !(force || step % vtkEvery_ == 0)) return true;
    char name[40], contacts[40];
    std::snprintf(name, sizeof(name), "/frame_%06lld.vtk", step);
    std::snprintf(contacts, sizeof(contacts), "/contacts_%06lld.vtk", step);
    if (!WriteVtkFrame(scene, s->vtkDirectory + name, error) ||
        !WriteVtkContacts(scene, s->vtkDirectory + contacts, error))
      return false;
    ++s->vtkFrames;
    return true;
  }
  bool Close(Error* error) { return writer_.Close(error); }
  /// The trajectory's length after the last frame due by its schedule (a frame forced by the
  /// end of a run is not part of the uninterrupted run).
  long long ScheduledBytes() const { return scheduledBytes_; }

 private:
  TrajectoryWriter writer_;
  int every_ = 1, vtkEvery_ = 1;
  long long scheduledBytes_ = 0;
};

// The checkpoint after `step`: the scene's state and the run's accumulators.
bool SaveCheckpoint(const SceneFile& file, const RunOptions& options, const RunSummary& s,
                    const RunOutputs& outputs, long long step, double dt, Error* error) {
  Checkpoint c;
  c.sceneHash = file.textHash;
  c.scenePath = file.path;
  c.snapshot = file.scene->Save();
  CheckpointRun& r = c.run;
  r.step = step;
  r.dt = dt;
  r.integrator = ToString(file.scene->Settings().integrator);
  r.trajectoryPath = s.trajectoryPath;
  r.trajectoryBytes = outputs.ScheduledBytes();
  static_cast<RunAccumulators&>(r) = s;  // the summary's accumulators (kRunAccumulatorFields)
  return WriteCheckpoint(options.checkpointPath, c, error);
}

// Continues from a checkpoint: the scene's state and the summary's accumulators.
void Resume(const Checkpoint& c, Scene& scene, RunSummary* s) {
  scene.Restore(c.snapshot);
  const CheckpointRun& r = c.run;
  s->steps = static_cast<int>(r.step);
  static_cast<RunAccumulators&>(*s) = r;  // the summary's accumulators (kRunAccumulatorFields)
}

void CheckExpectations(const SceneFile& file, const Scene& scene, RunSummary* s) {
  const SceneExpectations& e = file.expect;
  std::ostringstream m;
  auto fail = [&] {
    s->expectationFailures.push_back(m.str());
    m.str("");
  };
  if (e.maxPenetration && s->maxPenetration > *e.maxPenetration) {
    m << "max penetration " << s->maxPenetration << " m > expected " << *e.maxPenetration << " m";
    fail();
  }
  if (e.maxRelativeEnergyDrift) {
    const double drift = std::abs(s->finalEnergy - s->initialEnergy) /
                         std::max(std::abs(s->initialEnergy), 1e-300);
    if (drift > *e.maxRelativeEnergyDrift) {
      m << "relative energy drift " << drift << " > expected " << *e.maxRelativeEnergyDrift;
      fail();
    }
  }
  if (e.allConverged && (s->stopped > 0 || s->diverged > 0)) {
    m << s->stopped << " stages stopped and " << s->diverged << " diverged; expected all converged";
    fail();
  }
  for (const auto& r : e.finalPositions) {
    for (size_t i = 0; i < file.actorNames.size(); ++i) {
      if (file.actorNames[i] != r.actor) continue;
      const Eigen::Vector3d p = scene.CenterOfMass({static_cast<int>(i)});
      const double err = (p - r.position).norm();
      if (err > r.tolerance) {
        m << "actor " << r.actor << " ends at (" << p.transpose() << "), " << err
          << " m from the expected (" << r.position.transpose() << ") > " << r.tolerance << " m";
        fail();
      }
    }
  }
}

}  // namespace

bool PlanSteps(double duration, double dt, long long* steps, std::string* error) {
  if (!(dt > 0 && std::isfinite(dt))) {
    *error = "dt: must be > 0 and finite, got " + NumberText(dt);
    return false;
  }
  if (!(duration > 0 && std::isfinite(duration))) {
    *error = "duration: must be > 0 and finite, got " + NumberText(duration);
    return false;
  }
  const double n = std::max(1.0, std::round(duration / dt));  // in double: no wrap-around
  if (!(n <= limits::kMaxSteps)) {
    *error = "duration / dt: " + NumberText(duration) + " s / " + NumberText(dt) +
             " s = " + NumberText(n) + " steps, beyond the limit of " +
             NumberText(limits::kMaxSteps) + " steps per run";
    return false;
  }
  *steps = static_cast<long long>(n);
  return true;
}

bool RunScene(SceneFile* file, const RunOptions& options, RunSummary* summary, Error* error) {
  Error scratch;
  if (!error) error = &scratch;
  Scene& scene = *file->scene;
  RunSummary s;
  auto end = [&](RunEnd how, const std::string& message) {
    s.end = how;
    if (how == RunEnd::InvalidInput) Fail(error, message);
    else s.endMessage = message;
    *summary = s;
    return false;
  };
  const double dt = options.dt.value_or(file->dt);
  long long steps = 0;
  std::string why;
  if (!PlanSteps(options.duration.value_or(file->duration), dt, &steps, &why))
    return end(RunEnd::InvalidInput, why);
  if (std::string m = Validate(file->output, "output."); !m.empty())  // e.g. every = 0
    return end(RunEnd::InvalidInput, m);
  const PenetrationBound bound = MakePenetrationBound(*file);
  if (std::string m = CheckInitialState(file, bound); !m.empty())
    return end(RunEnd::InvalidInput, m);
  const Checkpoint* resume = options.resume;
  if (resume && resume->run.step >= steps)
    return end(RunEnd::InvalidInput,
               "--resume: the checkpoint is at step " + std::to_string(resume->run.step) +
                   " and the run has " + std::to_string(steps) + " steps: nothing is left to run");
  s.trajectoryPath = options.out.value_or(file->output.path);
  if (options.view && s.trajectoryPath.empty())
    return end(RunEnd::InvalidInput,
               "--view: the viewer page needs a trajectory (output.path or --out)");
  s.vtkDirectory = options.vtk.value_or(file->output.vtk);
  TrajectoryOptions content;
  content.contacts = options.contacts.value_or(file->output.contacts);
  RunOutputs outputs;
  if (resume) {
    Resume(*resume, scene, &s);
  } else {
    s.initialEnergy = scene.Energies().Total();
    s.maxPenetration = std::max(0.0, -scene.ContactState().minSignedDistance);
  }
  if (!outputs.Open(*file, content, scene, dt, resume, &s, error))
    return end(resume ? RunEnd::InvalidInput : RunEnd::OutputFailed, error->message);
  bool finite = true;
  for (long long k = resume ? resume->run.step + 1 : 1; k <= steps; ++k) {
    StepReport rep;
    const Clock::time_point t0 = Clock::now();
    if (!scene.Step(dt, &rep, error)) return end(RunEnd::InvalidInput, error->message);
    const Clock::time_point t1 = Clock::now();
    s.wallSeconds += Seconds(t0, t1);
    Accumulate(rep, &s);
    const std::string failed = CheckStep(*file, k, rep, bound, &finite);
    const int signal = options.interrupted ? options.interrupted() : 0;
    const bool last = k == steps || !failed.empty() || signal != 0;
    if (finite && !outputs.Write(scene, k, &rep, last, &s, error)) {
      s.end = RunEnd::OutputFailed;
      s.endMessage = error->message;
      break;
    }
    if (!failed.empty()) {
      s.end = RunEnd::Unphysical;
      s.endMessage = failed;
      break;
    }
    const bool checkpoint = options.checkpointEvery > 0 &&
                            (k % options.checkpointEvery == 0 || signal != 0);
    if (checkpoint && !SaveCheckpoint(*file, options, s, outputs, k, dt, error)) {
      s.end = RunEnd::OutputFailed;
      s.endMessage = error->message;
      break;
    }
    if (signal != 0) {
      s.end = RunEnd::Interrupted;
      s.signal = signal;
      s.endMessage = "stopped by signal " + std::to_string(signal) + " after step " +
                     std::to_string(k) + " of " + std::to_string(steps) + " (t = " +
                     NumberText(scene.Time()) + " s); its frame is written" +
                     (checkpoint ? " and the checkpoint " + options.checkpointPath : "");
      break;
    }
    if (options.progress) options.progress(rep, double(k) / steps);
    s.outputSeconds += Seconds(t1, Clock::now());
  }
  Error closing;
  if (!outputs.Close(&closing) && s.end != RunEnd::OutputFailed) {
    s.end = RunEnd::OutputFailed;
    s.endMessage = closing.message;
  }
  s.simulatedSeconds = scene.Time();
  s.finalEnergy = finite ? scene.Energies().Total() : NAN;
  if (options.view && s.end != RunEnd::OutputFailed) {  // also of a run that ended early
    const Clock::time_point t0 = Clock::now();
    ViewerPageInfo page;
    Error viewError;
    if (WriteViewerPage(s.trajectoryPath, ViewerPagePath(s.trajectoryPath), &page, &viewError)) {
      s.viewerPage = page.path;
      s.viewerSeconds = Seconds(t0, Clock::now());
    } else if (s.end == RunEnd::Completed) {
      s.end = RunEnd::OutputFailed;
      s.endMessage = viewError.message;
    } else {
      s.endMessage += "; the viewer page was not written: " + viewError.message;
    }
  }
  if (s.end != RunEnd::Completed) error->message = s.endMessage;
  if (s.end == RunEnd::Completed) CheckExpectations(*file, scene, &s);
  *summary = s;
  return s.end == RunEnd::Completed;
}

void PrintSummary(const SceneFile& file, const RunSummary& s, std::ostream& os) {
  const Scene& scene = *file.scene;
  os << "\n== superdex run: " << file.path << " ==\n";
  if (!file.description.empty()) os << file.description << "\n";
  os << std::setprecision(4);
  os << "actors            " << scene.NumActors() << " (integrator "
     << ToString(scene.Settings().integrator) << ")\n";
  os << "steps             " << s.steps << " of dt = " << file.scene->Time() / std::max(1, s.steps)
     << " s, simulated " << s.simulatedSeconds << " s\n";
  os << "wall time         " << s.wallSeconds << " s ("
     << s.wallSeconds / std::max(s.simulatedSeconds, 1e-300)
     << " s per simulated second; in the steps)\n";
  os << "output            " << s.outputSeconds << " s (trajectory, VTK frames, progress)\n";
  os << "Newton iterations " << double(s.newtonIterations) / std::max(1, s.steps)
     << " per step (max " << s.maxNewtonIterations << ")\n";
  if (s.freeStages > 0)
    os << "free stages       " << s.freeStages << " of " << s.stages
       << " in closed form (no active contact sample: no Newton iteration)\n";
  if (s.krylovIterations > 0)
    os << "Krylov iterations " << double(s.krylovIterations) / std::max(1L, s.newtonIterations)
       << " per Newton iteration (" << s.krylovFallbacks << " solves fell back to direct)\n";
  if (s.fallbacks > 0)
    os << "fallbacks         " << s.fallbacks
       << " stages: residual solve failed, re-solved with explicit normals\n";
  if (s.wallSeconds > 0) {
    const double w = 100.0 / s.wallSeconds;
    os << "time split        assembly " << s.assemblySeconds * w << " %, linear solves "
       << s.factorizationSeconds * w << " %, line search " << s.lineSearchSeconds * w
       << " % of the wall time\n";
  }
  os << "stages            " << s.converged << " converged, " << s.stopped << " stopped, "
     << s.diverged << " diverged\n";
  os << "max penetration   " << s.maxPenetration * 1e3 << " mm (max of −φ at step ends)\n";
  if (std::isfinite(s.minDetF))
    os << "soft tets         min det F " << s.minDetF
       << (s.minDetF > 0 ? " (no tet inverted)" : " (INVERTED TETS)") << "\n";
  // The change is physical where contacts dissipate (friction, damping) or drives add work;
  // without them it is the integrator's error.
  const double change = s.finalEnergy - s.initialEnergy;
  os << "energy            " << s.initialEnergy << " J -> " << s.finalEnergy << " J (change "
     << change << " J, " << 100.0 * change / std::max(std::abs(s.initialEnergy), 1e-300)
     << " %; friction and damping dissipate, joint drives and kinematic actors do work, the rest "
        "is integration error)\n";
  if (!s.trajectoryPath.empty()) os << "trajectory        " << s.trajectoryPath << "\n";
  if (!s.viewerPage.empty())
    os << "viewer page       " << s.viewerPage << " (open it in a browser)\n";
  if (s.vtkFrames > 0)
    os << "VTK frames        " << s.vtkFrames << " in " << s.vtkDirectory
       << "/ (open the series in ParaView; cell data: traction, pressure)\n";
  if (s.end == RunEnd::Interrupted) os << "INTERRUPTED       " << s.endMessage << "\n";
  if (s.end == RunEnd::Unphysical) os << "RUN FAILED        " << s.endMessage << "\n";
  if (s.end == RunEnd::OutputFailed) os << "OUTPUT FAILED     " << s.endMessage << "\n";
  if (s.end != RunEnd::Completed) {
    os << "expectations      not checked (the run ended early)\n";
  } else if (s.expectationFailures.empty()) {
    os << "expectations      " << (file.expect.maxPenetration || file.expect.allConverged ||
                                   file.expect.maxRelativeEnergyDrift ||
                                   !file.expect.finalPositions.empty()
                                       ? "all hold"
                                       : "none given")
       << "\n";
  } else {
    for (const auto& f : s.expectationFailures) os << "EXPECTATION FAILED: " << f << "\n";
  }
}

}  // namespace superdex
