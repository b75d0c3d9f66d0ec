#include "scenes/trajectory_writer.h"

#include <Eigen/Geometry>
#include <filesystem>
#include <nlohmann/json.hpp>

namespace superdex {
namespace {

using json = nlohmann::json;

json Vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

}  // namespace

bool TrajectoryWriter::Open(const std::string& path, const Scene& scene,
                            const std::vector<std::string>& names, double dt, Error* error) {
  std::error_code ec;
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
  out_.open(path);
  if (!out_) return Fail(error, "output.path: cannot write \"" + path + "\"");
  json h;
  h["format"] = "superdex-trajectory/1";
  h["dt"] = dt;
  h["integrator"] = ToString(scene.Settings().integrator);
  h["gravity"] = Vec(scene.Settings().gravity);
  json actors = json::array();
  for (int i = 0; i < scene.NumActors(); ++i) {
    if (scene.IsSoft({i})) {
      const SoftBodyModel& m = scene.SoftModel({i});
      actors.push_back({{"name", names[i]}, {"type", "soft"}, {"dynamic", true}, {"mass", m.mass},
                        {"nodes", m.NumNodes()}, {"tets", m.rest.NumTets()}});
      continue;
    }
    const RigidBodyModel& m = scene.Model({i});
    actors.push_back({{"name", names[i]}, {"type", "rigid"}, {"dynamic", m.dynamic}, {"mass", m.mass}});
  }
  h["actors"] = actors;
  out_ << h.dump() << '\n';
  return true;
}

void TrajectoryWriter::WriteFrame(Scene& scene, int step, const StepReport* report) {
  json f;
  f["t"] = scene.Time();
  f["step"] = step;
  json actors = json::array();
  for (int i = 0; i < scene.NumActors(); ++i) {
    if (scene.IsSoft({i})) {  // centre of mass and its velocity; the nodes go to VTK frames
      actors.push_back({{"p", Vec(scene.CenterOfMass({i}))}, {"v", Vec(scene.CenterOfMassVelocity({i}))}});
      continue;
    }
    const RigidBodyState& s = scene.State({i});
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
  out_ << f.dump() << '\n';
}

}  // namespace superdex
