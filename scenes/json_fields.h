// The scene file's field readers (internal to scenes/): each reads one JSON field and throws
// LoadError "<json path>: <rule>" on the first problem; LoadSceneText turns it into an Error.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <climits>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include "core/scene.h"
#include "geometry/number_text.h"
#include "scenes/limits.h"

namespace superdex::scene_json {

using json = nlohmann::json;

// Internal only: loading stops at the first problem; LoadSceneText turns it into an Error.
struct LoadError {
  std::string message;
};
[[noreturn]] inline void Throw(const std::string& path, const std::string& rule) {
  throw LoadError{path + ": " + rule};
}

inline std::string Join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

inline const char* TypeName(const json& j) { return j.type_name(); }

inline void CheckObject(const json& j, const std::string& path, std::set<std::string> known) {
  if (!j.is_object()) Throw(path.empty() ? "(top level)" : path, std::string("must be an object, got ") + TypeName(j));
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!known.count(it.key())) Throw(Join(path, it.key()), "unknown field");
}

inline double Number(const json& obj, const std::string& path, const char* key,
              std::optional<double> def = std::nullopt) {
  const std::string p = Join(path, key);
  if (!obj.contains(key)) {
    if (def) return *def;
    Throw(p, "missing required field");
  }
  const json& v = obj.at(key);
  if (!v.is_number()) Throw(p, std::string("must be a number, got ") + TypeName(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) Throw(p, "must be finite");
  return x;
}

inline double Positive(const json& obj, const std::string& path, const char* key,
                std::optional<double> def = std::nullopt) {
  const double x = Number(obj, path, key, def);
  if (!(x > 0)) {
    std::ostringstream s;
    s << "must be > 0, got " << x;
    Throw(Join(path, key), s.str());
  }
  return x;
}

inline int Integer(const json& obj, const std::string& path, const char* key, int def, int lo, int hi) {
  const std::string p = Join(path, key);
  if (!obj.contains(key)) return def;
  const json& v = obj.at(key);
  if (!v.is_number_integer()) Throw(p, std::string("must be an integer, got ") + TypeName(v));
  // An unsigned value above the signed range must not wrap to a small one.
  const bool huge = v.is_number_unsigned() && v.get<unsigned long long>() > LLONG_MAX;
  const long long x = huge ? LLONG_MAX : v.get<long long>();
  if (x < lo || x > hi) {
    std::ostringstream s;
    s << "must be in [" << lo << ", " << hi << "], got " << v.dump();
    Throw(p, s.str());
  }
  return static_cast<int>(x);
}

inline bool Bool(const json& obj, const std::string& path, const char* key, bool def) {
  if (!obj.contains(key)) return def;
  const json& v = obj.at(key);
  if (!v.is_boolean()) Throw(Join(path, key), std::string("must be true or false, got ") + TypeName(v));
  return v.get<bool>();
}

inline std::string String(const json& obj, const std::string& path, const char* key,
                   std::optional<std::string> def = std::nullopt) {
  if (!obj.contains(key)) {
    if (def) return *def;
    Throw(Join(path, key), "missing required field");
  }
  const json& v = obj.at(key);
  if (!v.is_string()) Throw(Join(path, key), std::string("must be a string, got ") + TypeName(v));
  return v.get<std::string>();
}

template <int N>
Eigen::Matrix<double, N, 1> Vector(const json& obj, const std::string& path, const char* key,
                                   const Eigen::Matrix<double, N, 1>& def) {
  if (!obj.contains(key)) return def;
  const json& v = obj.at(key);
  const std::string p = Join(path, key);
  if (!v.is_array() || v.size() != N)
    Throw(p, "must be an array of " + std::to_string(N) + " numbers");
  Eigen::Matrix<double, N, 1> out;
  for (int i = 0; i < N; ++i) {
    if (!v[i].is_number()) Throw(p + "[" + std::to_string(i) + "]", "must be a number");
    out[i] = v[i].get<double>();
    if (!std::isfinite(out[i])) Throw(p + "[" + std::to_string(i) + "]", "must be finite");
  }
  return out;
}

/// Calls each(item, "<path>.<key>[m]") for every item of the array obj[key] (present); a value
/// that is no array is refused with `rule`.
template <typename Each>
void ForEachItem(const json& obj, const std::string& path, const char* key, const char* rule,
                 Each each) {
  const json& list = obj.at(key);
  const std::string p = Join(path, key);
  if (!list.is_array()) Throw(p, rule);
  for (size_t m = 0; m < list.size(); ++m) each(list[m], p + "[" + std::to_string(m) + "]");
}

/// "must be at most <kMaxLength> m ..., got x": the scene-size rule (limits::kMaxLength).
inline std::string TooLarge(double x) {
  return "must be at most " + NumberText(limits::kMaxLength) + " m (the scene size limit), got " +
         NumberText(x);
}

/// A length [m] in (0, limits::kMaxLength].
inline double Length(const json& obj, const std::string& path, const char* key,
                     std::optional<double> def = std::nullopt) {
  const double x = Positive(obj, path, key, def);
  if (x > limits::kMaxLength) Throw(Join(path, key), TooLarge(x));
  return x;
}

/// A point or extent [m] whose components are within ±limits::kMaxLength.
inline Eigen::Vector3d Point(const json& obj, const std::string& path, const char* key,
                             const Eigen::Vector3d& def) {
  const Eigen::Vector3d p = Vector<3>(obj, path, key, def);
  for (int i = 0; i < 3; ++i)
    if (std::abs(p[i]) > limits::kMaxLength)
      Throw(Join(path, key) + "[" + std::to_string(i) + "]", TooLarge(p[i]));
  return p;
}

/// Mesh vertices (after their scale) within ±limits::kMaxLength; `path` names the field to blame.
inline void CheckCoordinates(const std::vector<Eigen::Vector3d>& vertices, const std::string& path) {
  double largest = 0.0;
  for (const Eigen::Vector3d& v : vertices) largest = std::max(largest, v.cwiseAbs().maxCoeff());
  if (largest > limits::kMaxLength)
    Throw(path, "the mesh's coordinates (after scale) " + TooLarge(largest));
}

template <typename E>
E Enum(const json& obj, const std::string& path, const char* key, E def) {
  if (!obj.contains(key)) return def;
  const std::string s = String(obj, path, key);
  E e;
  if (!ParseName(s, &e))
    Throw(Join(path, key), "unknown value \"" + s + "\" (expected one of: " + AllNames(def) + ")");
  return e;
}

// Whether T is std::optional of an enum (a field that may be left unset).
template <typename T>
inline constexpr bool kIsOptionalEnum = false;
template <typename E>
inline constexpr bool kIsOptionalEnum<std::optional<E>> = std::is_enum_v<E>;

// Reads the fields of a parameter table (optim/field_table.h) from the object j: the keys are the
// rows' names (a nested row's key holds an object read by its own table), an absent key keeps the
// value in *out, any other key is refused unless it is one of `alsoKnown` (read by the caller).
// The rules are checked where the struct is validated (Validate, Scene::Add...Actor), except
// integers' range.
template <typename Table, typename Class>
void ReadFields(const json& j, const std::string& path, const Table& table, Class* out,
                std::set<std::string> alsoKnown = {}) {
  ForEachField(table, [&](const auto& f) { alsoKnown.insert(f.name); });
  CheckObject(j, path, alsoKnown);
  ForEachField(table, [&](const auto& f) {
    using T = typename std::decay_t<decltype(f)>::ValueType;
    T& v = f.Of(*out);
    if constexpr (kIsNested<decltype(f)>) {
      if (j.contains(f.name)) ReadFields(j.at(f.name), Join(path, f.name), *f.table, &v);
    } else if constexpr (std::is_same_v<T, bool>) {
      v = Bool(j, path, f.name, v);
    } else if constexpr (std::is_enum_v<T>) {
      v = Enum(j, path, f.name, v);
    } else if constexpr (std::is_same_v<T, int>) {
      const int lo = f.rule.kind == Rule::AtLeast ? static_cast<int>(f.rule.lo) : INT_MIN;
      const int hi = f.rule.fileMax > 0
                         ? static_cast<int>(std::min<long long>(f.rule.fileMax, INT_MAX))
                         : INT_MAX;
      v = Integer(j, path, f.name, v, lo, hi);
    } else if constexpr (std::is_same_v<T, double>) {
      v = Number(j, path, f.name, v);
    } else if constexpr (std::is_same_v<T, std::string>) {
      v = String(j, path, f.name, v);
    } else if constexpr (kIsFixedVector<T>) {
      v = Vector<T::RowsAtCompileTime>(j, path, f.name, v);
    } else if constexpr (kIsOptionalEnum<T>) {  // absent or null: none
      if (j.contains(f.name) && !j.at(f.name).is_null())
        v = Enum(j, path, f.name, typename T::value_type());
      else if (j.contains(f.name))
        v.reset();
    } else {
      static_assert(sizeof(T) == 0, "no scene-file reader for this field type");
    }
  });
}

/// "orientation" [x, y, z, w] or "euler_deg" [x, y, z] (intrinsic z-y'-x''; at most one; absent:
/// the identity).
inline Eigen::Quaterniond ReadOrientation(const json& j, const std::string& path) {
  if (j.contains("orientation") && j.contains("euler_deg"))
    Throw(path, "give at most one of \"orientation\" and \"euler_deg\"");
  if (j.contains("euler_deg")) {
    const Eigen::Vector3d e = Vector<3>(j, path, "euler_deg", Eigen::Vector3d::Zero()) * M_PI / 180.0;
    return Eigen::AngleAxisd(e.z(), Eigen::Vector3d::UnitZ()) *
           Eigen::AngleAxisd(e.y(), Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(e.x(), Eigen::Vector3d::UnitX());
  }
  const Eigen::Vector4d q = Vector<4>(j, path, "orientation", Eigen::Vector4d(0, 0, 0, 1));
  if (!(q.norm() > 0)) Throw(Join(path, "orientation"), "must be a non-zero quaternion [x, y, z, w]");
  // As given: the actor normalizes it once when it is built, as for a description from Python.
  return Eigen::Quaterniond(q[3], q[0], q[1], q[2]);
}

}  // namespace superdex::scene_json
