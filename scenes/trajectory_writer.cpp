#include "scenes/trajectory_writer.h"

#include <Eigen/Geometry>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/contact/contact_report.h"
#include "core/model/articulated_kind.h"
#include "scenes/version.h"

namespace superdex {
namespace {

using json = nlohmann::json;

json Vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

// v to 7 significant digits (single precision), so that it prints short: the fields added for
// the viewer (shapes' vertices, soft surfaces, contact samples) are bulk data.
double Single(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.7g", v);
  return std::strtod(text, nullptr);
}

void Push(json* flat, const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) flat->push_back(Single(v[k]));
}

json Numbers(const Eigen::VectorXd& v) { return json(std::vector<double>(v.data(), v.data() + v.size())); }

json Quaternion(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q(R);
  return json::array({q.x(), q.y(), q.z(), q.w()});
}

// An articulated actor's frame: its centre of mass and velocity, each link's frame (its origin
// and rotation), the joint coordinates, the joints' velocities (tangent layout) and the drives'
// forces.
json ArticulatedFrameJson(const Scene& scene, ActorHandle h, const ArticulatedKind& kind) {
  const KindState& s = scene.KindStateOf(h);
  json links = json::array();
  const std::vector<RigidPose> poses = kind.LinkPoses(s.x);
  for (const RigidPose& pose : poses)
    links.push_back({{"p", Vec(pose.p)}, {"q", Quaternion(pose.R)}});
  return {{"p", Vec(kind.CenterOfMass(s))},
          {"q", Quaternion(poses[0].R)},
          {"v", Vec(kind.CenterOfMassVelocity(s))},
          {"links", links},
          {"joint_positions", Numbers(kind.JointPositions(s.x))},
          {"joint_velocities", Numbers(kind.JointVelocities(s))},
          {"drive_forces", Numbers(kind.DriveForces(s, scene.Time()))}};
}

json RigidShapeJson(const RigidBodyModel& m) {
  const RigidShape& s = m.shape;
  switch (s.kind) {
    case RigidShapeKind::Sphere: return {{"type", "sphere"}, {"radius", s.radius}};
    case RigidShapeKind::Box: return {{"type", "box"}, {"half_extents", Vec(s.halfExtents)}};
    case RigidShapeKind::Plane: return {{"type", "plane"}, {"normal", Vec(s.planeNormal)}};
    case RigidShapeKind::Mesh:
    case RigidShapeKind::Capsule: break;
  }
  // Vertices in the body frame (origin at the centre of mass): world = p + R v. A capsule as its
  // triangulation.
  const bool capsule = s.kind == RigidShapeKind::Capsule;
  TriangleMesh drawn;
  if (capsule) drawn = MakeCapsuleDrawing(s.radius, s.halfLength);
  const TriangleMesh& mesh = capsule ? drawn : *s.mesh;
  json vertices = json::array(), faces = json::array();
  for (const Eigen::Vector3d& v : mesh.vertices) Push(&vertices, v - m.shapeOffset);
  for (const Eigen::Vector3i& f : mesh.faces)
    for (int k = 0; k < 3; ++k) faces.push_back(f[k]);
  return {{"type", "mesh"}, {"source", capsule ? std::string("capsule") : s.meshSource},
          {"vertices", vertices}, {"faces", faces}};
}

// A drawn surface (ActorKind::SurfaceTriangles) over numNodes nodes: the nodes its faces use (in
// first-use order) and the faces as indices into that list.
json SurfaceJson(const std::vector<Eigen::Vector3i>& triangles, int numNodes,
                 std::vector<int>* nodes) {
  std::vector<int> local(numNodes, -1);
  json faces = json::array();
  for (const Eigen::Vector3i& f : triangles) {
    for (int k = 0; k < 3; ++k) {
      if (local[f[k]] < 0) {
        local[f[k]] = static_cast<int>(nodes->size());
        nodes->push_back(f[k]);
      }
      faces.push_back(local[f[k]]);
    }
  }
  return {{"nodes", *nodes}, {"faces", faces}};
}

// The active contact samples as columns: the actor pair (colliding, collider), positions [m],
// normal tractions [Pa] (> 0 pushing the colliding actor out), forces w_q (t_n + t_f + t_d) on the
// colliding actor with the step's friction and damping [N].
// Then per actor pair, both passes summed (SummarizeContactPairs, full precision): force,
// torque about the origin, centre of pressure, area and max penetration.
json ContactsJson(Scene& scene) {
  json pairs = json::array(), p = json::array(), tn = json::array(), f = json::array();
  const std::vector<ContactSampleRecord> records = scene.ContactSamples();
  for (const ContactSampleRecord& r : records) {
    pairs.push_back(r.colliding);
    pairs.push_back(r.collider);
    Push(&p, r.position);
    tn.push_back(Single(r.traction.dot(r.normal)));
    Push(&f, r.weight * (r.traction + r.friction + r.damping));
  }
  json totals = json::array();
  for (const ContactPairSummary& s : SummarizeContactPairs(records)) {
    json centre = s.centreOfPressure.allFinite() ? Vec(s.centreOfPressure) : json(nullptr);
    totals.push_back({{"a", s.a},
                      {"b", s.b},
                      {"force", Vec(s.force)},
                      {"friction_force", Vec(s.frictionForce)},
                      {"torque", Vec(s.torque)},
                      {"centre_of_pressure", centre},
                      {"area", s.area},
                      {"max_penetration", s.maxPenetration}});
  }
  return {{"count", tn.size()}, {"pairs", pairs}, {"p", p}, {"tn", tn}, {"f", f},
          {"pair_totals", totals}};
}

}  // namespace

TrajectoryWriter::~TrajectoryWriter() {
  if (file_) std::fclose(file_);
}

bool TrajectoryWriter::WriteLine(const std::string& line, Error* error) {
  errno = 0;
  if (std::fputs(line.c_str(), file_) < 0 || std::fputc('\n', file_) == EOF ||
      std::fflush(file_) != 0)
    return Fail(error, "output.path: writing \"" + path_ + "\" failed: " +
                           (errno ? std::strerror(errno) : "write error"));
  return true;
}

bool TrajectoryWriter::Close(Error* error) {
  if (!file_) return true;
  errno = 0;
  const int status = std::fclose(file_);
  file_ = nullptr;
  if (status != 0)
    return Fail(error, "output.path: closing \"" + path_ + "\" failed: " +
                           (errno ? std::strerror(errno) : "write error"));
  return true;
}

std::string TrajectoryWriter::Header(const Scene& scene, const std::vector<std::string>& names,
                                    double dt, const TrajectoryOptions& options) {
  options_ = options;
  surfaceNodes_.assign(scene.NumActors(), {});
  json h;
  h["format"] = "superdex-trajectory/1";
  h["superdex_version"] = kVersion;
  h["dt"] = dt;
  h["integrator"] = ToString(scene.Settings().integrator);
  h["gravity"] = Vec(scene.Settings().gravity);
  h["contacts"] = options.contacts;
  json actors = json::array();
  for (int i = 0; i < scene.NumActors(); ++i) {
    if (scene.IsSoft({i})) {
      const SoftBodyModel& m = scene.SoftModel({i});
      actors.push_back({{"name", names[i]}, {"type", "soft"}, {"dynamic", true}, {"mass", m.mass},
                        {"nodes", m.NumNodes()}, {"tets", m.rest.NumTets()},
                        {"surface", SurfaceJson(m.faces, m.NumNodes(), &surfaceNodes_[i])}});
      continue;
    }
    const ActorKind& kind = scene.Kind({i});
    if (const auto* body = dynamic_cast<const NodeBodyKind*>(&kind);
        body && kind.SurfaceTriangles()) {  // a shell: its triangles
      actors.push_back({{"name", names[i]}, {"type", kind.KindName()}, {"dynamic", true},
                        {"mass", body->TotalMass()}, {"nodes", body->NumNodes()},
                        {"surface", SurfaceJson(*kind.SurfaceTriangles(), body->NumNodes(),
                                                &surfaceNodes_[i])}});
      continue;
    }
    if (!scene.BodyModel({i}) && !dynamic_cast<const ArticulatedKind*>(&kind)) {
      // A kind the writer cannot draw: a marker at its centre of mass.
      actors.push_back({{"name", names[i]}, {"type", kind.KindName()}, {"dynamic", true}});
      continue;
    }
    if (const auto* art = dynamic_cast<const ArticulatedKind*>(&scene.Kind({i}))) {
      json links = json::array();
      double mass = 0.0;
      for (int l = 0; l < art->NumLinks(); ++l) {
        links.push_back({{"name", art->LinkName(l)},
                         {"joint", ToString(art->Tree().Joint(l).type)},
                         {"mass", art->LinkMass(l)}});
        mass += art->LinkMass(l);
      }
      actors.push_back({{"name", names[i]}, {"type", "articulated"}, {"dynamic", true},
                        {"mass", mass}, {"links", links}});
      continue;
    }
    const RigidBodyModel& m = *scene.BodyModel({i});
    const bool attached = scene.IsAttached({i});
    json a = {{"name", names[i]}, {"type", "rigid"}, {"dynamic", attached || m.dynamic},
              {"mass", attached ? 0.0 : m.mass}, {"shape", RigidShapeJson(m)}};
    if (m.kinematic) a["kinematic"] = true;
    if (attached) a["attached_to"] = names[scene.Parent({i}).index];  // a link's shape
    actors.push_back(std::move(a));
  }
  h["actors"] = actors;
  return h.dump();
}

bool TrajectoryWriter::Open(const std::string& path, const Scene& scene,
                            const std::vector<std::string>& names, double dt, Error* error,
                            const TrajectoryOptions& options) {
  std::error_code ec;
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
  path_ = path;
  errno = 0;
  file_ = std::fopen(path.c_str(), "w");
  if (!file_)
    return Fail(error, "output.path: cannot write \"" + path + "\": " +
                           (errno ? std::strerror(errno) : "open failed"));
  return WriteLine(Header(scene, names, dt, options), error);
}

bool TrajectoryWriter::Reopen(const std::string& path, long long bytes, const Scene& scene,
                              const std::vector<std::string>& names, double dt, Error* error,
                              const TrajectoryOptions& options) {
  const std::string header = Header(scene, names, dt, options);
  path_ = path;
  std::string first;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in || !std::getline(in, first))
      return Fail(error, "output.path: cannot resume \"" + path + "\": it cannot be read");
  }
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || static_cast<long long>(size) < bytes)
    return Fail(error, "output.path: cannot resume \"" + path + "\": it holds " +
                           std::to_string(ec ? 0 : size) + " bytes, the checkpoint needs " +
                           std::to_string(bytes));
  if (first != header)
    return Fail(error, "output.path: cannot resume \"" + path +
                           "\": its header is not this run's (another scene or options)");
  std::filesystem::resize_file(path, static_cast<std::uintmax_t>(bytes), ec);
  errno = 0;
  file_ = ec ? nullptr : std::fopen(path.c_str(), "a");
  if (!file_)
    return Fail(error, "output.path: cannot resume \"" + path + "\": " +
                           (ec ? ec.message() : errno ? std::strerror(errno) : "open failed"));
  return true;
}

long long TrajectoryWriter::Bytes() const {
  return file_ ? static_cast<long long>(std::ftell(file_)) : 0;
}

bool TrajectoryWriter::WriteFrame(Scene& scene, long long step, const StepReport* report,
                                  Error* error) {
  json f;
  f["t"] = scene.Time();
  f["step"] = step;
  json actors = json::array();
  for (int i = 0; i < scene.NumActors(); ++i) {
    if (!surfaceNodes_[i].empty()) {  // centre of mass, its velocity and the surface's nodes
      json surface = json::array();
      const Eigen::VectorXd& x = scene.KindStateOf({i}).x;
      for (int a : surfaceNodes_[i]) Push(&surface, x.segment<3>(3 * a));
      actors.push_back({{"p", Vec(scene.CenterOfMass({i}))},
                        {"v", Vec(scene.CenterOfMassVelocity({i}))},
                        {"surface", surface}});
      continue;
    }
    if (const auto* art = dynamic_cast<const ArticulatedKind*>(&scene.Kind({i}))) {
      actors.push_back(ArticulatedFrameJson(scene, {i}, *art));
      continue;
    }
    if (!scene.BodyModel({i})) {  // a marker
      actors.push_back({{"p", Vec(scene.CenterOfMass({i}))},
                        {"v", Vec(scene.CenterOfMassVelocity({i}))}});
      continue;
    }
    const RigidBodyState s = scene.BodyState({i});
    const Eigen::Quaterniond q(s.R);
    actors.push_back({{"p", Vec(s.p)},
                      {"q", json::array({q.x(), q.y(), q.z(), q.w()})},
                      {"v", Vec(s.v)},
                      {"w", Vec(s.AngularVelocity())}});
  }
  f["actors"] = actors;
  const EnergyReport e = scene.Energies();
  f["energy"] = {{"kinetic", e.kinetic}, {"gravity", e.gravity}, {"contact", e.contact},
                 {"elastic", e.elastic}, {"total", e.Total()}};
  if (options_.contacts) f["contacts"] = ContactsJson(scene);
  if (report) {
    f["stats"] = {{"newton_iterations", report->newtonIterations},
                  {"line_search_steps", report->lineSearchSteps},
                  {"status", ToString(report->status)},
                  {"active_samples", report->contact.activeSamples},
                  {"min_signed_distance",
                   std::isfinite(report->contact.minSignedDistance)
                       ? json(report->contact.minSignedDistance)
                       : json(nullptr)},
                  {"wall_seconds", report->wallSeconds}};
    if (std::isfinite(report->minDetF)) f["stats"]["min_det_f"] = report->minDetF;
  }
  return WriteLine(f.dump(), error);
}

}  // namespace superdex
