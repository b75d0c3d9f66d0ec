#include "scenes/runner.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>

#include "scenes/trajectory_writer.h"
#include "scenes/viewer_page.h"
#include "scenes/vtk_writer.h"

namespace superdex {

bool RunScene(SceneFile* file, const RunOptions& options, RunSummary* summary, Error* error) {
  Scene& scene = *file->scene;
  const double dt = options.dt.value_or(file->dt);
  const double duration = options.duration.value_or(file->duration);
  if (!(dt > 0 && std::isfinite(dt))) return Fail(error, "dt: must be > 0");
  if (!(duration > 0 && std::isfinite(duration))) return Fail(error, "duration: must be > 0");
  RunSummary s;
  s.trajectoryPath = options.out.value_or(file->output.path);
  if (options.view && s.trajectoryPath.empty())
    return Fail(error, "--view: the viewer page needs a trajectory (output.path or --out)");
  TrajectoryWriter writer;
  if (!s.trajectoryPath.empty()) {
    TrajectoryOptions content;
    content.contacts = options.contacts.value_or(file->output.contacts);
    if (!writer.Open(s.trajectoryPath, scene, file->actorNames, dt, error, content)) return false;
    writer.WriteFrame(scene, 0, nullptr);
  }
  s.vtkDirectory = options.vtk.value_or(file->output.vtk);
  auto writeVtk = [&](int step) {
    char name[32];
    std::snprintf(name, sizeof(name), "/frame_%06d.vtk", step);
    if (!WriteVtkFrame(scene, s.vtkDirectory + name, error)) return false;
    ++s.vtkFrames;
    return true;
  };
  if (!s.vtkDirectory.empty() && !writeVtk(0)) return false;
  s.initialEnergy = scene.Energies().Total();
  s.maxPenetration = std::max(0.0, -scene.ContactState().minSignedDistance);
  const int steps = std::max(1, static_cast<int>(std::llround(duration / dt)));
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  for (int k = 1; k <= steps; ++k) {
    StepReport rep;
    const Clock::time_point t0 = Clock::now();
    if (!scene.Step(dt, &rep, error)) return false;
    const Clock::time_point t1 = Clock::now();
    s.wallSeconds += seconds(t0, t1);
    ++s.steps;
    s.newtonIterations += rep.newtonIterations;
    s.fallbacks += rep.fallbacks;
    s.stages += rep.stages;
    s.freeStages += rep.freeStages;
    s.krylovIterations += rep.krylovIterations;
    s.krylovFallbacks += rep.krylovFallbacks;
    s.assemblySeconds += rep.assemblySeconds;
    s.factorizationSeconds += rep.factorizationSeconds;
    s.lineSearchSeconds += rep.lineSearchSeconds;
    s.maxNewtonIterations = std::max(s.maxNewtonIterations, rep.newtonIterations);
    (rep.status == StageStatus::Converged ? s.converged
     : rep.status == StageStatus::Stopped ? s.stopped
                                          : s.diverged) += 1;
    s.minDetF = std::min(s.minDetF, rep.minDetF);
    if (std::isfinite(rep.contact.minSignedDistance))
      s.maxPenetration = std::max(s.maxPenetration, -rep.contact.minSignedDistance);
    if (writer.IsOpen() && (k % file->output.every == 0 || k == steps))
      writer.WriteFrame(scene, k, &rep);
    if (!s.vtkDirectory.empty() && (k % file->output.vtkEvery == 0 || k == steps) && !writeVtk(k))
      return false;
    if (options.progress) options.progress(rep, double(k) / steps);
    s.outputSeconds += seconds(t1, Clock::now());
  }
  s.simulatedSeconds = scene.Time();
  s.finalEnergy = scene.Energies().Total();
  if (options.view) {
    writer.Close();
    const Clock::time_point t0 = Clock::now();
    ViewerPageInfo page;
    if (!WriteViewerPage(s.trajectoryPath, ViewerPagePath(s.trajectoryPath), &page, error))
      return false;
    s.viewerPage = page.path;
    s.viewerSeconds = seconds(t0, Clock::now());
  }

  const SceneExpectations& e = file->expect;
  auto fail = [&](const std::string& m) { s.expectationFailures.push_back(m); };
  std::ostringstream m;
  if (e.maxPenetration && s.maxPenetration > *e.maxPenetration) {
    m.str("");
    m << "max penetration " << s.maxPenetration << " m > expected " << *e.maxPenetration << " m";
    fail(m.str());
  }
  if (e.maxRelativeEnergyDrift) {
    const double drift = std::abs(s.finalEnergy - s.initialEnergy) /
                         std::max(std::abs(s.initialEnergy), 1e-300);
    if (drift > *e.maxRelativeEnergyDrift) {
      m.str("");
      m << "relative energy drift " << drift << " > expected " << *e.maxRelativeEnergyDrift;
      fail(m.str());
    }
  }
  if (e.allConverged && (s.stopped > 0 || s.diverged > 0)) {
    m.str("");
    m << s.stopped << " stages stopped and " << s.diverged << " diverged; expected all converged";
    fail(m.str());
  }
  for (const auto& r : e.finalPositions) {
    for (size_t i = 0; i < file->actorNames.size(); ++i) {
      if (file->actorNames[i] != r.actor) continue;
      const Eigen::Vector3d p = scene.CenterOfMass({static_cast<int>(i)});
      const double err = (p - r.position).norm();
      if (err > r.tolerance) {
        m.str("");
        m << "actor " << r.actor << " ends at (" << p.transpose() << "), " << err
          << " m from the expected (" << r.position.transpose() << ") > " << r.tolerance << " m";
        fail(m.str());
      }
    }
  }
  *summary = s;
  return true;
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
  const double drift = s.finalEnergy - s.initialEnergy;
  os << "energy            " << s.initialEnergy << " J -> " << s.finalEnergy << " J (drift "
     << drift << " J, " << 100.0 * drift / std::max(std::abs(s.initialEnergy), 1e-300)
     << " %)\n";
  if (!s.trajectoryPath.empty()) os << "trajectory        " << s.trajectoryPath << "\n";
  if (!s.viewerPage.empty())
    os << "viewer page       " << s.viewerPage << " (open it in a browser)\n";
  if (s.vtkFrames > 0)
    os << "VTK frames        " << s.vtkFrames << " in " << s.vtkDirectory
       << "/ (open the series in ParaView; cell data: traction, pressure)\n";
  if (s.expectationFailures.empty()) {
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
