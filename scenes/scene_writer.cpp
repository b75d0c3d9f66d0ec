#include "scenes/scene_writer.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/model/rigid_math.h"
#include "scenes/version.h"

namespace superdex {
namespace {

using json = nlohmann::json;

json Vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

json Keyframes(const VectorKeyframes& keys) {
  json out = json::array();
  for (const auto& [t, v] : keys) out.push_back({t, v.x(), v.y(), v.z()});
  return out;
}

json Quaternion(const Eigen::Quaterniond& q) { return json::array({q.x(), q.y(), q.z(), q.w()}); }

// The rows of `table` whose value in c differs from the struct's default initializer's, as a
// JSON object (a nested table as an object of its own, left out when nothing in it differs): what
// ReadFields reads back to c.
template <typename Table, typename Class>
json ChangedFields(const Table& table, const Class& c) {
  json out = json::object();
  const Class defaults{};
  ForEachField(table, [&](const auto& f) {
    using T = typename std::decay_t<decltype(f)>::ValueType;
    const T& v = f.Of(c);
    const T& d = f.Of(defaults);
    if constexpr (kIsNested<decltype(f)>) {
      json inner = ChangedFields(*f.table, v);
      if (!inner.empty()) out[f.name] = std::move(inner);
    } else if constexpr (std::is_enum_v<T>) {
      if (v != d) out[f.name] = ToString(v);
    } else if constexpr (kIsFixedVector<T>) {
      if (v != d) {
        json a = json::array();
        for (int i = 0; i < v.size(); ++i) a.push_back(v[i]);
        out[f.name] = std::move(a);
      }
    } else {
      if (!(v == d)) out[f.name] = v;
    }
  });
  return out;
}

// Writes what goes beside the scene file: `<stem>.<actor>.<ext>`; returns its file name.
struct Beside {
  std::filesystem::path dir;
  std::string stem;
  std::string Name(const std::string& actor, const char* ext) const {
    return stem + "." + actor + "." + ext;
  }
};

bool RigidShapeJson(const RigidActorDesc& d, const Beside& beside, json* out, Error* error) {
  const RigidShape& s = d.shape;
  switch (s.kind) {
    case RigidShapeKind::Sphere:
      *out = {{"type", "sphere"}, {"radius", s.radius}, {"surface_resolution", s.surfaceResolution}};
      return true;
    case RigidShapeKind::Box:
      *out = {{"type", "box"}, {"half_extents", Vec(s.halfExtents)},
              {"surface_resolution", s.surfaceResolution}};
      return true;
    case RigidShapeKind::Plane:
      *out = {{"type", "plane"}, {"normal", Vec(s.planeNormal)}};
      return true;
    case RigidShapeKind::Capsule:
      *out = {{"type", "capsule"}, {"radius", s.radius}, {"half_length", s.halfLength},
              {"surface_resolution", s.surfaceResolution}};
      return true;
    case RigidShapeKind::Mesh: {
      const std::string file = beside.Name(d.name, "obj");
      std::string message;
      if (!s.mesh || !WriteObj(*s.mesh, (beside.dir / file).string(), &message))
        return Fail(error, d.name + ".shape: " + (s.mesh ? message : "no mesh"));
      *out = {{"type", "mesh"}, {"file", file}};
      return true;
    }
  }
  return Fail(error, d.name + ".shape: unknown kind");
}

// The fields rigid and soft descriptions share: placement, initial velocity, contact
// parameters, collider and quadrature types, layer and grid SDF (JSON objects keep their keys
// sorted, so the order of insertion does not show in the file).
template <typename Desc>
void PlacementAndContact(const Desc& d, json* out) {
  json& j = *out;
  j["position"] = Vec(d.position);
  j["orientation"] = Quaternion(d.orientation);
  j["velocity"] = Vec(d.linearVelocity);
  if (json c = ChangedFields(kContactParamsFields, d.contact); !c.empty()) j["contact"] = c;
  j["collider_type"] = ToString(d.colliderType);
  j["boundary_element_type"] = ToString(d.boundaryElementType);
  if (d.contactLayer != "default") j["contact_layer"] = d.contactLayer;
  if (json g = ChangedFields(kGridSdfFields, d.gridSdf); !g.empty()) j["grid_sdf"] = g;
}

bool SameState(const RigidBodyState& a, const RigidBodyState& b) {
  return a.p == b.p && a.R == b.R && a.v == b.v && a.Rdot == b.Rdot;
}

bool RigidActorJson(const Scene& scene, ActorHandle a, const Beside& beside, json* out,
                    Error* error) {
  RigidActorDesc d = scene.RigidDesc(a);
  const RigidBodyModel& m = scene.Model(a);
  const RigidBodyState& s = scene.State(a);
  // The current state where the description no longer gives it (a dynamic actor's set state).
  if (m.dynamic && !SameState(s, InitialRigidState(d, m))) {
    d.orientation = Eigen::Quaterniond(s.R);
    d.position = s.p - s.R * m.shapeOffset;
    d.linearVelocity = s.v;
    d.angularVelocity = s.AngularVelocity();
  }
  json j = {{"name", d.name}};
  if (d.kinematic) j["kinematic"] = true;
  else if (!d.dynamic) j["dynamic"] = false;
  json shape;
  if (!RigidShapeJson(d, beside, &shape, error)) return false;
  j["shape"] = std::move(shape);
  if (d.dynamic) {
    if (d.mass) j["mass"] = *d.mass;
    else j["density"] = d.density;
    if (d.inertia) {
      const Eigen::Matrix3d& I = *d.inertia;
      if (!I.isDiagonal(0.0))
        return Fail(error, d.name + ".inertia: a full inertia tensor has no scene-file form "
                                    "(principal moments in the shape frame only)");
      j["inertia"] = Vec(I.diagonal());
    }
  }
  PlacementAndContact(d, &j);
  if (d.surfaceIntegral != SurfaceIntegral::Quadrature)
    j["surface_integral"] = ToString(d.surfaceIntegral);
  j["angular_velocity"] = Vec(d.angularVelocity);
  if (!d.path.empty()) {
    json path = json::array();
    for (const PoseKeyframe& k : d.path)
      path.push_back({{"t", k.t}, {"position", Vec(k.position)},
                      {"orientation", Quaternion(k.orientation)}});
    j["path"] = std::move(path);
  }
  if (!d.appliedForce.empty()) j["applied_force"] = Keyframes(d.appliedForce);
  if (!d.appliedTorque.empty()) j["applied_torque"] = Keyframes(d.appliedTorque);
  *out = std::move(j);
  return true;
}

// Whether every node's 3-vector of `delta` is the same (to round-off in `value`'s magnitude);
// that vector in *shift.
bool UniformShift(const Eigen::VectorXd& delta, const Eigen::VectorXd& value,
                  Eigen::Vector3d* shift) {
  *shift = delta.head<3>();
  const double tolerance = 1e-12 * (value.lpNorm<Eigen::Infinity>() + 1.0);
  for (Eigen::Index i = 0; i < delta.size(); i += 3)
    if ((delta.segment<3>(i) - *shift).lpNorm<Eigen::Infinity>() > tolerance) return false;
  return true;
}

bool SoftActorJson(const Scene& scene, ActorHandle a, const Beside& beside, json* out,
                   Error* error) {
  SoftActorDesc d = scene.SoftDesc(a);
  SoftBodyModel built;
  SoftBodyState initial;
  if (!BuildSoftBody(d, d.name + ".", &built, &initial, error)) return false;
  const SoftBodyState& s = scene.SoftState(a);
  // A state moved as a whole (every node by the same displacement and velocity change: the
  // fitting's position and velocity parameters) is the description's, moved; any other has no
  // scene-file form.
  Eigen::Vector3d dx, dv;
  if (!(s.x == initial.x && s.v == initial.v)) {
    if (!UniformShift(s.x - initial.x, s.x, &dx) || !UniformShift(s.v - initial.v, s.v, &dv))
      return Fail(error, d.name + ": a soft actor's state set after its creation, other than a "
                                  "uniform shift, has no scene-file form (save it with get_state "
                                  "or a checkpoint)");
    d.position += dx;
    d.linearVelocity += dv;
  }
  const std::string file = beside.Name(d.name, "msh");
  std::string message;
  if (!d.mesh || !WriteGmsh22(*d.mesh, (beside.dir / file).string(), &message))
    return Fail(error, d.name + ".mesh: " + (d.mesh ? message : "no mesh"));
  json j = {{"name", d.name}, {"type", "soft"}, {"mesh", {{"type", "file"}, {"file", file}}}};
  PlacementAndContact(d, &j);
  if (json mat = ChangedFields(kSoftMaterialFields, d.material); !mat.empty()) j["material"] = mat;
  if (!d.constraints.empty()) {
    json list = json::array();
    for (const NodeConstraint& k : d.constraints) {
      json c = {{"nodes", k.nodes}};
      if (!k.path.empty()) c["path"] = Keyframes(k.path);
      list.push_back(std::move(c));
    }
    j["constraints"] = std::move(list);
  }
  *out = std::move(j);
  return true;
}

// The contact filter's settings in force, each as one asymmetric setting.
json ContactFilterJson(const Scene& scene) {
  json list = json::array();
  const ContactFilter& f = scene.Filter();
  for (const auto& [pair, enable] : f.LayerSettings())
    list.push_back({{"layers", {pair.first, pair.second}}, {"enable", enable}, {"symmetric", false}});
  for (const auto& [pair, enable] : f.ActorSettings())
    list.push_back({{"actors", {scene.ActorName({pair.first}), scene.ActorName({pair.second})}},
                    {"enable", enable},
                    {"symmetric", false}});
  return list;
}

bool SceneJson(const Scene& scene, const SceneWriteOptions& options, const Beside& beside,
               json* out, Error* error) {
  if (scene.Time() > 0.0)
    return Fail(error, "scene: it has stepped to t = " + std::to_string(scene.Time()) +
                           " s; write it before stepping (save a state with get_state or a "
                           "checkpoint)");
  json j = {{"format", "superdex-scene/1"}, {"superdex_version", kVersion}};
  if (!options.description.empty()) j["description"] = options.description;
  json settings = ChangedFields(kSceneSettingsFields, scene.Settings());
  settings["dt"] = options.dt;
  settings["duration"] = options.duration;
  if (options.penetrationBound) settings["penetration_bound"] = *options.penetrationBound;
  j["settings"] = std::move(settings);
  json actors = json::array();
  for (int i = 0; i < scene.NumActors(); ++i) {
    const ActorHandle a{i};
    if (scene.IsKind(a))
      return Fail(error, scene.ActorName(a) + ": an actor of the generic layer (" +
                             scene.Kind(a).KindName() + ") has no scene-file form");
    json actor;
    if (!(scene.IsSoft(a) ? SoftActorJson(scene, a, beside, &actor, error)
                          : RigidActorJson(scene, a, beside, &actor, error)))
      return false;
    if (const ActorHandle p = scene.Parent(a); p.IsValid()) actor["parent"] = scene.ActorName(p);
    actors.push_back(std::move(actor));
  }
  j["actors"] = std::move(actors);
  if (json filter = ContactFilterJson(scene); !filter.empty()) j["contact_filter"] = filter;
  if (json output = ChangedFields(kOutputSpecFields, options.output); !output.empty())
    j["output"] = output;
  *out = std::move(j);
  return true;
}

}  // namespace

bool WriteSceneFile(const Scene& scene, const std::string& path, const SceneWriteOptions& options,
                    Error* error) {
  const std::filesystem::path p(path);
  Beside beside{p.has_parent_path() ? p.parent_path() : std::filesystem::path("."),
                p.stem().string()};
  std::error_code ec;
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
  json j;
  Error local;
  if (!SceneJson(scene, options, beside, &j, &local)) return Fail(error, path + ": " + local.message);
  std::ofstream out(path);
  out << j.dump(1) << '\n';
  out.flush();
  if (!out) return Fail(error, path + ": cannot write file");
  return true;
}

SceneFile SceneFileOf(const Scene& scene, const SceneWriteOptions& options) {
  SceneFile f;
  f.description = options.description;
  f.scene = std::make_unique<Scene>(scene);
  f.dt = options.dt;
  f.duration = options.duration;
  f.penetrationBound = options.penetrationBound;
  f.output = options.output;
  for (int i = 0; i < scene.NumActors(); ++i) f.actorNames.push_back(scene.ActorName({i}));
  return f;
}

}  // namespace superdex
