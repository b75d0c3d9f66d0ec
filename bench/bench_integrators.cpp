// Error against wall time for every integrator on three scenes.
//   superdex_bench_integrators [CSV_PATH]
// Prints a table and writes CSV (scene, method, dt, error, wall seconds per simulated second,
// Newton iterations per step, stages not converged) for bench/plot_integrators.py.
//   drop      scenes/data/drop.json (k = 1e9): |z(1 s) − z_ref(1 s)| after the first bounce [m];
//             reference: DIRK33 at Δt = 2.5e-5
//   incline   30° incline, μ = 0.5, c_n = 1 s/m, 1 s: relative error of the sliding acceleration
//             against g (sin30° − μ cos30°) (bottom-face centre, fit over [0.3, 1] s)
//   tumbling  free asymmetric box, 1 s: ‖R(1 s) − R_ref‖_F, reference RK4 on Euler's equations
#include <Eigen/QR>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "core/dynamics/integrators.h"
#include "core/model/rigid_math.h"
#include "scenes/scene_file.h"

using namespace superdex;

namespace {

struct Result {
  double error = NAN, wall = 0.0, newton = 0.0;
  int failed = 0;
};

const IntegrationMethod kMethods[] = {
    IntegrationMethod::BackwardEuler,    IntegrationMethod::BDF2,   IntegrationMethod::BDF3,
    IntegrationMethod::DIRK22,           IntegrationMethod::DIRK23, IntegrationMethod::DIRK33,
    IntegrationMethod::SymplecticDIRK12, IntegrationMethod::SymplecticDIRK22};

// Steps `scene` to time T; calls sample(scene) after every step.
template <typename Sample>
Result Run(Scene& scene, double dt, double T, Sample sample) {
  Result r;
  Error e;
  const int steps = static_cast<int>(std::lround(T / dt));
  long newton = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) {
    StepReport rep;
    if (!scene.Step(dt, &rep, &e)) return r;
    newton += rep.newtonIterations;
    r.failed += rep.status != StageStatus::Converged;
    sample(scene);
  }
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / T;
  r.newton = double(newton) / steps;
  return r;
}

double DropHeight(IntegrationMethod m, double dt, Result* r) {
  SceneFile f;
  Error e;
  if (!LoadSceneFile(std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/drop.json", &f, &e)) {
    std::fprintf(stderr, "error: %s\n", e.message.c_str());
    std::exit(2);
  }
  f.scene->SetIntegrator(m, &e);
  *r = Run(*f.scene, dt, 1.0, [](Scene&) {});
  return f.scene->State(ActorHandle{1}).p.z();
}

Result Incline(IntegrationMethod m, double dt) {
  const double th = M_PI / 6;
  const Eigen::Vector3d n(std::sin(th), 0, std::cos(th)), down(std::cos(th), 0, -std::sin(th));
  SceneSettings s;
  s.integrator = m;
  Scene scene(s);
  Error e;
  RigidActorDesc g;
  g.name = "ground";
  g.dynamic = false;
  g.shape.kind = RigidShapeKind::Plane;
  g.shape.planeNormal = n;
  g.contact.normalViscousDampingCoefficient = 1.0;
  scene.AddRigidActor(g, &e);
  RigidActorDesc c;
  c.name = "cube";
  c.shape.kind = RigidShapeKind::Box;
  c.shape.halfExtents = Eigen::Vector3d::Constant(0.1);
  c.shape.surfaceResolution = 2;
  c.mass = 1.0;
  c.contact.normalViscousDampingCoefficient = 1.0;
  c.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(th, Eigen::Vector3d::UnitY()));
  c.position = n * (0.1 + 1e-5);
  scene.AddRigidActor(c, &e);
  const ActorHandle h{1};
  const Eigen::Vector3d b0 = scene.State(h).p + scene.State(h).R * Eigen::Vector3d(0, 0, -0.1);
  std::vector<Eigen::Vector3d> rows;
  std::vector<double> ys;
  Result r = Run(scene, dt, 1.0, [&](Scene& sc) {
    if (sc.Time() < 0.3 - 1e-12) return;
    const Eigen::Vector3d b = sc.State(h).p + sc.State(h).R * Eigen::Vector3d(0, 0, -0.1);
    rows.emplace_back(1.0, sc.Time(), sc.Time() * sc.Time());
    ys.push_back((b - b0).dot(down));
  });
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

const Eigen::Vector3d kHalf(0.3, 0.2, 0.1), kOmega0(0.4, 2.5, 1.0);

Eigen::Matrix3d TumblingReference() {
  const Eigen::Vector3d l = 2.0 * kHalf;
  const Eigen::Vector3d I(l.y() * l.y() + l.z() * l.z(), l.x() * l.x() + l.z() * l.z(),
                          l.x() * l.x() + l.y() * l.y());
  auto f = [&](const Eigen::Vector3d& w) {
    return Eigen::Vector3d(I.cwiseProduct(w).cross(w).cwiseQuotient(I));
  };
  const int n = 200000;
  const double h = 1.0 / n;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d w = kOmega0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Matrix3d k1 = R * Skew(w);
    const Eigen::Vector3d l1 = f(w);
    const Eigen::Matrix3d k2 = (R + 0.5 * h * k1) * Skew(w + 0.5 * h * l1);
    const Eigen::Vector3d l2 = f(w + 0.5 * h * l1);
    const Eigen::Matrix3d k3 = (R + 0.5 * h * k2) * Skew(w + 0.5 * h * l2);
    const Eigen::Vector3d l3 = f(w + 0.5 * h * l2);
    const Eigen::Matrix3d k4 = (R + h * k3) * Skew(w + h * l3);
    const Eigen::Vector3d l4 = f(w + h * l3);
    R += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    w += h / 6 * (l1 + 2 * l2 + 2 * l3 + l4);
  }
  return NearestRotation(R);
}

Result Tumbling(IntegrationMethod m, double dt, const Eigen::Matrix3d& ref) {
  SceneSettings s;
  s.integrator = m;
  s.gravity.setZero();
  s.solver.absoluteTolerance = 1e-24;
  s.solver.relativeTolerance = 1e-14;
  s.solver.stepTolerance = 1e-14;
  Scene scene(s);
  Error e;
  RigidActorDesc b;
  b.name = "tumbler";
  b.shape.kind = RigidShapeKind::Box;
  b.shape.halfExtents = kHalf;
  b.shape.surfaceResolution = 1;
  b.mass = 2.0;
  b.angularVelocity = kOmega0;
  b.colliderType = ColliderType::None;
  scene.AddRigidActor(b, &e);
  Result r = Run(scene, dt, 1.0, [](Scene&) {});
  r.error = (scene.State(ActorHandle{0}).R - ref).norm();
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string csvPath = argc > 1 ? argv[1] : "out/bench_integrators.csv";
  std::ofstream csv(csvPath);
  if (!csv) {
    std::fprintf(stderr, "error: cannot write %s (does its folder exist?)\n", csvPath.c_str());
    return 2;
  }
  csv << "scene,method,dt,error,wall_per_sim_s,newton_per_step,failed\n";
  std::printf("%-9s %-17s %8s %12s %12s %10s %5s\n", "scene", "method", "dt [s]", "error",
              "wall/sim s", "Newton/st", "fail");
  auto emit = [&](const char* scene, IntegrationMethod m, double dt, const Result& r) {
    std::printf("%-9s %-17s %8.1e %12.3e %12.4g %10.2f %5d\n", scene, ToString(m), dt, r.error,
                r.wall, r.newton, r.failed);
    std::fflush(stdout);
    csv << scene << "," << ToString(m) << "," << dt << "," << r.error << "," << r.wall << ","
        << r.newton << "," << r.failed << "\n";
  };
  Result unused;
  const double zRef = DropHeight(IntegrationMethod::DIRK33, 2.5e-5, &unused);
  for (IntegrationMethod m : kMethods)
    for (double dt : {1e-3, 5e-4, 2.5e-4, 1.25e-4}) {
      Result r;
      const double z = DropHeight(m, dt, &r);
      r.error = std::abs(z - zRef);
      emit("drop", m, dt, r);
    }
  for (IntegrationMethod m : kMethods)
    for (double dt : {4e-3, 2e-3, 1e-3, 5e-4}) emit("incline", m, dt, Incline(m, dt));
  const Eigen::Matrix3d ref = TumblingReference();
  for (IntegrationMethod m : kMethods)
    for (double dt : {4e-2, 2e-2, 1e-2, 5e-3}) emit("tumbling", m, dt, Tumbling(m, dt, ref));
  std::printf("CSV: %s\n", csvPath.c_str());
  return 0;
}
