// Error against time step for the three stage-discrete dissipation modes and two integrators.
//   superdex_bench_dissipation
// Prints one table. Scenes (the tests' setups, see tests/core/test_friction_physics.cpp and
// tests/core/test_restitution.cpp):
//   incline      0.2 m, 1 kg cube on a 30° incline, μ = 0.5, c_n = 1 s/m, 1 s; error: relative
//                error of the sliding acceleration (least-squares fit over t in [0.3, 1] s of the
//                bottom-face centre) against g (sin30° − μ cos30°)
//   restitution  the same cube, gravity off, k = 1e6 Pa/m, launched flat at 4 m/s, c_n = 0.25 s/m
//                (c_n v = 1); error: |e − e_exact| with e_exact = 0.593624 from the exact
//                Hunt–Crossley impact integral (the spec's rational formula gives 0.58668)
// Columns: wall seconds per simulated second, Newton iterations per step, stages not converged.
#include <Eigen/QR>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/scene.h"

using namespace superdex;

namespace {

struct Result {
  double error = NAN;
  double wallPerSim = 0.0;
  double newtonPerStep = 0.0;
  int failed = 0;
};

RigidActorDesc Cube(double k, double mu, double cn) {
  RigidActorDesc d;
  d.name = "cube";
  d.shape.kind = RigidShapeKind::Box;
  d.shape.halfExtents = Eigen::Vector3d::Constant(0.1);
  d.shape.surfaceResolution = 2;
  d.mass = 1.0;
  d.contact.penaltyCoefficient = k;
  d.contact.coulombFrictionCoefficient = mu;
  d.contact.normalViscousDampingCoefficient = cn;
  return d;
}

RigidActorDesc Ground(const Eigen::Vector3d& n, double k, double mu, double cn) {
  RigidActorDesc d;
  d.name = "ground";
  d.dynamic = false;
  d.shape.kind = RigidShapeKind::Plane;
  d.shape.planeNormal = n;
  d.contact.penaltyCoefficient = k;
  d.contact.coulombFrictionCoefficient = mu;
  d.contact.normalViscousDampingCoefficient = cn;
  return d;
}

SceneSettings Settings(IntegrationMethod m, int mode, bool gravity) {
  SceneSettings s;
  s.integrator = m;
  s.eval.explicitNormals = mode == 0;
  s.eval.implicitNormalForceForDissipation = mode == 2;
  if (!gravity) s.gravity.setZero();
  return s;
}

Result Incline(IntegrationMethod m, int mode, double dt) {
  const double th = M_PI / 6;
  const Eigen::Vector3d n(std::sin(th), 0, std::cos(th)), down(std::cos(th), 0, -std::sin(th));
  Scene scene(Settings(m, mode, true));
  Error e;
  scene.AddRigidActor(Ground(n, 1e9, 0.5, 1.0), &e);
  RigidActorDesc c = Cube(1e9, 0.5, 1.0);
  c.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(th, Eigen::Vector3d::UnitY()));
  c.position = n * (0.1 + 1e-5);
  scene.AddRigidActor(c, &e);
  const ActorHandle h{1};
  const Eigen::Vector3d b0 = scene.State(h).p + scene.State(h).R * Eigen::Vector3d(0, 0, -0.1);
  std::vector<Eigen::Vector3d> rows;
  std::vector<double> ys;
  Result r;
  const int steps = static_cast<int>(std::lround(1.0 / dt));
  long newton = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) {
    StepReport rep;
    if (!scene.Step(dt, &rep, &e)) return r;
    newton += rep.newtonIterations;
    r.failed += rep.status != StageStatus::Converged;
    const double t = scene.Time();
    if (t >= 0.3 - 1e-12) {
      const Eigen::Vector3d b = scene.State(h).p + scene.State(h).R * Eigen::Vector3d(0, 0, -0.1);
      rows.emplace_back(1.0, t, t * t);
      ys.push_back((b - b0).dot(down));
    }
  }
  r.wallPerSim = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.newtonPerStep = double(newton) / steps;
  Eigen::MatrixXd A(rows.size(), 3);
  Eigen::VectorXd y(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    A.row(i) = rows[i].transpose();
    y[i] = ys[i];
  }
  const double a = 2 * A.colPivHouseholderQr().solve(y)[2];
  const double exact = 9.81 * (std::sin(th) - 0.5 * std::cos(th));
  r.error = std::abs(a - exact) / exact;
  return r;
}

Result Restitution(IntegrationMethod m, int mode, double dt) {
  Scene scene(Settings(m, mode, false));
  Error e;
  scene.AddRigidActor(Ground(Eigen::Vector3d::UnitZ(), 1e6, 0.5, 0.25), &e);
  RigidActorDesc c = Cube(1e6, 0.5, 0.25);
  c.position = Eigen::Vector3d(0, 0, 0.1 + 0.001 + 1e-4);
  c.linearVelocity = Eigen::Vector3d(0, 0, -4.0);
  scene.AddRigidActor(c, &e);
  Result r;
  long newton = 0;
  int steps = 0;
  bool touched = false;
  const auto t0 = std::chrono::steady_clock::now();
  while (steps < 100000) {
    StepReport rep;
    if (!scene.Step(dt, &rep, &e)) return r;
    ++steps;
    newton += rep.newtonIterations;
    r.failed += rep.status != StageStatus::Converged;
    if (rep.contact.activeSamples > 0) {
      touched = true;
    } else if (touched) {
      r.error = std::abs(scene.State(ActorHandle{1}).v.z() / 4.0 - 0.59362426004004);
      break;
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.wallPerSim = wall / scene.Time();
  r.newtonPerStep = double(newton) / steps;
  return r;
}

}  // namespace

int main() {
  const char* modes[3] = {"explicit", "reconstructed", "implicit"};
  std::printf("%-12s %-14s %-14s %8s %12s %12s %10s %6s\n", "scene", "integrator", "mode",
              "dt [s]", "error", "wall/sim s", "Newton/st", "fail");
  for (IntegrationMethod m : {IntegrationMethod::BackwardEuler, IntegrationMethod::BDF2}) {
    for (int mode = 0; mode < 3; ++mode) {
      for (double dt : {4e-3, 2e-3, 1e-3, 5e-4}) {
        const Result r = Incline(m, mode, dt);
        std::printf("%-12s %-14s %-14s %8.0e %12.3e %12.4g %10.2f %6d\n", "incline", ToString(m),
                    modes[mode], dt, r.error, r.wallPerSim, r.newtonPerStep, r.failed);
      }
      for (double dt : {4e-4, 2e-4, 1e-4}) {
        const Result r = Restitution(m, mode, dt);
        std::printf("%-12s %-14s %-14s %8.0e %12.3e %12.4g %10.2f %6d\n", "restitution",
                    ToString(m), modes[mode], dt, r.error, r.wallPerSim, r.newtonPerStep, r.failed);
      }
      std::fflush(stdout);
    }
  }
  return 0;
}
