// Reads superdex scene files (format superdex-scene/1) into PeerScene; unknown fields that the
// peers cannot reproduce (soft actors, meshes) are refused with a message.
#include "peer_scene.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "scenes/grid_copies.h"

namespace superdex::peers {
namespace {

using json = nlohmann::json;

Eigen::Vector3d Vec(const json& j, const char* key, const Eigen::Vector3d& def) {
  if (!j.contains(key)) return def;
  const json& v = j.at(key);
  return Eigen::Vector3d(v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>());
}

Eigen::Quaterniond Orientation(const json& a) {
  if (a.contains("euler_deg")) {
    const Eigen::Vector3d e = Vec(a, "euler_deg", Eigen::Vector3d::Zero()) * M_PI / 180.0;
    return Eigen::Quaterniond(Eigen::AngleAxisd(e.z(), Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(e.y(), Eigen::Vector3d::UnitY()) *
                              Eigen::AngleAxisd(e.x(), Eigen::Vector3d::UnitX()));
  }
  if (a.contains("orientation")) {
    const json& q = a.at("orientation");
    return Eigen::Quaterniond(q.at(3).get<double>(), q.at(0).get<double>(), q.at(1).get<double>(),
                              q.at(2).get<double>())
        .normalized();
  }
  return Eigen::Quaterniond::Identity();
}

PeerBody ReadBody(const json& a) {
  PeerBody b;
  b.name = a.at("name").get<std::string>();
  if (a.value("type", std::string("rigid")) != "rigid")
    throw std::runtime_error(b.name + ": only rigid actors are supported by the peers");
  b.dynamic = a.value("dynamic", true);
  b.collides = a.value("collider_type", std::string("Auto")) != "None";
  b.orientation = Orientation(a);
  b.position = Vec(a, "position", Eigen::Vector3d::Zero());
  b.velocity = Vec(a, "velocity", Eigen::Vector3d::Zero());
  b.angularVelocity = Vec(a, "angular_velocity", Eigen::Vector3d::Zero());
  const json& s = a.at("shape");
  const std::string type = s.at("type").get<std::string>();
  double volume = 0.0;
  if (type == "plane") {
    b.shape = ShapeKind::Plane;
    b.normal = (b.orientation * Vec(s, "normal", Eigen::Vector3d::UnitZ())).normalized();
  } else if (type == "box") {
    b.shape = ShapeKind::Box;
    // The scene file gives exactly one of the two (superdex's reader enforces it).
    if (s.contains("size") == s.contains("half_extents"))
      throw std::runtime_error(b.name + ": a box needs exactly one of \"size\" and \"half_extents\"");
    b.halfExtents = s.contains("size") ? Eigen::Vector3d(0.5 * Vec(s, "size", Eigen::Vector3d::Zero()))
                                       : Vec(s, "half_extents", Eigen::Vector3d::Zero());
    volume = 8.0 * b.halfExtents.prod();
  } else if (type == "sphere") {
    b.shape = ShapeKind::Sphere;
    b.radius = s.at("radius").get<double>();
    volume = 4.0 / 3.0 * M_PI * std::pow(b.radius, 3);
  } else {
    throw std::runtime_error(b.name + ": shape \"" + type + "\" is not supported by the peers");
  }
  if (b.dynamic) {
    b.mass = a.contains("mass") ? a.at("mass").get<double>() : a.value("density", 1000.0) * volume;
    if (b.shape == ShapeKind::Box) {
      const Eigen::Vector3d l2 = (2.0 * b.halfExtents).cwiseAbs2();
      b.inertia = b.mass / 12.0 * Eigen::Vector3d(l2.y() + l2.z(), l2.x() + l2.z(), l2.x() + l2.y());
    } else {
      b.inertia.setConstant(0.4 * b.mass * b.radius * b.radius);
    }
    if (a.contains("inertia")) b.inertia = Vec(a, "inertia", b.inertia);
  }
  if (a.contains("contact")) {
    const json& c = a.at("contact");
    b.mu = c.value("coulomb_friction_coefficient", b.mu);
    b.normalDamping = c.value("normal_viscous_damping_coefficient", b.normalDamping);
    b.k = c.value("penalty_coefficient", b.k);
    b.eps = c.value("penalty_smoothing_half_distance", b.eps);
    b.delta = c.value("penalty_threshold_default", b.delta);
  }
  return b;
}

// Grid replication as scenes/scene_file.cpp does it (scenes/grid_copies.h).
void Replicate(const json& a, const PeerBody& proto, std::vector<PeerBody>* out) {
  if (!a.contains("grid")) {
    out->push_back(proto);
    return;
  }
  const json& g = a.at("grid");
  const std::vector<Eigen::Vector3d> offsets =
      GridCopyOffsets(Vec(g, "count", Eigen::Vector3d::Ones()),
                      Vec(g, "spacing", Eigen::Vector3d::Zero()), g.value("jitter", 0.0),
                      g.value("seed", 1));
  for (size_t k = 0; k < offsets.size(); ++k) {
    PeerBody b = proto;
    b.name = proto.name + "_" + std::to_string(k);
    b.position += offsets[k];
    out->push_back(b);
  }
}

}  // namespace

int PeerScene::LastDynamic() const {
  for (int i = int(bodies.size()) - 1; i >= 0; --i)
    if (bodies[i].dynamic) return i;
  return -1;
}

double PeerScene::PairFriction() const {
  const PeerBody* d = nullptr;
  const PeerBody* s = nullptr;
  for (const PeerBody& b : bodies) {
    if (b.dynamic && !d) d = &b;
    if (!b.dynamic && !s) s = &b;
  }
  if (!d) return 0.0;
  return s ? std::sqrt(d->mu * s->mu) : d->mu;
}

bool LoadPeerScene(const std::string& scene, PeerScene* out, std::string* error) {
  std::string path = scene;
  if (path.size() < 5 || path.substr(path.size() - 5) != ".json")
    path = std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/" + scene + ".json";
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open";
    return false;
  }
  try {
    const json j = json::parse(in);
    PeerScene s;
    const size_t slash = path.find_last_of('/');
    s.name = path.substr(slash == std::string::npos ? 0 : slash + 1);
    s.name = s.name.substr(0, s.name.size() - 5);
    if (j.contains("settings")) {
      const json& st = j.at("settings");
      s.gravity = Vec(st, "gravity", s.gravity);
      s.duration = st.value("duration", s.duration);
    }
    for (const json& a : j.at("actors")) Replicate(a, ReadBody(a), &s.bodies);
    *out = std::move(s);
  } catch (const std::exception& e) {
    *error = path + ": " + e.what();
    return false;
  }
  return true;
}

}  // namespace superdex::peers
