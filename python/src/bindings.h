// Shared declarations of the Python bindings (one file per group of types).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <list>
#include <string>
#include <vector>

namespace superdex {
class Scene;
}

namespace superdex::python {

namespace py = pybind11;

// One function per group of classes, called in this order by module.cpp (a class is registered
// before a signature names it).
void BindParams(py::module_& m);  // enums and parameter structs, from their tables
void BindTetMesh(py::module_& m);
void BindSoftActorDesc(py::module_& m);  // NodeConstraint, SoftActorDesc
void BindShellActorDesc(py::module_& m);  // ShellActorDesc, make_rectangle_mesh
void BindRigidShape(py::module_& m);
void BindRigidActorDesc(py::module_& m);
void BindStepReport(py::module_& m);
void BindActorContactParams(py::module_& m);  // Actor.contact_params, live
void BindActor(py::module_& m);
void BindSceneState(py::module_& m);  // SceneState
void BindArticulatedDescs(py::module_& m);  // ArticulatedLinkDesc, ArticulatedActorDesc, read_urdf
void BindSceneClass(py::module_& m);  // Scene, with contact filtering and its state
void BindArticulatedMethods(py::class_<Scene>& scene);  // Scene.add_articulated_actor
void BindShellMethods(py::class_<Scene>& scene);  // Scene.add_shell_actor
void BindSceneStateMethods(py::class_<Scene>& scene);  // get_state, set_state, clone
void BindSceneFile(py::module_& m);  // SceneFile, load_scene
void BindForwardSensitivity(py::module_& m);
void BindFitting(py::module_& m);  // FitResult, TrajectoryGradient, fit, trajectory_gradient
void BindRunSummary(py::module_& m);
void BindRunScene(py::module_& m);
void BindLoadSceneText(py::module_& m);

template <typename Call>
auto WithoutGil(Call&& call) {
  py::gil_scoped_release release;
  return call();
}

/// A docstring built at binding time, kept as long as the module (pybind11 keeps the pointers).
inline const char* Keep(std::string s) {
  static std::list<std::string> kept;
  return kept.emplace_back(std::move(s)).c_str();
}

/// Raises ValueError(message) when message is not empty.
inline void CheckValue(const std::string& message) {
  if (!message.empty()) throw py::value_error(message);
}

/// A quaternion as [x, y, z, w] (the Python API's order).
inline Eigen::Vector4d QuaternionXyzw(const Eigen::Quaterniond& q) {
  return Eigen::Vector4d(q.x(), q.y(), q.z(), q.w());
}
/// [x, y, z, w] as a unit quaternion; ValueError for a zero or non-finite one.
inline Eigen::Quaterniond QuaternionFromXyzw(const Eigen::Vector4d& q) {
  if (!(q.allFinite() && q.norm() > 0))
    throw py::value_error("orientation: must be a non-zero finite quaternion [x, y, z, w]");
  return Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized();
}

/// The property `orientation` of an actor description: a quaternion [x, y, z, w], normalized on
/// assignment (ValueError for a zero one).
template <typename Desc>
void DefOrientation(py::class_<Desc>& c, const char* doc) {
  c.def_property(
      "orientation", [](const Desc& d) { return QuaternionXyzw(d.orientation); },
      [](Desc& d, const Eigen::Vector4d& q) { d.orientation = QuaternionFromXyzw(q); }, doc);
}

/// Rows of fixed-size Eigen vectors as an (n, N) numpy array (a copy).
template <typename T, int N>
py::array_t<T> RowsToArray(const std::vector<Eigen::Matrix<T, N, 1>>& rows) {
  py::array_t<T> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(N)});
  auto A = a.template mutable_unchecked<2>();
  for (size_t i = 0; i < rows.size(); ++i)
    for (int k = 0; k < N; ++k) A(static_cast<py::ssize_t>(i), k) = rows[i][k];
  return a;
}

/// A stacked vector [x_0; x_1; …] (3n entries) as an (n, 3) numpy array (a copy).
inline py::array_t<double> StackedToArray(const Eigen::VectorXd& x) {
  const py::ssize_t n = x.size() / 3;
  py::array_t<double> a({n, py::ssize_t(3)});
  auto A = a.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) A(i, k) = x[3 * i + k];
  return a;
}

/// "<field>: must be an (n, N) array, got shape (…)".
inline std::string ShapeError(const char* field, int N, const py::array& a) {
  return std::string(field) + ": must be an (n, " + std::to_string(N) + ") array, got shape " +
         py::str(py::tuple(py::cast(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()))))
             .cast<std::string>();
}

/// An (n, N) array-like of numbers as rows; ValueError naming `field` for another shape.
template <int N>
std::vector<Eigen::Matrix<double, N, 1>> RowsFromArray(const py::handle& obj, const char* field) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a) throw py::value_error(std::string(field) + ": must be an array of numbers");
  std::vector<Eigen::Matrix<double, N, 1>> rows;
  if (a.size() == 0 && a.ndim() <= 2) return rows;
  if (a.ndim() != 2 || a.shape(1) != N)
    throw py::value_error(ShapeError(field, N, a));
  const auto A = a.template unchecked<2>();
  rows.resize(a.shape(0));
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (int k = 0; k < N; ++k) rows[i][k] = A(i, k);
  return rows;
}

/// An (n, N) array-like of integers as rows; ValueError naming `field` for another shape, for
/// non-integer entries or for values outside the range of int.
template <int N>
std::vector<Eigen::Matrix<int, N, 1>> IndexRowsFromArray(const py::handle& obj, const char* field) {
  const py::array raw = py::array::ensure(obj);
  if (!raw) throw py::value_error(std::string(field) + ": must be an array of integers");
  std::vector<Eigen::Matrix<int, N, 1>> rows;
  if (raw.size() == 0 && raw.ndim() <= 2) return rows;
  const char kind = raw.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw py::value_error(std::string(field) + ": must hold integers, got dtype " +
                          py::str(raw.dtype()).cast<std::string>());
  const auto a = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(raw);
  if (a.ndim() != 2 || a.shape(1) != N)
    throw py::value_error(ShapeError(field, N, a));
  const auto A = a.template unchecked<2>();
  rows.resize(a.shape(0));
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    for (int k = 0; k < N; ++k) {
      const long long v = A(i, k);
      if (v < -2147483647LL || v > 2147483647LL)
        throw py::value_error(std::string(field) + ": index " + std::to_string(v) +
                              " out of range");
      rows[i][k] = static_cast<int>(v);
    }
  return rows;
}

}  // namespace superdex::python
