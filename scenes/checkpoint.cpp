#include "scenes/checkpoint.h"

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <type_traits>

#include "scenes/json_text.h"

namespace superdex {
namespace {

using json = nlohmann::json;

constexpr const char* kFormat = "superdex-checkpoint";
constexpr int kVersion = 1;
constexpr const char* kStateFormat = "superdex-state";
constexpr int kStateVersion = 1;
constexpr int kRigidValues = 24;  // p, R (column-major), v, Ṙ

// A double as a hex float string: exact, also for ±inf and nan.
std::string Hex(double x) {
  char text[64];
  std::snprintf(text, sizeof(text), "%a", x);
  return text;
}

std::string HashText(std::uint64_t h) {
  char text[32];
  std::snprintf(text, sizeof(text), "fnv1a64:%016" PRIx64, h);
  return text;
}

json Doubles(const double* x, int n) {
  json a = json::array();
  for (int i = 0; i < n; ++i) a.push_back(Hex(x[i]));
  return a;
}

json RigidJson(const std::vector<RigidBodyState>& states) {
  json a = json::array();
  for (const RigidBodyState& s : states) {
    double v[kRigidValues];
    Eigen::Map<Eigen::Vector3d>{v} = s.p;
    Eigen::Map<Eigen::Matrix3d>{v + 3} = s.R;
    Eigen::Map<Eigen::Vector3d>{v + 12} = s.v;
    Eigen::Map<Eigen::Matrix3d>{v + 15} = s.Rdot;
    a.push_back(Doubles(v, kRigidValues));
  }
  return a;
}

json VectorJson(const std::vector<SoftBodyState>& states) {
  json a = json::array();
  for (const SoftBodyState& s : states)
    a.push_back({{"x", Doubles(s.x.data(), static_cast<int>(s.x.size()))},
                 {"v", Doubles(s.v.data(), static_cast<int>(s.v.size()))}});
  return a;
}

// The scene's side (time, states, history, the stage policy's state) into *j.
void SnapshotToJson(const Scene::Snapshot& snapshot, json* out) {
  json& j = *out;
  const StageDriver::State& d = snapshot.driver;
  j["driver"] = {{"explicit_first_stages", d.explicitFirstStages},
                 {"explicit_first_run", d.explicitFirstRun},
                 {"last_potential_iterations", d.lastPotentialIterations},
                 {"last_stage_in_contact", d.lastStageInContact}};
  const StepState& s = snapshot.step;
  j["time"] = Hex(s.time);
  j["rigid"] = RigidJson(s.rigidStates);
  j["vector"] = VectorJson(s.vectorStates);
  json history = json::array();
  for (size_t h = 0; h < s.rigidHistory.size(); ++h)
    history.push_back({{"time", Hex(h < s.historyTimes.size() ? s.historyTimes[h] : 0.0)},
                       {"rigid", RigidJson(s.rigidHistory[h])},
                       {"vector", VectorJson(h < s.vectorHistory.size() ? s.vectorHistory[h]
                                                                       : std::vector<SoftBodyState>())}});
  j["history"] = history;
}

json ToJson(const Checkpoint& c) {
  const CheckpointRun& r = c.run;
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["scene_hash"] = HashText(c.sceneHash);
  j["scene"] = c.scenePath;
  json run = {{"step", r.step},
              {"dt", Hex(r.dt)},
              {"integrator", r.integrator},
              {"trajectory", r.trajectoryPath},
              {"trajectory_bytes", r.trajectoryBytes}};
  // The summary's accumulators: integers as JSON integers, doubles as hex floats (the object's
  // keys are sorted when written).
  ForEachField(kRunAccumulatorFields, [&](const auto& f) {
    if constexpr (std::is_integral_v<typename std::decay_t<decltype(f)>::ValueType>)
      run[f.name] = f.Of(r);
    else
      run[f.name] = Hex(f.Of(r));
  });
  j["run"] = run;
  SnapshotToJson(c.snapshot, &j);
  return j;
}

// Reading: each accessor throws Bad{"<field>: <rule>"} on the first problem.
struct Bad {
  std::string message;
};
[[noreturn]] void Throw(const std::string& field, const std::string& rule) {
  throw Bad{field + ": " + rule};
}

const json& At(const json& j, const std::string& path, const char* key) {
  if (!j.is_object()) Throw(path, "must be an object");
  if (!j.contains(key)) Throw(path.empty() ? key : path + "." + key, "missing");
  return j.at(key);
}

std::string Field(const std::string& path, const char* key) {
  return path.empty() ? key : path + "." + key;
}

double HexNumber(const json& v, const std::string& field) {
  if (!v.is_string()) Throw(field, "must be a hex float string, got " + std::string(v.type_name()));
  const std::string& text = v.get_ref<const std::string&>();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size())
    Throw(field, "\"" + text + "\" is not a number");
  return x;
}

double HexAt(const json& j, const std::string& path, const char* key) {
  return HexNumber(At(j, path, key), Field(path, key));
}

long long IntegerAt(const json& j, const std::string& path, const char* key, long long lo) {
  const json& v = At(j, path, key);
  if (!v.is_number_integer()) Throw(Field(path, key), "must be an integer");
  const long long x = v.is_number_unsigned() && v.get<unsigned long long>() > (1ULL << 62)
                          ? (1LL << 62)
                          : v.get<long long>();
  if (x < lo || x > (1LL << 53)) Throw(Field(path, key), "out of range: " + v.dump());
  return x;
}

std::string StringAt(const json& j, const std::string& path, const char* key) {
  const json& v = At(j, path, key);
  if (!v.is_string()) Throw(Field(path, key), "must be a string");
  return v.get<std::string>();
}

const json& ArrayAt(const json& j, const std::string& path, const char* key) {
  const json& v = At(j, path, key);
  if (!v.is_array()) Throw(Field(path, key), "must be an array");
  return v;
}

void ReadDoubles(const json& a, const std::string& field, Eigen::VectorXd* out) {
  if (!a.is_array()) Throw(field, "must be an array");
  out->resize(static_cast<Eigen::Index>(a.size()));
  for (size_t i = 0; i < a.size(); ++i)
    (*out)[static_cast<Eigen::Index>(i)] =
        HexNumber(a[i], field + "[" + std::to_string(i) + "]");
}

std::vector<RigidBodyState> ReadRigid(const json& j, const std::string& path) {
  const json& a = ArrayAt(j, path, "rigid");
  std::vector<RigidBodyState> states(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    const std::string field = Field(path, "rigid") + "[" + std::to_string(i) + "]";
    Eigen::VectorXd v;
    ReadDoubles(a[i], field, &v);
    if (v.size() != kRigidValues)
      Throw(field, "needs 24 numbers (p, R, v, dR/dt), got " + std::to_string(v.size()));
    states[i].p = v.segment<3>(0);
    states[i].R = Eigen::Map<const Eigen::Matrix3d>(v.data() + 3);
    states[i].v = v.segment<3>(12);
    states[i].Rdot = Eigen::Map<const Eigen::Matrix3d>(v.data() + 15);
  }
  return states;
}

std::vector<SoftBodyState> ReadVector(const json& j, const std::string& path) {
  const json& a = ArrayAt(j, path, "vector");
  std::vector<SoftBodyState> states(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    const std::string field = Field(path, "vector") + "[" + std::to_string(i) + "]";
    ReadDoubles(At(a[i], field, "x"), field + ".x", &states[i].x);
    ReadDoubles(At(a[i], field, "v"), field + ".v", &states[i].v);
    if (states[i].x.size() != states[i].v.size())
      Throw(field, "x and v differ in length");
  }
  return states;
}

void ReadRun(const json& j, CheckpointRun* r) {
  const json& run = At(j, "", "run");
  r->step = IntegerAt(run, "run", "step", 0);
  r->dt = HexAt(run, "run", "dt");
  r->integrator = StringAt(run, "run", "integrator");
  r->trajectoryPath = StringAt(run, "run", "trajectory");
  r->trajectoryBytes = IntegerAt(run, "run", "trajectory_bytes", 0);
  ForEachField(kRunAccumulatorFields, [&](const auto& f) {
    using T = typename std::decay_t<decltype(f)>::ValueType;
    if constexpr (std::is_integral_v<T>)
      f.Of(*r) = static_cast<T>(IntegerAt(run, "run", f.name, 0));
    else
      f.Of(*r) = HexAt(run, "run", f.name);
  });
}

// The scene's side of SnapshotToJson back from j (Bad on the first problem).
void SnapshotFromJson(const json& j, Scene::Snapshot* snapshot) {
  const json& d = At(j, "", "driver");
  StageDriver::State& ds = snapshot->driver;
  ds.explicitFirstStages = static_cast<int>(IntegerAt(d, "driver", "explicit_first_stages", 0));
  ds.explicitFirstRun = static_cast<int>(IntegerAt(d, "driver", "explicit_first_run", 0));
  ds.lastPotentialIterations =
      static_cast<int>(IntegerAt(d, "driver", "last_potential_iterations", 0));
  const json& contact = At(d, "driver", "last_stage_in_contact");
  if (!contact.is_boolean()) Throw("driver.last_stage_in_contact", "must be true or false");
  ds.lastStageInContact = contact.get<bool>();
  StepState& s = snapshot->step;
  s = StepState();
  s.time = HexAt(j, "", "time");
  s.rigidStates = ReadRigid(j, "");
  s.vectorStates = ReadVector(j, "");
  const json& history = ArrayAt(j, "", "history");
  if (history.size() > 2) Throw("history", "holds at most 2 states, got " + std::to_string(history.size()));
  for (size_t h = 0; h < history.size(); ++h) {
    const std::string path = "history[" + std::to_string(h) + "]";
    s.historyTimes.push_back(HexAt(history[h], path, "time"));
    s.rigidHistory.push_back(ReadRigid(history[h], path));
    s.vectorHistory.push_back(ReadVector(history[h], path));
  }
}

// The document's format and version (Bad unless they are `format` and `version`).
void CheckHeader(const json& j, const char* format, int version) {
  if (!j.is_object()) Throw("(top level)", "must be an object");
  if (StringAt(j, "", "format") != format)
    Throw("format", "\"" + StringAt(j, "", "format") + "\" is not \"" + format + "\"");
  const long long v = IntegerAt(j, "", "version", 0);
  if (v != version)
    Throw("version", std::to_string(v) + " is not supported (this build reads version " +
                         std::to_string(version) + ")");
}

void FromJson(const json& j, Checkpoint* c) {
  CheckHeader(j, kFormat, kVersion);
  const std::string hash = StringAt(j, "", "scene_hash");
  unsigned long long h = 0;
  char tail = 0;
  if (std::sscanf(hash.c_str(), "fnv1a64:%16llx%c", &h, &tail) != 1 || hash.size() != 24)
    Throw("scene_hash", "\"" + hash + "\" is not fnv1a64:<16 hex digits>");
  c->sceneHash = h;
  c->scenePath = StringAt(j, "", "scene");
  ReadRun(j, &c->run);
  SnapshotFromJson(j, &c->snapshot);
}

// Whether `states` have the shapes of `reference` (the scene's own), else the field and rule.
std::string SameShapes(const std::vector<RigidBodyState>& rigid,
                       const std::vector<SoftBodyState>& vector, const StepState& reference,
                       const std::string& path) {
  if (rigid.size() != reference.rigidStates.size())
    return Field(path, "rigid") + ": " + std::to_string(rigid.size()) +
           " rigid actors, the scene has " + std::to_string(reference.rigidStates.size());
  if (vector.size() != reference.vectorStates.size())
    return Field(path, "vector") + ": " + std::to_string(vector.size()) +
           " soft (and generic) actors, the scene has " +
           std::to_string(reference.vectorStates.size());
  for (size_t i = 0; i < vector.size(); ++i)
    if (vector[i].x.size() != reference.vectorStates[i].x.size())
      return Field(path, "vector") + "[" + std::to_string(i) + "].x: " +
             std::to_string(vector[i].x.size()) + " values, the scene's actor has " +
             std::to_string(reference.vectorStates[i].x.size());
  return {};
}

// Whether a snapshot's states and history have the sizes of `scene`'s, else the field and rule.
std::string SnapshotShapes(const Scene::Snapshot& snapshot, const Scene& scene) {
  const StepState reference = scene.Save().step;
  const StepState& s = snapshot.step;
  if (std::string m = SameShapes(s.rigidStates, s.vectorStates, reference, ""); !m.empty()) return m;
  for (size_t h = 0; h < s.rigidHistory.size(); ++h)
    if (std::string m = SameShapes(s.rigidHistory[h], s.vectorHistory[h], reference,
                                   "history[" + std::to_string(h) + "]");
        !m.empty())
      return m;
  return {};
}

}  // namespace

std::uint64_t SceneTextHash(const std::string& text) {
  std::uint64_t h = 14695981039346656037ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

bool WriteCheckpoint(const std::string& path, const Checkpoint& checkpoint, Error* error) {
  const std::string part = path + ".part";
  const std::string text = ToJson(checkpoint).dump() + "\n";
  auto failed = [&](const std::string& what) {
    const std::string reason = errno ? std::strerror(errno) : "write error";
    std::remove(part.c_str());
    return Fail(error, "checkpoint: " + what + " \"" + path + "\" failed: " + reason);
  };
  errno = 0;
  std::FILE* f = std::fopen(part.c_str(), "wb");
  if (!f) return failed("writing");
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size() &&
                       std::fflush(f) == 0;
  if (std::fclose(f) != 0 || !written) return failed("writing");
  if (std::rename(part.c_str(), path.c_str()) != 0) return failed("renaming the new");
  return true;
}

bool ReadCheckpoint(const std::string& path, Checkpoint* checkpoint, Error* error) {
  const std::string where = "checkpoint " + path + ": ";
  std::ifstream in(path, std::ios::binary);
  if (!in) return Fail(error, where + "cannot open file");
  std::stringstream buf;
  buf << in.rdbuf();
  const std::string text = buf.str();
  if (text.empty()) return Fail(error, where + "the file is empty");
  json j;
  std::string why;
  if (!ParseJsonText(text, &j, &why))
    return Fail(error, where + why + (text.back() != '\n' ? " (the file is truncated)" : ""));
  try {
    FromJson(j, checkpoint);
  } catch (const Bad& bad) {
    return Fail(error, where + bad.message);
  }
  return true;
}

bool CheckpointFits(const Checkpoint& c, const std::string& path, const Scene& scene,
                    std::uint64_t sceneHash, double dt, Error* error) {
  const std::string where = "checkpoint " + path + ": ";
  if (c.sceneHash != sceneHash)
    return Fail(error, where + "scene_hash: written for the scene file \"" + c.scenePath +
                           "\" (" + HashText(c.sceneHash) + "); this scene file's text has " +
                           HashText(sceneHash) +
                           ": resume with the scene file the checkpoint was written from");
  if (c.run.dt != dt)
    return Fail(error, where + "run.dt: written at dt = " + Hex(c.run.dt) + " s, resumed at " +
                           Hex(dt) + " s (give the same --dt)");
  const std::string integrator = ToString(scene.Settings().integrator);
  if (c.run.integrator != integrator)
    return Fail(error, where + "run.integrator: written with " + c.run.integrator +
                           ", resumed with " + integrator + " (give the same --integrator)");
  if (std::string m = SnapshotShapes(c.snapshot, scene); !m.empty()) return Fail(error, where + m);
  return true;
}

std::string StateText(const Scene::Snapshot& snapshot) {
  json j;
  j["format"] = kStateFormat;
  j["version"] = kStateVersion;
  SnapshotToJson(snapshot, &j);
  return j.dump();
}

bool ReadStateText(const std::string& text, Scene::Snapshot* snapshot, Error* error) {
  json j;
  std::string why;
  if (!ParseJsonText(text, &j, &why)) return Fail(error, "state: " + why);
  try {
    CheckHeader(j, kStateFormat, kStateVersion);
    SnapshotFromJson(j, snapshot);
  } catch (const Bad& bad) {
    return Fail(error, "state: " + bad.message);
  }
  return true;
}

bool StateFits(const Scene::Snapshot& snapshot, const Scene& scene, Error* error) {
  if (std::string m = SnapshotShapes(snapshot, scene); !m.empty())
    return Fail(error, "state: " + m);
  return true;
}

}  // namespace superdex
