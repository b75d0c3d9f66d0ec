// Command line, metrics and result line of the peer adapters. Metric definitions (README.md):
//   drop           e = sqrt((E_after − g z_c) / (E_before − g z_c)) from the ballistic energy
//                  per unit mass E = v²/2 + g z, at the last sample before and the first after
//                  the bounce with the sphere > 1 cm above the plane; error |1 − e|
//   incline        a from a least-squares parabola of the distance along the slope over
//                  [0.5 s, T]; error |a − a_exact| / a_exact, a_exact = g (sin θ − μ cos θ)
//   incline_creep  creep speed |s(T) − s(T/2)| / (T/2), s the distance along the slope, once the
//                  contact has settled; error = that speed (also: |s(1 s)|)
//   stack          top box: horizontal drift |xy(T) − xy(0)|, vertical drift |z(T) − z(t_s)|
//                  after settling (t_s = min(1 s, T/2)); error = hypot of both
//   pile           error = max penetration
//   tumble         relative drift of the rotational energy and of the world angular momentum
//                  at T; error = the energy drift
#include "peer_run.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

namespace superdex::peers {
namespace {

using json = nlohmann::json;

json Finite(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

const PeerBody* FirstStatic(const PeerScene& s) {
  for (const PeerBody& b : s.bodies)
    if (!b.dynamic) return &b;
  return nullptr;
}

json DropMetrics(const PeerScene& s, const std::vector<TrackSample>& tr) {
  const PeerBody& ball = s.bodies[s.LastDynamic()];
  const PeerBody* plane = FirstStatic(s);
  const Eigen::Vector3d n = plane ? plane->normal : Eigen::Vector3d::UnitZ();
  const double g = s.gravity.norm();
  auto height = [&](const TrackSample& x) { return (x.p - (plane ? plane->position : Eigen::Vector3d::Zero())).dot(n) - ball.radius; };
  auto energy = [&](const TrackSample& x) { return 0.5 * x.v.squaredNorm() + g * height(x); };
  double before = NAN, after = NAN;
  bool bounced = false;
  for (const TrackSample& x : tr) {
    const bool free = height(x) > 0.01;
    const double vn = x.v.dot(n);
    if (!bounced && free && vn < 0) before = energy(x);
    if (!free && vn > 0) bounced = true;
    if (bounced && free && vn > 0) {
      after = energy(x);
      break;
    }
  }
  const double e = std::sqrt(std::max(0.0, after) / before);
  return {{"restitution", Finite(e)}, {"error", Finite(std::isfinite(e) ? std::abs(1 - e) : 1.0)}};
}

Eigen::Vector3d Downhill(const PeerScene& s) {
  const PeerBody* plane = FirstStatic(s);
  const Eigen::Vector3d n = plane->normal;
  return (s.gravity - s.gravity.dot(n) * n).normalized();
}

json InclineMetrics(const PeerScene& s, const std::vector<TrackSample>& tr) {
  const Eigen::Vector3d d = Downhill(s);
  const PeerBody* plane = FirstStatic(s);
  const double g = s.gravity.norm();
  const double cosTh = std::abs(plane->normal.dot(s.gravity.normalized()));
  const double sinTh = std::sqrt(std::max(0.0, 1 - cosTh * cosTh));
  const double exact = g * (sinTh - s.PairFriction() * cosTh);
  const double t0 = 0.5, T = tr.back().t;
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Atb = Eigen::Vector3d::Zero();
  for (const TrackSample& x : tr) {
    if (x.t < t0 - 1e-12) continue;
    const Eigen::Vector3d row(1, x.t, x.t * x.t);
    AtA += row * row.transpose();
    Atb += row * (x.p - tr.front().p).dot(d);
  }
  const double a = 2 * AtA.ldlt().solve(Atb)[2];
  return {{"acceleration", Finite(a)}, {"exact_acceleration", exact}, {"fit_window", {t0, T}},
          {"error", Finite(std::abs(a - exact) / std::abs(exact))}};
}

json CreepMetrics(const PeerScene& s, const std::vector<TrackSample>& tr) {
  const Eigen::Vector3d d = Downhill(s);
  const double T = tr.back().t;
  auto at = [&](double time) {  // distance along the slope at the last sample up to `time`
    double out = NAN;
    for (const TrackSample& x : tr)
      if (x.t <= time + 1e-9) out = (x.p - tr.front().p).dot(d);
    return out;
  };
  const double speed = std::abs(at(T) - at(0.5 * T)) / (0.5 * T);
  return {{"creep_speed", Finite(speed)}, {"creep_1s", Finite(std::abs(at(1.0)))},
          {"error", Finite(speed)}};
}

json StackMetrics(const PeerScene& s, const std::vector<TrackSample>& tr) {
  double zGeom = 0.0;  // top centre with every box resting exactly on the one below
  int top = s.LastDynamic();
  for (int i = 0; i <= top; ++i)
    if (s.bodies[i].dynamic) zGeom += 2 * s.bodies[i].halfExtents.z();
  zGeom -= s.bodies[top].halfExtents.z();
  const double T = tr.back().t, ts = std::min(1.0, 0.5 * T);
  Eigen::Vector3d settled = tr.front().p;
  for (const TrackSample& x : tr)
    if (x.t <= ts + 1e-9) settled = x.p;
  const Eigen::Vector3d end = tr.back().p;
  const double horizontal = (end - tr.front().p).head<2>().norm();
  const double vertical = std::abs(end.z() - settled.z());
  return {{"horizontal_drift", Finite(horizontal)}, {"vertical_drift", Finite(vertical)},
          {"sag", Finite(zGeom - end.z())}, {"settle_time", ts},
          {"error", Finite(std::hypot(horizontal, vertical))}};
}

json TumbleMetrics(const PeerScene& s, const std::vector<TrackSample>& tr) {
  const PeerBody& b = s.bodies[s.LastDynamic()];
  auto world = [&](const TrackSample& x) {
    const Eigen::Matrix3d R = x.q.toRotationMatrix();
    return Eigen::Matrix3d(R * b.inertia.asDiagonal() * R.transpose());
  };
  auto energy = [&](const TrackSample& x) { return 0.5 * x.w.dot(world(x) * x.w); };
  auto momentum = [&](const TrackSample& x) { return Eigen::Vector3d(world(x) * x.w); };
  const double e0 = energy(tr.front()), e1 = energy(tr.back());
  const Eigen::Vector3d l0 = momentum(tr.front()), l1 = momentum(tr.back());
  const double de = std::abs(e1 - e0) / e0;
  return {{"energy_drift", Finite(de)}, {"momentum_drift", Finite((l1 - l0).norm() / l0.norm())},
          {"error", Finite(de)}};
}

}  // namespace

json SceneMetrics(const PeerScene& s, const std::vector<TrackSample>& tr) {
  if (tr.size() < 2) return {{"error", nullptr}};
  if (s.name == "drop") return DropMetrics(s, tr);
  if (s.name == "incline") return InclineMetrics(s, tr);
  if (s.name == "incline_creep") return CreepMetrics(s, tr);
  if (s.name == "stack") return StackMetrics(s, tr);
  if (s.name == "tumble") return TumbleMetrics(s, tr);
  return {};  // pile: the penetration is the metric
}

bool ParseOptions(int argc, char** argv, PeerOptions* o, std::string* message) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) {
      *message = a + ": missing value";
      return false;
    }
    const std::string v = argv[++i];
    if (a == "--scene") o->scene = v;
    else if (a == "--dt") o->dt = std::atof(v.c_str());
    else if (a == "--duration") o->duration = std::atof(v.c_str());
    else if (a == "--solver") o->solver = v;
    else if (a == "--iterations") o->iterations = std::atoi(v.c_str());
    else if (a == "--timeconst") o->timeconst = std::atof(v.c_str());
    else if (a == "--out") o->out = v;
    else if (a == "--model") o->model = v;
    else {
      *message = a + ": unknown option";
      return false;
    }
  }
  if (o->scene.empty() || !(o->dt > 0)) {
    *message = "usage: --scene NAME|FILE.json --dt DT [--duration S] [--solver NAME] "
               "[--iterations N] [--timeconst S] [--out TRACK.jsonl] [--model MJCF.xml]";
    return false;
  }
  return true;
}

Recorder::Recorder(const PeerScene& scene, const PeerOptions& options, std::string engine)
    : scene_(scene), options_(options), engine_(std::move(engine)) {}

bool Recorder::Add(const TrackSample& s, double penetration) {
  const bool finite = s.p.allFinite() && s.v.allFinite() && s.w.allFinite() && std::isfinite(penetration);
  if (!finite) {
    nan_ = true;
    return false;
  }
  maxPenetration_ = std::max(maxPenetration_, penetration);
  track_.push_back(s);
  return true;
}

void Recorder::Print(double wall, double simulated, const json& settings) const {
  json r;
  r["engine"] = engine_;
  r["scene"] = scene_.name;
  r["dt"] = options_.dt;
  r["wall_seconds"] = wall;
  r["simulated_seconds"] = simulated;
  r["wall_per_simulated_second"] = wall / std::max(simulated, 1e-300);
  r["max_penetration"] = maxPenetration_;
  r["nan"] = nan_;
  json m = nan_ ? json{{"error", nullptr}} : SceneMetrics(scene_, track_);
  if (!m.contains("error")) m["error"] = maxPenetration_;
  r["failed"] = nan_ || m["error"].is_null() || !failure_.empty();
  if (!failure_.empty()) r["failure"] = failure_;
  r["metrics"] = m;
  r["settings"] = settings;
  std::cout << r.dump() << std::endl;
  if (!options_.out.empty()) {
    std::ofstream out(options_.out);
    for (const TrackSample& x : track_)
      out << json{{"t", x.t},
                  {"p", {x.p.x(), x.p.y(), x.p.z()}},
                  {"q", {x.q.x(), x.q.y(), x.q.z(), x.q.w()}},
                  {"v", {x.v.x(), x.v.y(), x.v.z()}},
                  {"w", {x.w.x(), x.w.y(), x.w.z()}}}
                 .dump()
          << '\n';
  }
}

bool StartRun(int argc, char** argv, PeerOptions* options, PeerScene* scene) {
  std::string message;
  if (!ParseOptions(argc, argv, options, &message)) {
    std::cerr << message << "\n";
    return false;
  }
  if (!LoadPeerScene(options->scene, scene, &message)) {
    std::cerr << "error: " << message << "\n";
    return false;
  }
  return true;
}

}  // namespace superdex::peers
