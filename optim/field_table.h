// Tables that write a name once: the names of an enum's values (EnumName), and the fields of a
// parameter struct (Field: snake_case name, member, unit, rule, description; the default is the
// struct's own initializer). Validation is generated here (ValidateFields, and Validate for a
// struct that names its table with FieldsOf); the scene-file reader
// (scenes/scene_file.cpp), the Python properties (python/src/bind_params.cpp) and
// docs/parameters.md (`superdex params --markdown`) iterate the same tables.
//
// It sits in optim/ because optim is the lowest place both the solver's parameters
// (NonlinearSolverParams) and core/model's can include; it knows nothing of either.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>

namespace superdex {

// ---------------------------------------------------------------------------------------------
// Enum names. An enum E has a name table when `NamesOf(E())` is declared next to it (found by
// argument-dependent lookup):
//   EnumNames<Color> NamesOf(Color);
// and defined once, in a .cpp file, over its rows (value, name, optional doc):
//   SUPERDEX_ENUM_NAMES(Color, {Color::Red, "Red"}, {Color::Blue, "Blue", "doc"})
// Then ToString, Parse, ParseName, AllNames and OneOfText below work for it.
#define SUPERDEX_ENUM_NAMES(E, ...)                              \
  EnumNames<E> NamesOf(E) {                                      \
    static constexpr EnumName<E> kNameTable[] = {__VA_ARGS__};   \
    return kNameTable;                                           \
  }

template <typename E>
struct EnumName {
  E value;
  const char* name;
  const char* doc = "";  ///< one line for the Python enum and the docs ("" if none)
};

/// A view of an enum's name table.
template <typename E>
struct EnumNames {
  const EnumName<E>* first = nullptr;
  const EnumName<E>* last = nullptr;
  template <size_t N>
  constexpr EnumNames(const EnumName<E> (&table)[N]) : first(table), last(table + N) {}
  constexpr const EnumName<E>* begin() const { return first; }
  constexpr const EnumName<E>* end() const { return last; }
};

template <typename E>
using IfNamed = std::enable_if_t<std::is_enum_v<E>, decltype(NamesOf(E()))>;

/// The value's name; "?" for a value outside the table.
template <typename E, typename = IfNamed<E>>
const char* ToString(E value) {
  for (const EnumName<E>& n : NamesOf(E()))
    if (n.value == value) return n.name;
  return "?";
}

/// Parses the exact name (e.g. "BDF2", "P1Q3"). False if unknown.
template <typename E, typename = IfNamed<E>>
bool Parse(const std::string& name, E* value) {
  for (const EnumName<E>& n : NamesOf(E()))
    if (name == n.name) {
      *value = n.value;
      return true;
    }
  return false;
}

/// Parses a name as every reader does (scene files, Python, the command line): the exact name,
/// unless the enum declares its own ParseName overload next to it (found by argument-dependent
/// lookup; e.g. one that also accepts a capitalized name).
template <typename E, typename = IfNamed<E>>
bool ParseName(const std::string& name, E* value) {
  return Parse(name, value);
}

/// Whether the value is one of the table's.
template <typename E, typename = IfNamed<E>>
bool IsNamed(E value) {
  for (const EnumName<E>& n : NamesOf(E()))
    if (n.value == value) return true;
  return false;
}

/// "A, B, C": every valid name, for error messages.
template <typename E, typename = IfNamed<E>>
std::string AllNames(E) {
  std::string out;
  for (const EnumName<E>& n : NamesOf(E())) out += (out.empty() ? "" : ", ") + std::string(n.name);
  return out;
}

/// "A, B or C".
template <typename E, typename = IfNamed<E>>
std::string OneOfText(E) {
  std::string out;
  const EnumNames<E> names = NamesOf(E());
  for (const EnumName<E>* n = names.begin(); n != names.end(); ++n)
    out += (n == names.begin() ? "" : n + 1 == names.end() ? " or " : ", ") + std::string(n->name);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Rules. A field's value must satisfy its rule; the message is "<field>: must be <Text()>, got
// <value>". Numbers must also be finite where the kind says so.

struct Rule {
  enum Kind {
    Any,          ///< no constraint (flags, names: an enum field must be one of its names)
    Finite,       ///< finite
    Positive,     ///< finite and > 0
    NonNegative,  ///< finite and >= 0
    Closed,       ///< finite and in [lo, hi]
    Open,         ///< in (lo, hi)
    Above,        ///< finite and > lo
    AtLeast,      ///< an integer >= lo
  };
  Kind kind = Any;
  double lo = 0.0, hi = 0.0;
  /// Integers: the largest value a scene file accepts (a guard against typos; 0: none).
  long long fileMax = 0;
  /// The message's words where they are not the kind's own (e.g. "finite and > 0").
  const char* wording = nullptr;

  template <typename T>
  bool Holds(T x) const {
    const double v = static_cast<double>(x);
    switch (kind) {
      case Any: return true;
      case Finite: return std::isfinite(v);
      case Positive: return std::isfinite(v) && v > 0.0;
      case NonNegative: return std::isfinite(v) && v >= 0.0;
      case Closed: return std::isfinite(v) && v >= lo && v <= hi;
      case Open: return v > lo && v < hi;
      case Above: return std::isfinite(v) && v > lo;
      case AtLeast: return v >= lo;
    }
    return false;
  }
  /// What follows "must be ": "> 0", "in [-1, 1]", ...; "" for Any.
  std::string Text() const {
    if (wording) return wording;
    std::ostringstream s;
    switch (kind) {
      case Any: break;
      case Finite: s << "finite"; break;
      case Positive: s << "> 0"; break;
      case NonNegative: s << ">= 0"; break;
      case Closed: s << "in [" << lo << ", " << hi << "]"; break;
      case Open: s << "in (" << lo << ", " << hi << ")"; break;
      case Above: s << "> " << lo; break;
      case AtLeast: s << ">= " << lo; break;
    }
    return s.str();
  }
  /// The same rule with other words in its message.
  constexpr Rule Worded(const char* words) const {
    Rule r = *this;
    r.wording = words;
    return r;
  }
};

constexpr Rule NoRule() { return {}; }
constexpr Rule FiniteRule() { return {Rule::Finite}; }
constexpr Rule PositiveRule() { return {Rule::Positive}; }
constexpr Rule NonNegativeRule() { return {Rule::NonNegative}; }
constexpr Rule InClosed(double lo, double hi) { return {Rule::Closed, lo, hi}; }
constexpr Rule InOpen(double lo, double hi) { return {Rule::Open, lo, hi}; }
/// Finite and > lo.
constexpr Rule Above(double lo) { return {Rule::Above, lo}; }
/// An integer >= lo; a scene file also refuses values above fileMax.
constexpr Rule AtLeast(int lo, long long fileMax) {
  return {Rule::AtLeast, double(lo), 0.0, fileMax};
}

// ---------------------------------------------------------------------------------------------
// Fields. A table is a std::tuple of rows, one per parameter, in the order of validation:
//   - Field (MakeField): a value: a number (double, int), a flag, an enum's name, an optional
//     enum, a text (std::string), or a fixed-size vector of numbers (Eigen::Matrix<double, N, 1>;
//     the rule holds for every component). A row of a nested struct spliced into the outer table (e.g.
//     NonlinearSolverParams::linear) reaches its member through `outer` (LiftFields).
//   - NestedField (MakeNested): a struct member with a table of its own (e.g.
//     SceneSettings::solver): an object in scene files, a property holding the struct in Python,
//     its own section in the docs, validated by the struct's Validate.

template <typename Class, typename T, typename Inner = Class>
struct Field {
  using ClassType = Class;
  using ValueType = T;
  using Outer = std::conditional_t<std::is_same_v<Inner, Class>, std::nullptr_t, Inner Class::*>;
  const char* name;  ///< snake_case: the JSON key, the Python property, the message's field
  Outer outer;       ///< the nested struct holding the member (nullptr when Inner is Class)
  T Inner::*member;
  const char* unit;  ///< SI unit ("m", "Pa/m", "-" for ratios); "" for flags and names
  Rule rule;
  const char* doc;  ///< what it is, one sentence

  constexpr T& Of(Class& c) const {
    if constexpr (std::is_same_v<Inner, Class>) return c.*member;
    else return (c.*outer).*member;
  }
  constexpr const T& Of(const Class& c) const {
    if constexpr (std::is_same_v<Inner, Class>) return c.*member;
    else return (c.*outer).*member;
  }
  /// The struct's default initializer's value.
  T Default() const {
    const Class c{};
    return Of(c);
  }
};

template <typename Class, typename T>
constexpr Field<Class, T> MakeField(const char* name, T Class::*member, const char* unit, Rule rule,
                                    const char* doc) {
  return {name, nullptr, member, unit, rule, doc};
}

/// A row without a rule: a figure a run reports (RunSummary), never read from input.
template <typename Class, typename T>
constexpr Field<Class, T> MakeField(const char* name, T Class::*member, const char* unit,
                                    const char* doc) {
  return MakeField(name, member, unit, NoRule(), doc);
}

/// A struct member with its own table (`table`, its Validate), named `typeName` in the docs.
template <typename Class, typename Inner, typename Table>
struct NestedField {
  using ClassType = Class;
  using ValueType = Inner;
  const char* name;      ///< snake_case: the JSON key, the Python property, the message's field
  Inner Class::*member;
  const char* typeName;  ///< the struct's name, e.g. "NonlinearSolverParams"
  const Table* table;
  const char* doc;

  constexpr Inner& Of(Class& c) const { return c.*member; }
  constexpr const Inner& Of(const Class& c) const { return c.*member; }
};

template <typename Class, typename Inner, typename Table>
constexpr NestedField<Class, Inner, Table> MakeNested(const char* name, Inner Class::*member,
                                                      const char* typeName, const Table& table,
                                                      const char* doc) {
  return {name, member, typeName, &table, doc};
}

template <typename F>
struct IsNestedField : std::false_type {};
template <typename Class, typename Inner, typename Table>
struct IsNestedField<NestedField<Class, Inner, Table>> : std::true_type {};
/// Whether the row F (a row's decayed type) is a NestedField.
template <typename F>
constexpr bool kIsNested = IsNestedField<std::decay_t<F>>::value;

/// A nested struct's table as rows of the outer struct.
template <typename Class, typename Inner, typename... T>
constexpr auto LiftFields(Inner Class::*outer, const std::tuple<Field<Inner, T>...>& table) {
  return std::apply(
      [outer](const auto&... f) {
        return std::make_tuple(Field<Class, typename std::decay_t<decltype(f)>::ValueType, Inner>{
            f.name, outer, f.member, f.unit, f.rule, f.doc}...);
      },
      table);
}

/// Calls visit(row) for every row of the table, in order.
template <typename Table, typename Visit>
void ForEachField(const Table& table, Visit&& visit) {
  std::apply([&](const auto&... f) { (visit(f), ...); }, table);
}

/// Calls visit(row) in order until it returns true; whether one did.
template <typename Table, typename Visit>
bool AnyField(const Table& table, Visit&& visit) {
  return std::apply([&](const auto&... f) { return (visit(f) || ...); }, table);
}

/// The snake_case name of the table's row for `member` (a direct member of Class); "?" if none.
template <typename Table, typename Class, typename T>
const char* FieldName(const Table& table, T Class::*member) {
  const char* name = "?";
  ForEachField(table, [&](const auto& f) {
    if constexpr (std::is_same_v<std::decay_t<decltype(f.member)>, T Class::*> &&
                  std::is_same_v<typename std::decay_t<decltype(f)>::ClassType, Class>)
      if (f.member == member) name = f.name;
  });
  return name;
}

namespace field_table_detail {
template <typename T>
struct IsOptional : std::false_type {};
template <typename T>
struct IsOptional<std::optional<T>> : std::true_type {};
}  // namespace field_table_detail

/// Whether T is a fixed-size column of doubles (a vector row: gravity [m/s²]).
template <typename T>
struct IsFixedVector : std::false_type {};
template <int N>
struct IsFixedVector<Eigen::Matrix<double, N, 1>> : std::true_type {};
template <typename T>
constexpr bool kIsFixedVector = IsFixedVector<T>::value;

/// Values as the tables print them: numbers as %g does, flags true/false, enums by name,
/// an empty optional as "none".
template <typename T>
std::string ValueText(const T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    return v ? "true" : "false";
  } else if constexpr (std::is_enum_v<T>) {
    return ToString(v);
  } else if constexpr (field_table_detail::IsOptional<T>::value) {
    return v ? ValueText(*v) : std::string("none");
  } else if constexpr (std::is_same_v<T, std::string>) {
    return "\"" + v + "\"";
  } else if constexpr (kIsFixedVector<T>) {
    std::string t = "[";
    for (int i = 0; i < v.size(); ++i) t += (i ? ", " : "") + ValueText(v[i]);
    return t + "]";
  } else {
    std::ostringstream s;
    s << v;
    std::string t = s.str();  // 1e+09 -> 1e9, 1e-08 -> 1e-8
    const size_t e = t.find('e');
    if (e == std::string::npos) return t;
    size_t digits = e + 1;
    std::string exponent = t[digits] == '-' ? "-" : "";
    if (t[digits] == '-' || t[digits] == '+') ++digits;
    while (digits + 1 < t.size() && t[digits] == '0') ++digits;
    return t.substr(0, e + 1) + exponent + t.substr(digits);
  }
}

/// The kind of value a row holds, as the docs say it: number, integer, true/false, one of the
/// enum's names.
template <typename T>
std::string TypeText() {
  if constexpr (std::is_same_v<T, bool>) return "true/false";
  else if constexpr (std::is_enum_v<T>) return "name: " + AllNames(T());
  else if constexpr (field_table_detail::IsOptional<T>::value)
    return TypeText<typename T::value_type>() + ", or none";
  else if constexpr (std::is_same_v<T, std::string>) return "text";
  else if constexpr (kIsFixedVector<T>) return std::to_string(T::RowsAtCompileTime) + " numbers";
  else if constexpr (std::is_integral_v<T>) return "integer";
  else return "number";
}

/// The table as a markdown table: name, type, unit, default, rule, description.
template <typename Table>
std::string FieldsMarkdown(const Table& table) {
  std::string md = "| name | type | unit | default | rule | description |\n"
                   "|---|---|---|---|---|---|\n";
  ForEachField(table, [&](const auto& f) {
    if constexpr (kIsNested<decltype(f)>) {
      md += std::string("| `") + f.name + "` | " + f.typeName + " | | its table | | " + f.doc +
            " |\n";
    } else {
      using T = typename std::decay_t<decltype(f)>::ValueType;
      std::string rule = f.rule.Text();
      if (f.rule.fileMax > 0) rule += " (scene files: <= " + std::to_string(f.rule.fileMax) + ")";
      md += std::string("| `") + f.name + "` | " + TypeText<T>() + " | " + f.unit + " | " +
            ValueText(f.Default()) + " | " + rule + " | " + f.doc + " |\n";
    }
  });
  return md;
}

/// "" when the row's value is valid, else "<prefix><name>: must be <rule>, got <value>"; a nested
/// row: "<prefix><name>." followed by its struct's Validate message.
template <typename F>
std::string CheckField(const F& f, const typename F::ClassType& c, const std::string& prefix) {
  using T = typename F::ValueType;
  const T& v = f.Of(c);
  auto fail = [&](const std::string& rule, const auto& got) {
    std::ostringstream s;
    s << prefix << f.name << ": must be " << rule << ", got " << got;
    return s.str();
  };
  if constexpr (kIsNested<F>) {
    const std::string m = Validate(v);  // the nested struct's own rules, found by ADL
    if (!m.empty()) return prefix + f.name + "." + m;
  } else if constexpr (std::is_enum_v<T>) {
    if (!IsNamed(v)) return fail(OneOfText(T()), static_cast<int>(v));
  } else if constexpr (field_table_detail::IsOptional<T>::value) {
    if (v && !IsNamed(*v)) return fail(OneOfText(typename T::value_type()), static_cast<int>(*v));
  } else if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
    if (!f.rule.Holds(v)) return fail(f.rule.Text(), v);
  } else if constexpr (kIsFixedVector<T>) {
    for (int i = 0; i < v.size(); ++i)
      if (!f.rule.Holds(v[i])) return fail(f.rule.Text(), ValueText(v));
  }
  return std::string();
}

/// "" when every row is valid, else the first failing row's message (CheckField).
template <typename Table, typename Class>
std::string ValidateFields(const Table& table, const Class& c, const std::string& prefix = "") {
  std::string message;
  AnyField(table, [&](const auto& f) {
    message = CheckField(f, c, prefix);
    return !message.empty();
  });
  return message;
}

// A struct S validated by its table alone declares the table next to itself (found by
// argument-dependent lookup, as NamesOf is):
//   constexpr const auto& FieldsOf(const S&) { return kSFields; }
// A struct with rules beyond its rows (ExperimentalEvalParams) declares its own Validate instead.

/// "" when every row of the struct's table (FieldsOf) is valid, else
/// "<prefix><field>: must be <rule>, got <value>" for the first invalid row (ValidateFields).
template <typename Class, typename = decltype(FieldsOf(std::declval<const Class&>()))>
std::string Validate(const Class& c, const std::string& prefix = "") {
  return ValidateFields(FieldsOf(c), c, prefix);
}

}  // namespace superdex
