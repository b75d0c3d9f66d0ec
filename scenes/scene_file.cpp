#include "scenes/scene_file.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/model/shell_kind.h"
#include "geometry/mesh_io.h"
#include "geometry/tet_mesh.h"
#include "scenes/checkpoint.h"
#include "scenes/grid_copies.h"
#include "scenes/json_fields.h"
#include "scenes/json_text.h"
#include "scenes/articulated_spec.h"
#include "scenes/shape_spec.h"
#include "scenes/shell_spec.h"
#include "scenes/soft_mesh_spec.h"

namespace superdex {
namespace {

using namespace scene_json;

void ReadSoftActor(const json& a, const std::string& path, const std::string& baseDir,
                   ActorHandle parent, SceneFile* out) {
  CheckObject(a, path,
              {"name", "type", "mesh", "material", "position", "orientation", "euler_deg",
               "velocity", "contact", "collider_type", "boundary_element_type", "contact_layer",
               "parent", "constraints", "grid_sdf", "skin"});
  SoftActorDesc d;
  d.name = String(a, path, "name");
  if (!a.contains("mesh")) Throw(Join(path, "mesh"), "missing required field");
  double softTets = 0;
  for (const ActorHandle h : out->scene->SoftActors())
    softTets += out->scene->SoftModel(h).rest.NumTets();
  d.mesh = ReadTetMeshSpec(a.at("mesh"), Join(path, "mesh"), baseDir,
                           limits::kMaxSoftTets - softTets, &d.meshSource);
  if (a.contains("material"))
    ReadFields(a.at("material"), Join(path, "material"), kSoftMaterialFields, &d.material);
  d.position = Point(a, path, "position", Eigen::Vector3d::Zero());
  d.orientation = ReadOrientation(a, path);
  d.linearVelocity = Vector<3>(a, path, "velocity", Eigen::Vector3d::Zero());
  if (a.contains("contact")) d.contact = ReadContact(a.at("contact"), Join(path, "contact"));
  d.colliderType = Enum(a, path, "collider_type", ColliderType::None);
  if (a.contains("grid_sdf")) d.gridSdf = ReadGridSdf(a.at("grid_sdf"), Join(path, "grid_sdf"));
  d.boundaryElementType = Enum(a, path, "boundary_element_type", ActorBoundaryElementType::P1Q3);
  d.contactLayer = String(a, path, "contact_layer", std::string("default"));
  if (a.contains("constraints"))
    d.constraints = ReadConstraints(a.at("constraints"), Join(path, "constraints"), *d.mesh,
                                    d.position, d.orientation);
  if (a.contains("skin")) d.skin = ReadSkin(a.at("skin"), Join(path, "skin"), *d.mesh);
  Error err;
  if (!out->scene->AddSoftActor(d, &err, parent).IsValid()) throw LoadError{path + "." + err.message};
  out->actorNames.push_back(d.name);
}

// "path": [{"t": t, "position": [x, y, z], "orientation": [x, y, z, w] | "euler_deg": [..]}, ...]
// (a keyframe without an orientation keeps the actor's).
std::vector<PoseKeyframe> ReadPosePath(const json& a, const std::string& path) {
  std::vector<PoseKeyframe> out;
  const Eigen::Quaterniond held = ReadOrientation(a, path);
  ForEachItem(a, path, "path", "must be an array of keyframes {\"t\", \"position\", \"orientation\"}",
              [&](const json& k, const std::string& kp) {
                if (!k.is_object()) Throw(kp, "must be an object {\"t\", \"position\", \"orientation\"}");
                CheckObject(k, kp, {"t", "position", "orientation", "euler_deg"});
                if (!k.contains("t")) Throw(Join(kp, "t"), "missing required field");
                if (!k.contains("position")) Throw(Join(kp, "position"), "missing required field");
                PoseKeyframe f;
                f.t = Number(k, kp, "t");
                f.position = Point(k, kp, "position", Eigen::Vector3d::Zero());
                f.orientation = k.contains("orientation") || k.contains("euler_deg")
                                    ? ReadOrientation(k, kp)
                                    : held;
                out.push_back(f);
              });
  return out;
}

// obj[key] as a constant vector [x, y, z] or keyframes [[t, x, y, z], ...] (absent: none).
VectorKeyframes ReadVectorKeyframes(const json& obj, const std::string& path, const char* key,
                                    const char* unitsForm) {
  VectorKeyframes out;
  if (!obj.contains(key)) return out;
  const json& v = obj.at(key);
  const std::string rule = std::string("must be ") + unitsForm + " or keyframes [[t, x, y, z], ...]";
  if (v.is_array() && !v.empty() && v[0].is_number()) {  // the constant form
    if (v.size() != 3) Throw(Join(path, key), rule);
    out.push_back({0.0, Vector<3>(obj, path, key, Eigen::Vector3d::Zero())});
    return out;
  }
  ForEachItem(obj, path, key, rule.c_str(), [&](const json& f, const std::string& fp) {
    if (!f.is_array() || f.size() != 4) Throw(fp, rule);
    for (const json& x : f)
      if (!x.is_number()) Throw(fp, "must be [t, x, y, z] (numbers)");
    out.push_back({f[0].get<double>(),
                   Eigen::Vector3d(f[1].get<double>(), f[2].get<double>(), f[3].get<double>())});
  });
  return out;
}

// The actor named by the field "parent" (none without it); it must come earlier.
ActorHandle ReadParent(const json& a, const std::string& path, const SceneFile& out) {
  ActorHandle parent;
  if (!a.contains("parent")) return parent;
  const std::string p = String(a, path, "parent");
  for (size_t k = 0; k < out.actorNames.size(); ++k)
    if (out.actorNames[k] == p) parent.index = static_cast<int>(k);
  if (!parent.IsValid()) Throw(Join(path, "parent"), "no earlier actor named \"" + p + "\"");
  return parent;
}

RigidActorDesc ReadRigidDesc(const json& a, const std::string& path, const std::string& baseDir) {
  CheckObject(a, path,
              {"name", "type", "dynamic", "shape", "density", "mass", "inertia", "position",
               "orientation", "euler_deg", "velocity", "angular_velocity", "contact",
               "collider_type", "boundary_element_type", "surface_integral", "contact_layer",
               "parent", "grid", "grid_sdf", "kinematic", "path", "applied_force",
               "applied_torque"});
  const std::string type = String(a, path, "type", std::string("rigid"));
  if (type != "rigid")
    Throw(Join(path, "type"), "unknown value \"" + type + "\" (supported: rigid, soft, shell, articulated)");
  RigidActorDesc d;
  d.name = String(a, path, "name");
  d.kinematic = Bool(a, path, "kinematic", false);
  d.dynamic = Bool(a, path, "dynamic", !d.kinematic);
  if (!a.contains("shape")) Throw(Join(path, "shape"), "missing required field");
  d.shape = ReadShape(a.at("shape"), Join(path, "shape"), baseDir);
  if (a.contains("density")) d.density = Positive(a, path, "density");
  if (a.contains("mass")) d.mass = Positive(a, path, "mass");
  if (a.contains("inertia")) {
    const Eigen::Vector3d I = Vector<3>(a, path, "inertia", Eigen::Vector3d::Zero());
    d.inertia = Eigen::Matrix3d(I.asDiagonal());
  }
  d.position = Point(a, path, "position", Eigen::Vector3d::Zero());
  d.orientation = ReadOrientation(a, path);
  d.linearVelocity = Vector<3>(a, path, "velocity", Eigen::Vector3d::Zero());
  d.angularVelocity = Vector<3>(a, path, "angular_velocity", Eigen::Vector3d::Zero());
  if (a.contains("contact")) d.contact = ReadContact(a.at("contact"), Join(path, "contact"));
  d.colliderType = Enum(a, path, "collider_type", ColliderType::Auto);
  d.boundaryElementType = Enum(a, path, "boundary_element_type", ActorBoundaryElementType::P1Q3);
  d.surfaceIntegral = Enum(a, path, "surface_integral", SurfaceIntegral::Quadrature);
  d.contactLayer = String(a, path, "contact_layer", std::string("default"));
  if (a.contains("grid_sdf")) d.gridSdf = ReadGridSdf(a.at("grid_sdf"), Join(path, "grid_sdf"));
  if (a.contains("path")) {
    if (a.contains("grid")) Throw(Join(path, "grid"), "an actor with a path cannot be replicated");
    d.path = ReadPosePath(a, path);
  }
  d.appliedForce = ReadVectorKeyframes(a, path, "applied_force", "[fx, fy, fz]");
  d.appliedTorque = ReadVectorKeyframes(a, path, "applied_torque", "[tx, ty, tz]");
  return d;
}

// Replication on a grid: count [nx, ny, nz], spacing [m], jitter [m] (uniform in
// [−jitter, jitter] per axis, fixed seed), names "<name>_<k>". Without "grid": d itself.
std::vector<RigidActorDesc> PlaceOnGrid(const json& a, const std::string& path,
                                        const RigidActorDesc& d, size_t actorsSoFar) {
  if (!a.contains("grid")) return {d};
  const json& g = a.at("grid");
  const std::string gp = Join(path, "grid");
  CheckObject(g, gp, {"count", "spacing", "jitter", "seed"});
  const Eigen::Vector3d c = Vector<3>(g, gp, "count", Eigen::Vector3d::Ones());
  for (int k = 0; k < 3; ++k)
    if (c[k] < 1 || c[k] > 1000 || c[k] != std::floor(c[k]))
      Throw(Join(gp, "count"), "must hold integers in [1, 1000]");
  const double total = double(actorsSoFar) + c.prod();
  if (total > limits::kMaxActors)
    Throw(Join(gp, "count"),
          "makes " + NumberText(c.prod()) + " actors, " + NumberText(total) +
              " in the scene: beyond the limit of " + NumberText(limits::kMaxActors) +
              " actors per scene (about " +
              NumberText(c.prod() * limits::kBytesPerActor / 1e9) + " GB to load)");
  const Eigen::Vector3d spacing = Vector<3>(g, gp, "spacing", Eigen::Vector3d::Zero());
  const double jitter = Number(g, gp, "jitter", 0.0);
  if (jitter < 0) Throw(Join(gp, "jitter"), "must be >= 0");
  const std::vector<Eigen::Vector3d> offsets =
      GridCopyOffsets(c, spacing, jitter, Integer(g, gp, "seed", 1, 0, 1 << 30));
  std::vector<RigidActorDesc> out;
  for (size_t k = 0; k < offsets.size(); ++k) {
    RigidActorDesc di = d;
    di.name = d.name + "_" + std::to_string(k);
    di.position += offsets[k];
    const double far = di.position.cwiseAbs().maxCoeff();
    if (!(far <= limits::kMaxLength))  // also an overflow to infinity
      Throw(Join(gp, spacing.cwiseAbs().maxCoeff() * c.maxCoeff() > jitter ? "spacing" : "jitter"),
            "places actor " + di.name + " at a coordinate that " + TooLarge(far));
    out.push_back(std::move(di));
  }
  return out;
}

void ReadActors(const json& actors, const std::string& baseDir, SceneFile* out) {
  if (!actors.is_array()) Throw("actors", std::string("must be an array, got ") + TypeName(actors));
  if (double(actors.size()) > limits::kMaxActors)
    Throw("actors", "holds " + std::to_string(actors.size()) + " actors, beyond the limit of " +
                        NumberText(limits::kMaxActors) + " per scene");
  std::set<std::string> names;
  for (size_t i = 0; i < actors.size(); ++i) {
    const std::string path = "actors[" + std::to_string(i) + "]";
    const json& a = actors[i];
    if (a.is_object() && a.contains("type") && a.at("type") == "soft") {
      const ActorHandle parent = ReadParent(a, path, *out);
      const std::string name = String(a, path, "name");
      if (!names.insert(name).second) Throw(Join(path, "name"), "duplicate actor name \"" + name + "\"");
      ReadSoftActor(a, path, baseDir, parent, out);
      continue;
    }
    if (a.is_object() && a.contains("type") && a.at("type") == "shell") {
      const ActorHandle parent = ReadParent(a, path, *out);
      const ShellActorDesc d = ReadShellDesc(a, path, baseDir);
      if (!names.insert(d.name).second) Throw(Join(path, "name"), "duplicate actor name \"" + d.name + "\"");
      Error err;
      std::unique_ptr<ShellKind> kind = ShellKind::Build(d, &err);
      if (!kind || !out->scene->AddActor(std::move(kind), &err, d.contactLayer, parent).IsValid())
        throw LoadError{path + "." + err.message};
      out->actorNames.push_back(d.name);
      continue;
    }
    if (a.is_object() && a.contains("type") && a.at("type") == "articulated") {
      const ActorHandle parent = ReadParent(a, path, *out);
      const ArticulatedActorDesc d = ReadArticulatedDesc(a, path, baseDir);
      if (!names.insert(d.name).second) Throw(Join(path, "name"), "duplicate actor name \"" + d.name + "\"");
      Error err;
      const std::string layer = String(a, path, "contact_layer", std::string("default"));
      const int before = out->scene->NumActors();
      if (!out->scene->AddArticulatedActor(d, &err, layer, parent).IsValid())
        throw LoadError{path + ": " + err.message};
      // With its links' shapes (AddArticulatedActor refused names other actors have).
      for (int k = before; k < out->scene->NumActors(); ++k) {
        const std::string& name = out->scene->ActorName({k});
        names.insert(name);
        out->actorNames.push_back(name);
      }
      continue;
    }
    const RigidActorDesc d = ReadRigidDesc(a, path, baseDir);
    const ActorHandle parent = ReadParent(a, path, *out);
    if (double(out->actorNames.size()) + 1 > limits::kMaxActors)
      Throw(path, "is beyond the limit of " + NumberText(limits::kMaxActors) + " actors per scene");
    for (const RigidActorDesc& di : PlaceOnGrid(a, path, d, out->actorNames.size())) {
      if (!names.insert(di.name).second) Throw(Join(path, "name"), "duplicate actor name \"" + di.name + "\"");
      Error err;
      if (!out->scene->AddRigidActor(di, &err, parent).IsValid())
        throw LoadError{path + "." + err.message};
      out->actorNames.push_back(di.name);
    }
  }
}

// "contact_filter": [{"layers": [a, b] | "actors": [A, B], "enable": bool, "symmetric": bool,
//                     "include_nested": bool (actors only)}, ...], applied in order.
void ReadContactFilter(const json& list, SceneFile* out) {
  if (!list.is_array()) Throw("contact_filter", std::string("must be an array, got ") + TypeName(list));
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = "contact_filter[" + std::to_string(i) + "]";
    const json& f = list[i];
    CheckObject(f, path, {"layers", "actors", "enable", "symmetric", "include_nested"});
    if (f.contains("layers") == f.contains("actors"))
      Throw(path, "give exactly one of \"layers\" and \"actors\"");
    const std::string key = f.contains("layers") ? "layers" : "actors";
    const json& pair = f.at(key);
    if (!pair.is_array() || pair.size() != 2 || !pair[0].is_string() || !pair[1].is_string())
      Throw(Join(path, key), "must be an array of two names");
    const bool enable = Bool(f, path, "enable", false);
    const bool symmetric = Bool(f, path, "symmetric", true);
    Scene& scene = *out->scene;
    Error err;
    if (key == "layers") {
      if (f.contains("include_nested"))
        Throw(Join(path, "include_nested"), "applies to actor pairs only");
      const std::string a = pair[0], b = pair[1];
      if (symmetric) scene.EnableLayerContactSymmetric(a, b, enable, &err);
      else scene.EnableLayerContactAsymmetric(a, b, enable, &err);
      continue;
    }
    ActorHandle h[2];
    for (int k = 0; k < 2; ++k) {
      const std::string name = pair[k];
      for (size_t n = 0; n < out->actorNames.size(); ++n)
        if (out->actorNames[n] == name) h[k].index = static_cast<int>(n);
      if (!h[k].IsValid())
        Throw(Join(path, "actors") + "[" + std::to_string(k) + "]", "no actor named \"" + name + "\"");
    }
    const IncludeNestedActors nested =
        Bool(f, path, "include_nested", false) ? IncludeNestedActors::Yes : IncludeNestedActors::No;
    const bool ok = symmetric ? scene.EnableActorContactSymmetric(h[0], h[1], enable, nested, &err)
                              : scene.EnableActorContactAsymmetric(h[0], h[1], enable, nested, &err);
    if (!ok) Throw(path, err.message);
  }
}

}  // namespace

bool LoadSceneText(const std::string& text, const std::string& baseDir, SceneFile* out,
                   Error* error) {
  // A reused SceneFile starts empty (its path, set by LoadSceneFile, is kept).
  const std::string path = out->path;
  *out = SceneFile();
  out->path = path;
  out->textHash = SceneTextHash(text);
  try {
    json j;
    std::string parseError;
    if (!ParseJsonText(text, &j, &parseError))  // a number out of range names its JSON path
      return Fail(error, (parseError.rfind("not valid JSON", 0) == 0 ||
                                  parseError.rfind("nested", 0) == 0
                              ? "(file): "
                              : "") +
                             parseError);
    CheckObject(j, "", {"format", "superdex_version", "description", "settings", "actors",
                        "contact_filter", "output", "expect"});
    const std::string format = String(j, "", "format", std::string("superdex-scene/1"));
    if (format != "superdex-scene/1")
      Throw("format", "unsupported \"" + format + "\" (expected superdex-scene/1)");
    out->description = String(j, "", "description", std::string());

    SceneSettings settings;
    if (j.contains("settings")) {
      // The scene's settings, and the scene file's own: dt, duration, penetration_bound.
      const json& s = j.at("settings");
      ReadFields(s, "settings", kSceneSettingsFields, &settings,
                 {"dt", "duration", "penetration_bound"});
      if (s.contains("penetration_bound"))
        out->penetrationBound = Length(s, "settings", "penetration_bound");
      out->dt = Positive(s, "settings", "dt", out->dt);
      out->duration = Positive(s, "settings", "duration", out->duration);
    }
    if (std::string m = Validate(settings, "settings."); !m.empty()) throw LoadError{m};
    out->scene = std::make_unique<Scene>(settings);

    if (!j.contains("actors")) Throw("actors", "missing required field");
    ReadActors(j.at("actors"), baseDir, out);

    if (j.contains("contact_filter")) ReadContactFilter(j.at("contact_filter"), out);

    if (j.contains("output")) {
      ReadFields(j.at("output"), "output", kOutputSpecFields, &out->output);
    }
    if (j.contains("expect")) {
      const json& e = j.at("expect");
      CheckObject(e, "expect", {"max_penetration", "max_relative_energy_drift", "all_converged",
                                "final_positions"});
      if (e.contains("max_penetration")) out->expect.maxPenetration = Positive(e, "expect", "max_penetration");
      if (e.contains("max_relative_energy_drift"))
        out->expect.maxRelativeEnergyDrift = Positive(e, "expect", "max_relative_energy_drift");
      out->expect.allConverged = Bool(e, "expect", "all_converged", false);
      if (e.contains("final_positions")) {
        const json& f = e.at("final_positions");
        if (!f.is_array()) Throw("expect.final_positions", "must be an array");
        for (size_t i = 0; i < f.size(); ++i) {
          const std::string p = "expect.final_positions[" + std::to_string(i) + "]";
          CheckObject(f[i], p, {"actor", "position", "tolerance"});
          SceneExpectations::RestingActor r;
          r.actor = String(f[i], p, "actor");
          bool found = false;
          for (const auto& n : out->actorNames) found |= n == r.actor;
          if (!found) Throw(Join(p, "actor"), "no actor named \"" + r.actor + "\"");
          r.position = Vector<3>(f[i], p, "position", Eigen::Vector3d::Zero());
          r.tolerance = Positive(f[i], p, "tolerance");
          out->expect.finalPositions.push_back(r);
        }
      }
    }
  } catch (const LoadError& e) {
    return Fail(error, e.message);
  } catch (const std::bad_alloc&) {
    return Fail(error, "(file): out of memory while loading the scene");
  } catch (const std::exception& e) {
    return Fail(error, std::string("(file): ") + e.what());
  }
  return true;
}

bool LoadSceneFile(const std::string& path, SceneFile* out, Error* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Fail(error, path + ": cannot open file");
  in.seekg(0, std::ios::end);
  const double bytes = static_cast<double>(in.tellg());
  in.seekg(0, std::ios::beg);
  if (bytes > limits::kMaxSceneFileBytes)
    return Fail(error, path + ": the file holds " + NumberText(bytes) +
                           " bytes, beyond the limit of " +
                           NumberText(limits::kMaxSceneFileBytes) + " bytes per scene file");
  std::stringstream buf;
  buf << in.rdbuf();
  out->path = path;
  const size_t slash = path.find_last_of('/');
  const std::string baseDir = slash == std::string::npos ? "." : path.substr(0, slash);
  Error local;
  if (!LoadSceneText(buf.str(), baseDir, out, &local)) return Fail(error, path + ": " + local.message);
  return true;
}

}  // namespace superdex
