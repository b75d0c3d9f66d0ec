// superdex_peer_mujoco: runs a superdex reference scene in MuJoCo (an MJCF model generated from
// the scene file) and prints one JSON result line (wall time, metrics, failure).
//   superdex_peer_mujoco --scene drop --dt 1e-3 [--duration S] [--solver newton|cg|pgs]
#include <mujoco/mujoco.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "contact_match.h"
#include "peer_run.h"

namespace sp = superdex::peers;

namespace {

constexpr double kDmin = 0.9, kDmax = 0.95;  // MuJoCo's default solimp (0.9 0.95 0.001 0.5 2)

/// The contact reference (solref) derived from superdex's law; see README.md.
struct ContactRef {
  double solref0 = 0.02, solref1 = 1.0;
  std::string rule;
};

ContactRef MatchContact(const sp::PeerScene& s, double dt, double timeconst) {
  ContactRef c;
  if (timeconst > 0) {
    c.solref0 = std::max(timeconst, 2 * dt);
    c.rule = "timeconst given on the command line";
    return c;
  }
  const int i = s.LastDynamic();
  const double g = s.gravity.norm();
  if (i < 0 || g == 0) {
    c.rule = "no contact";
    return c;
  }
  const sp::PeerBody& b = s.bodies[i];
  const sp::PeerBody* ground = nullptr;
  for (const sp::PeerBody& x : s.bodies)
    if (!x.dynamic) ground = ground ? ground : &x;
  const bool elastic = s.PairFriction() == 0 && b.normalDamping == 0 &&
                       (!ground || ground->normalDamping == 0);
  if (elastic && b.shape == sp::ShapeKind::Sphere) {
    // Undamped (direct solref, b = 0), stiffness giving superdex's peak penetration, capped by
    // MuJoCo's own integrator-safety bound (timeconst >= 2 dt, i.e. k <= 1/(2 dt)^2).
    const double height = b.position.z() - b.radius;
    const double d = sp::DropPeakPenetration(b, height, g);
    const double k = std::min(2 * g * (height + d) / (d * d), 1.0 / (4 * dt * dt));
    c.solref0 = -k;
    c.solref1 = 0.0;
    std::ostringstream r;
    r << "elastic: superdex peak penetration " << d << " m -> k = " << k << " 1/s^2 (direct, b = 0)";
    c.rule = r.str();
    return c;
  }
  // Critically damped, natural frequency of superdex's contact linearized at rest.
  const double omega = std::sqrt(sp::RestStiffness(b, g) / b.mass);
  c.solref0 = std::max(1.0 / omega, 2 * dt);
  c.solref1 = 1.0;
  std::ostringstream r;
  r << "rest stiffness: omega = " << omega << " rad/s -> timeconst 1/omega = " << 1.0 / omega
    << " s (MuJoCo clamps to >= 2 dt)";
  c.rule = r.str();
  return c;
}

std::string Quat(const Eigen::Quaterniond& q) {
  std::ostringstream o;
  o.precision(17);
  o << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z();
  return o.str();
}

std::string V3(const Eigen::Vector3d& v) {
  std::ostringstream o;
  o.precision(17);
  o << v.x() << ' ' << v.y() << ' ' << v.z();
  return o.str();
}

std::string ModelXml(const sp::PeerScene& s, const sp::PeerOptions& o, const ContactRef& c) {
  int dynamic = 0;
  for (const sp::PeerBody& b : s.bodies) dynamic += b.dynamic;
  // MuJoCo 2.2 preallocates dense njmax x njmax and njmax x nv arrays in one buffer that must
  // stay below 2 GB: 12 njmax² + 24 njmax nv bytes. Three rows per contact (elliptic, condim 3).
  const double nv = 6.0 * dynamic;
  const int njmaxCap = int((-24 * nv + std::sqrt(576 * nv * nv + 48 * 1.8e9)) / 24);
  const int njmax = std::min(3 * (100 + 6 * dynamic), njmaxCap);
  const int ncon = njmax / 3;
  const std::string solver = o.solver.empty() ? "Newton" : o.solver == "cg" ? "CG" : o.solver == "pgs" ? "PGS" : "Newton";
  const double mu = s.PairFriction();
  std::ostringstream x;
  x.precision(17);
  x << "<mujoco model=\"" << s.name << "\">\n"
    << "  <option timestep=\"" << o.dt << "\" gravity=\"" << V3(s.gravity)
    << "\" integrator=\"Euler\" cone=\"elliptic\" solver=\"" << solver << "\" iterations=\""
    << (o.iterations > 0 ? o.iterations : 100) << "\" tolerance=\"1e-8\"/>\n"
    << "  <size nconmax=\"" << ncon << "\" njmax=\"" << njmax << "\"/>\n"
    << "  <default><geom condim=\"3\" friction=\"" << mu << " 0.005 0.0001\" solref=\"" << c.solref0
    << ' ' << c.solref1 << "\" solimp=\"" << kDmin << ' ' << kDmax << " 0.001 0.5 2\"/></default>\n"
    << "  <worldbody>\n";
  for (const sp::PeerBody& b : s.bodies) {
    std::ostringstream geom;
    geom.precision(17);
    if (b.shape == sp::ShapeKind::Plane) {
      const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), b.normal);
      geom << "<geom name=\"" << b.name << "\" type=\"plane\" size=\"0 0 1\" pos=\"" << V3(b.position)
           << "\" quat=\"" << Quat(q) << "\"/>";
    } else {
      geom << "<geom name=\"" << b.name << "\" type=\""
           << (b.shape == sp::ShapeKind::Box ? "box\" size=\"" + V3(b.halfExtents) : "sphere\" size=\"" + std::to_string(b.radius))
           << "\"" << (b.collides ? "" : " contype=\"0\" conaffinity=\"0\"");
      if (b.dynamic) geom << " mass=\"" << b.mass << "\"";
      else geom << " pos=\"" << V3(b.position) << "\" quat=\"" << Quat(b.orientation) << "\"";
      geom << "/>";
    }
    if (!b.dynamic) {
      x << "    " << geom.str() << "\n";
      continue;
    }
    x << "    <body name=\"" << b.name << "\" pos=\"" << V3(b.position) << "\" quat=\""
      << Quat(b.orientation) << "\"><freejoint/>" << geom.str() << "</body>\n";
  }
  x << "  </worldbody>\n</mujoco>\n";
  return x.str();
}

}  // namespace

int main(int argc, char** argv) {
  sp::PeerOptions o;
  sp::PeerScene scene;
  if (!sp::StartRun(argc, argv, &o, &scene)) return 2;
  const double duration = o.duration > 0 ? o.duration : scene.duration;
  const ContactRef ref = MatchContact(scene, o.dt, o.timeconst);
  const std::string xml = ModelXml(scene, o, ref);
  if (!o.model.empty()) std::ofstream(o.model) << xml;

  mjVFS vfs;
  mj_defaultVFS(&vfs);
  mj_makeEmptyFileVFS(&vfs, "scene.xml", int(xml.size()));
  std::copy(xml.begin(), xml.end(), static_cast<char*>(vfs.filedata[0]));
  char err[1000] = "";
  mjModel* m = mj_loadXML("scene.xml", &vfs, err, sizeof(err));
  mj_deleteVFS(&vfs);
  if (!m) {
    std::cerr << "error: MuJoCo: " << err << "\n";
    return 2;
  }
  mjData* d = mj_makeData(m);

  // Initial velocities: free joints take the world linear velocity and the body-frame angular one.
  const int tracked = scene.LastDynamic();
  int body = 0, trackedBody = -1;
  for (int i = 0; i < int(scene.bodies.size()); ++i) {
    const sp::PeerBody& b = scene.bodies[i];
    if (!b.dynamic) continue;
    ++body;  // body 0 is the world
    if (i == tracked) trackedBody = body;
    mjtNum* v = d->qvel + m->jnt_dofadr[m->body_jntadr[body]];
    const Eigen::Vector3d w = b.orientation.conjugate() * b.angularVelocity;
    for (int k = 0; k < 3; ++k) v[k] = b.velocity[k], v[3 + k] = w[k];
  }

  sp::Recorder rec(scene, o, "mujoco");
  auto sample = [&]() {
    sp::TrackSample x;
    x.t = d->time;
    const mjtNum* q = d->qpos + m->jnt_qposadr[m->body_jntadr[trackedBody]];
    const mjtNum* v = d->qvel + m->jnt_dofadr[m->body_jntadr[trackedBody]];
    x.p = Eigen::Vector3d(q[0], q[1], q[2]);
    x.q = Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized();
    x.v = Eigen::Vector3d(v[0], v[1], v[2]);
    x.w = x.q * Eigen::Vector3d(v[3], v[4], v[5]);
    return x;
  };
  if (trackedBody > 0) rec.Add(sample(), 0.0);
  const long steps = std::max(1L, std::lround(duration / o.dt));
  double wall = 0.0;
  bool overflow = false;
  for (long k = 0; k < steps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    mj_step(m, d);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    double pen = 0.0;  // contacts of this step: the state at its start (the previous step's end)
    for (int c = 0; c < d->ncon; ++c) pen = std::max(pen, -d->contact[c].dist);
    overflow |= d->warning[mjWARN_CONTACTFULL].number > 0 || d->warning[mjWARN_CNSTRFULL].number > 0;
    if (trackedBody > 0 && !rec.Add(sample(), pen)) break;
  }
  nlohmann::json settings = {{"solver", m->opt.solver == mjSOL_NEWTON ? "Newton" : m->opt.solver == mjSOL_CG ? "CG" : "PGS"},
                             {"cone", "elliptic"}, {"integrator", "Euler"},
                             {"iterations", m->opt.iterations}, {"tolerance", m->opt.tolerance},
                             {"solref", {ref.solref0, ref.solref1}},
                             {"solimp", {kDmin, kDmax, 0.001, 0.5, 2}},
                             {"friction", scene.PairFriction()}, {"contact_rule", ref.rule},
                             {"buffer_overflow", overflow}, {"mujoco_version", mj_version()}};
  if (overflow) rec.Fail("MuJoCo's preallocated contact/constraint buffer overflowed: contacts were dropped");
  rec.Print(wall, d->time, settings);
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
