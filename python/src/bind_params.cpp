// Enums and parameter types of the spec, with snake_case properties that validate on assignment.
// Both come from the C++ tables (optim/field_table.h): an enum's names, a struct's fields.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <string>

#include "actor.h"
#include "bindings.h"
#include "core/dynamics/scene_settings.h"
#include "core/model/collider_params.h"
#include "core/model/contact_params.h"
#include "core/model/enums.h"
#include "core/model/eval_params.h"
#include "core/model/joint_params.h"
#include "core/model/kinematic_tree.h"
#include "core/model/shell_body.h"
#include "core/model/soft_body.h"
#include "energies/contact_dissipation.h"
#include "optim/newton_solver.h"

namespace superdex::python {
namespace {

// The enums bound as Python enums. A field of another enum type (linear_solver, line_search,
// psd_projection, stage_solver) is a property holding the value's name as a string.
template <typename E>
constexpr bool kPythonEnum = false;
template <>
constexpr bool kPythonEnum<ColliderType> = true;
template <>
constexpr bool kPythonEnum<ActorBoundaryElementType> = true;
template <>
constexpr bool kPythonEnum<IntegrationMethod> = true;
template <>
constexpr bool kPythonEnum<IncludeNestedActors> = true;
template <>
constexpr bool kPythonEnum<GridSdfResolutionMode> = true;
template <>
constexpr bool kPythonEnum<SurfaceIntegral> = true;
template <>
constexpr bool kPythonEnum<JointType> = true;
template <>
constexpr bool kPythonEnum<ShellBendingModel> = true;

template <typename E>
void BindEnum(py::module_& m, const char* name, const char* doc) {
  static_assert(kPythonEnum<E>);
  py::enum_<E> e(m, name, doc);
  for (const EnumName<E>& n : NamesOf(E())) e.value(n.name, n.value, *n.doc ? n.doc : nullptr);
}

template <typename T>
std::string PythonValueText(const T& v) {
  if constexpr (std::is_same_v<T, bool>) return v ? "True" : "False";
  else if constexpr (std::is_same_v<T, std::optional<ActorBoundaryElementType>>)
    return v ? ValueText(*v) : "None";
  else if constexpr (std::is_class_v<T> && !kIsFixedVector<T>)  // a nested row's struct
    return std::string(py::repr(py::cast(v)));
  else return ValueText(v);
}

// "<doc> [<unit>], <rule>. Default <value>."; a nested row: "<doc> (<TypeName>)."
template <typename F>
const char* DocOf(const F& f) {
  std::string d = f.doc;
  if constexpr (kIsNested<F>) return Keep(d + " (" + f.typeName + ").");
  else {
    if (*f.unit) d += std::string(" [") + f.unit + "]";
    if (const std::string rule = f.rule.Text(); !rule.empty()) d += ", " + rule;
    return Keep(d + ". Default " + PythonValueText(f.Default()) + ".");
  }
}

// The Python name of a row's value type, for messages.
template <typename T>
std::string PythonTypeName() {
  if constexpr (kIsFixedVector<T>)
    return "a sequence of " + std::to_string(T::RowsAtCompileTime) + " numbers";
  else if constexpr (std::is_class_v<T> && !std::is_same_v<T, std::string> &&
                     !field_table_detail::IsOptional<T>::value)  // a nested row's bound struct
    return "a " + std::string(py::str(py::type::of<T>().attr("__name__")));
  else return py::type_id<T>();
}

// The value a Python object gives the field: names for enums bound as strings.
template <typename F>
auto FromPython(const F& f, const py::handle& value) {
  using T = typename F::ValueType;
  if constexpr (std::is_enum_v<T> && !kPythonEnum<T>) {
    const std::string name = value.cast<std::string>();
    T v;
    if (!ParseName(name, &v))
      throw py::value_error(std::string(f.name) + ": unknown value \"" + name +
                            "\" (expected one of: " + AllNames(T()) + ")");
    return v;
  } else {
    try {
      return value.cast<T>();
    } catch (const py::cast_error&) {
      throw py::type_error(std::string(f.name) + ": must be " + PythonTypeName<T>() + ", got " +
                           py::str(py::type::of(value).attr("__name__")).cast<std::string>());
    }
  }
}

// A row's value as a Python object: a name for enums bound as strings, a read-only array for a
// vector (as a struct member's array was).
template <typename F>
py::object ToPython(const F& f, const typename F::ClassType& p) {
  using T = typename F::ValueType;
  if constexpr (std::is_enum_v<T> && !kPythonEnum<T>) {
    return py::str(ToString(f.Of(p)));
  } else if constexpr (kIsFixedVector<T>) {
    py::array a = py::cast(f.Of(p));
    a.attr("setflags")(py::arg("write") = false);
    return std::move(a);
  } else {
    return py::cast(f.Of(p));
  }
}

// Per row a property that validates the whole object after the assignment and rolls back on
// failure (a nested row's property gives the struct itself, so that `settings.solver.x = v`
// changes the settings); a constructor taking the fields positionally (in table order) or by
// name; a repr.
template <typename Class, typename Table>
void BindFields(py::class_<Class>& c, const Table& table) {
  ForEachField(table, [&](const auto& f) {
    auto set = [f](Class& p, const py::object& value) {
      Class q = p;
      f.Of(q) = FromPython(f, value);
      CheckValue(Validate(q));
      p = q;
    };
    using Row = std::decay_t<decltype(f)>;
    if constexpr (kIsNested<Row>) {
      c.def_property(
          f.name,
          py::cpp_function([f](Class& p) -> typename Row::ValueType& { return f.Of(p); },
                           py::return_value_policy::reference_internal),
          set, DocOf(f));
    } else {
      c.def_property(
          f.name, [f](const Class& p) { return ToPython(f, p); }, set, DocOf(f));
    }
  });
  const char* className = Keep(py::str(c.attr("__name__")).cast<std::string>());
  c.def(py::init([table, className](const py::args& args, const py::kwargs& kwargs) {
    Class p;
    size_t position = 0, named = 0;
    ForEachField(table, [&](const auto& f) {
      const bool byName = kwargs.contains(f.name);
      if (position < args.size() && byName)
        throw py::type_error(std::string(className) + "() got multiple values for '" + f.name +
                             "'");
      if (position < args.size()) f.Of(p) = FromPython(f, args[position]);
      if (byName) f.Of(p) = FromPython(f, kwargs[f.name]), ++named;
      ++position;
    });
    if (args.size() > position)
      throw py::type_error(std::string(className) + "() takes at most " +
                           std::to_string(position) + " positional arguments");
    if (named != kwargs.size()) {
      for (const auto& item : kwargs) {
        const std::string key = py::str(item.first);
        bool known = false;
        ForEachField(table, [&](const auto& f) { known |= key == f.name; });
        if (!known)
          throw py::type_error(std::string(className) + "() got an unexpected keyword argument '" +
                               key + "'");
      }
    }
    CheckValue(Validate(p));
    return p;
  }));
  c.def("__repr__", [table, className](const Class& p) {
    std::string s = std::string(className) + "(";
    bool first = true;
    ForEachField(table, [&](const auto& f) {
      s += (first ? "" : ", ") + std::string(f.name) + "=" + PythonValueText(f.Of(p));
      first = false;
    });
    return s + ")";
  });
}

// An actor's ContactParams, live: a property reads the actor's parameters now, an assignment
// changes them (Scene::SetContactParams validates; ValueError naming the field).
struct ActorContactParams {
  Actor actor;
  const ContactParams& Get() const { return actor.scene->GetContactParams(actor.Handle()); }
  void Set(const ContactParams& p) {
    Error e;
    if (!actor.scene->SetContactParams(actor.Handle(), p, &e)) throw py::value_error(e.message);
  }
};

template <typename Class, typename Table>
py::class_<Class> BindParamsClass(py::module_& m, const char* name, const char* doc,
                                  const Table& table) {
  py::class_<Class> c(m, name, doc);
  BindFields(c, table);
  return c;
}

}  // namespace

void BindActorContactParams(py::module_& m) {
  py::class_<ActorContactParams> c(
      m, "ActorContactParams",
      "An actor's contact parameters, live (Actor.contact_params): reading a property gives the\n"
      "actor's value now; assigning one changes the actor's, validated. copy() gives a\n"
      "ContactParams to keep or to give another actor.");
  ForEachField(kContactParamsFields, [&](const auto& f) {
    static_assert(!kIsNested<std::decay_t<decltype(f)>>);
    c.def_property(
        f.name, [f](const ActorContactParams& v) { return ToPython(f, v.Get()); },
        [f](ActorContactParams& v, const py::object& value) {
          ContactParams q = v.Get();
          f.Of(q) = FromPython(f, value);
          v.Set(q);
        },
        DocOf(f));
  });
  c.def("copy", [](const ActorContactParams& v) { return v.Get(); }, "A ContactParams copy.");
  c.def("__repr__", [](const ActorContactParams& v) {
    return "<" + v.actor.Name() + ".contact_params: " + std::string(py::repr(py::cast(v.Get()))) +
           ">";
  });
}

void SetActorContactParams(Actor& a, const py::object& value) {
  ActorContactParams live{a};
  if (py::isinstance<ActorContactParams>(value))
    return live.Set(value.cast<const ActorContactParams&>().Get());
  live.Set(value.cast<ContactParams>());
}

py::object ActorContactParamsOf(const Actor& a) { return py::cast(ActorContactParams{a}); }

void BindParams(py::module_& m) {
  BindEnum<ColliderType>(m, "ColliderType",
                         "How an actor supplies its distance field (spec: Collider "
                         "Representations). PointCloud is a shell's (its default, Auto); soft "
                         "actors accept None, Sdf and Auto. `None` is a Python keyword: write "
                         "getattr(ColliderType, 'None').");
  BindEnum<ActorBoundaryElementType>(m, "ActorBoundaryElementType",
                                     "Surface quadrature rule per boundary triangle.");
  BindEnum<IntegrationMethod>(m, "IntegrationMethod",
                              "Time integrators; every stage is an incremental-potential stage.");
  BindEnum<IncludeNestedActors>(m, "IncludeNestedActors",
                                "Whether actor-pair filtering also applies to nested actors.");
  BindEnum<GridSdfResolutionMode>(m, "GridSdfResolutionMode",
                                  "Reference length that sizes a grid SDF's voxels.");
  BindEnum<SurfaceIntegral>(m, "SurfaceIntegral",
                            "How a rigid actor integrates its normal penalty over its surface "
                            "(superdex's option, not a spec parameter).");

  const char* validated = " Every assignment is validated; a bad value raises ValueError naming "
                          "the field and the rule.";
  BindParamsClass<ContactParams>(
      m, "ContactParams",
      Keep(std::string("Contact response of one actor (spec: ContactParams).") + validated),
      kContactParamsFields);
  BindParamsClass<ExperimentalEvalParams>(
      m, "ExperimentalEvalParams",
      "Time levels of the dissipative terms (spec: Stage-Discrete Dissipation).\n"
      "explicit_normals=True: stage-start normals and load; the dissipation is an exact\n"
      "potential (stages are minimizations). False (default): current geometry with the\n"
      "stage-start load reconstructed; not a potential (residual solve). The combination\n"
      "(explicit_normals=True, implicit_normal_force_for_dissipation=True) is refused.",
      kExperimentalEvalFields);
  BindParamsClass<GridSdfParams>(m, "GridSdfParams",
                                 "Grid SDF construction for Sdf colliders (RigidActorDesc.grid_sdf, "
                                 "SoftActorDesc.grid_sdf).",
                                 kGridSdfFields);
  BindEnum<JointType>(m, "JointType", "Joint types of an articulated actor's links");
  BindEnum<ShellBendingModel>(m, "ShellBendingModel",
                              "A shell's bending model: Midedge (Kirchhoff-Love) or Hinge (cloth)");
  auto joint = BindParamsClass<JointParams>(
      m, "JointParams",
      Keep(std::string("Limits, damping and a PD drive of a Revolute or Prismatic joint "
                       "(ArticulatedLinkDesc.joint_params; units rad or m, N·m or N). Limits "
                       "default to -inf and inf (none), the force limit to inf.") + validated),
      kJointParamsFields);
  joint
      .def_readwrite("drive_target_position", &JointParams::driveTargetPosition,
                     "the drive's target x*(t): keyframes [(t [s], x), ...], piecewise linear; "
                     "empty: 0")
      .def_readwrite("drive_target_velocity", &JointParams::driveTargetVelocity,
                     "its target velocity v*(t): keyframes [(t, v), ...]; empty: the target "
                     "position path's slope");
  BindParamsClass<SoftMaterial>(
      m, "SoftMaterial",
      Keep(std::string("Bulk material of a soft actor (stable neo-Hookean).") + validated),
      kSoftMaterialFields);
  BindParamsClass<ShellMaterial>(
      m, "ShellMaterial",
      Keep(std::string("Material of a shell actor: membrane E h, plate E h^3 / (12 (1 - nu^2)).") +
           validated),
      kShellMaterialFields);
  BindParamsClass<PointCloudColliderParams>(
      m, "PointCloudColliderParams",
      "Point-cloud collider parameters (a shell's collider: ShellActorDesc.point_cloud).",
      kPointCloudColliderFields);
  BindParamsClass<NonlinearSolverParams>(
      m, "NonlinearSolverParams",
      Keep(std::string("Stage solver settings (scene files: settings.solver).") + validated),
      kNonlinearSolverFields);
  BindParamsClass<SceneSettings>(
      m, "SceneSettings",
      Keep(std::string("Scene-wide settings (scene files: settings).") + validated),
      kSceneSettingsFields);

  m.def("hunt_crossley_damping_from_restitution", &HuntCrossleyDampingFromRestitution,
        py::arg("e"), py::arg("v"),
        "Rational Hunt-Crossley approximation c_n = (1 - e)(1 + 9e/2) / (e v (1 + 8e/3)) [s/m]\n"
        "for a coefficient of restitution e in (0, 1] at impact speed v > 0 [m/s]; NaN outside.");
  m.def("hunt_crossley_restitution_from_damping", &HuntCrossleyRestitutionFromDamping,
        py::arg("cn"), py::arg("v"),
        "Closed-form inverse: e = 2 / (B + sqrt(B^2 + 4A)), A = 8a/3 + 9/2, B = a - 7/2, a = cn v.");
}

}  // namespace superdex::python
