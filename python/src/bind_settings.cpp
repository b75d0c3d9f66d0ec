// Rigid shapes and descriptions, and step reports (SceneSettings: bind_params.cpp, from its table).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>

#include "bindings.h"
#include "core/scene.h"
#include "geometry/mesh_io.h"
#include "geometry/triangle_mesh.h"

namespace superdex::python {
namespace {

// A shape of the kind with RigidShape's defaults (the surface resolution too, unless given).
RigidShape MakeShape(RigidShapeKind kind, std::optional<int> surfaceResolution = std::nullopt) {
  RigidShape s;
  s.kind = kind;
  if (surfaceResolution) s.surfaceResolution = *surfaceResolution;
  return s;
}

// An analytic shape checked by the rules an actor's shape meets when it is added (ValueError
// naming the field, e.g. "shape.radius: must be > 0, got -1").
RigidShape Checked(const RigidShape& shape) {
  RigidActorDesc d;
  d.shape = shape;
  d.dynamic = false;  // the shape's own rules only (no density, planes allowed)
  RigidBodyModel model;
  RigidBodyState state;
  Error e;
  if (!BuildRigidBody(d, "", &model, &state, &e)) throw py::value_error(e.message);
  return shape;
}

}  // namespace

void BindRigidShape(py::module_& m) {
  py::class_<RigidShape>(m, "RigidShape",
                         "Geometry of a rigid actor in its own frame; make one with sphere(), "
                         "box(), plane() or mesh().")
      .def_static(
          "sphere",
          [](double radius, int resolution) {
            RigidShape s = MakeShape(RigidShapeKind::Sphere, resolution);
            s.radius = radius;
            return Checked(s);
          },
          py::arg("radius"), py::arg("surface_resolution") = 3,
          "A sphere of the given radius [m]; surface_resolution icosphere subdivisions (0-7).")
      .def_static(
          "box",
          [](const Eigen::Vector3d& size, int resolution) {
            RigidShape box = MakeShape(RigidShapeKind::Box, resolution);
            box.halfExtents = 0.5 * size;
            return Checked(box);
          },
          py::arg("size"), py::arg("surface_resolution") = 2,
          "A box of edge lengths size = [x, y, z] [m]; surface_resolution cells per edge.")
      .def_static(
          "capsule",
          [](double radius, double length, int resolution) {
            RigidShape s = MakeShape(RigidShapeKind::Capsule, resolution);
            s.radius = radius;
            s.halfLength = 0.5 * length;
            return Checked(s);
          },
          py::arg("radius"), py::arg("length"), py::arg("surface_resolution") = 8,
          "A capsule along z: radius [m] about a straight part of the given length [m] (its total "
          "length is length + 2 radius); surface_resolution latitude rings per end cap (1-32).")
      .def_static(
          "plane",
          [](const Eigen::Vector3d& normal) {
            RigidShape s = MakeShape(RigidShapeKind::Plane);
            s.planeNormal = normal;
            return Checked(s);
          },
          py::arg("normal") = Eigen::Vector3d::UnitZ(),
          "The half space below the plane through the actor's position (static actors only).")
      .def_static(
          "mesh",
          [](const std::string& path, double scale) {
            if (!(std::isfinite(scale) && scale > 0))
              throw py::value_error("scale: must be > 0, got " + std::to_string(scale));
            auto mesh = std::make_shared<TriangleMesh>();
            std::string error;
            if (!ReadMeshFile(path, mesh.get(), &error)) throw py::value_error(error);
            for (auto& x : mesh->vertices) x *= scale;
            RigidShape s = MakeShape(RigidShapeKind::Mesh);
            s.mesh = mesh;
            s.meshSource = path;
            return s;
          },
          py::arg("path"), py::arg("scale") = 1.0, "A closed triangle mesh read from an OBJ, OFF, STL or PLY file.")
      .def_property_readonly("kind", [](const RigidShape& s) { return std::string(ToString(s.kind)); });
}

void BindRigidActorDesc(py::module_& m) {
  py::class_<RigidActorDesc> desc(m, "RigidActorDesc",
                                  "What a rigid actor is made from. Units: kg, m, m/s, rad/s.");
  desc.def(py::init([](const std::string& name, const RigidShape& shape, bool dynamic,
                       bool kinematic) {
             RigidActorDesc d;
             d.name = name;
             d.shape = shape;
             d.dynamic = dynamic && !kinematic;
             d.kinematic = kinematic;
             return d;
           }),
           py::arg("name"), py::arg("shape"), py::arg("dynamic") = true,
           py::arg("kinematic") = false,
           "kinematic=True makes a kinematic actor (not dynamic): it follows `path`, or moves at "
           "constant velocity and angular_velocity, and collides as a dynamic actor does without "
           "reacting.")
      .def_readwrite("name", &RigidActorDesc::name)
      .def_readwrite("dynamic", &RigidActorDesc::dynamic)
      .def_property(
          "kinematic", [](const RigidActorDesc& d) { return d.kinematic; },
          [](RigidActorDesc& d, bool k) {
            d.kinematic = k;
            if (k) d.dynamic = false;
          },
          "a prescribed motion (setting it True sets dynamic False)")
      .def_property(
          "path",
          [](const RigidActorDesc& d) {
            py::list out;
            for (const PoseKeyframe& k : d.path)
              out.append(py::make_tuple(k.t, k.position, QuaternionXyzw(k.orientation)));
            return out;
          },
          [](RigidActorDesc& d, const py::iterable& keys) {
            d.path.clear();
            for (const py::handle& item : keys) {
              const py::tuple k = py::cast<py::tuple>(item);
              if (k.size() != 2 && k.size() != 3)
                throw py::value_error("path: each keyframe is (t, position) or (t, position, "
                                      "orientation [x, y, z, w])");
              PoseKeyframe f;
              f.t = py::cast<double>(k[0]);
              f.position = py::cast<Eigen::Vector3d>(k[1]);
              f.orientation = k.size() == 3 ? QuaternionFromXyzw(py::cast<Eigen::Vector4d>(k[2]))
                                            : d.orientation;
              d.path.push_back(f);
            }
          },
          "kinematic: keyframes (t [s], position [m], orientation [x, y, z, w]) of the shape "
          "frame; a keyframe without an orientation takes the actor's")
      .def_readwrite("applied_force", &RigidActorDesc::appliedForce,
                     "dynamic: force at the centre of mass [N], world frame, as keyframes "
                     "[(t, [fx, fy, fz]), ...] (piecewise linear; one keyframe: constant)")
      .def_readwrite("applied_torque", &RigidActorDesc::appliedTorque,
                     "dynamic: torque [N m], world frame, as keyframes [(t, [tx, ty, tz]), ...]")
      .def_readwrite("shape", &RigidActorDesc::shape)
      .def_readwrite("density", &RigidActorDesc::density, "[kg/m^3], used without mass")
      .def_readwrite("mass", &RigidActorDesc::mass, "[kg] or None (then from density)")
      .def_readwrite("position", &RigidActorDesc::position, "shape frame origin [m]");
  DefOrientation(desc, "quaternion [x, y, z, w]");
  desc.def_readwrite("velocity", &RigidActorDesc::linearVelocity, "of the centre of mass [m/s]")
      .def_readwrite("angular_velocity", &RigidActorDesc::angularVelocity, "world frame [rad/s]")
      .def_readwrite("contact", &RigidActorDesc::contact, "ContactParams")
      .def_readwrite("collider_type", &RigidActorDesc::colliderType)
      .def_readwrite("boundary_element_type", &RigidActorDesc::boundaryElementType)
      .def_readwrite("surface_integral", &RigidActorDesc::surfaceIntegral,
                     "SurfaceIntegral: ExactSphere integrates a sphere's penalty exactly against "
                     "plane, box-face and sphere fields, its dissipation on its contact cap")
      .def_readwrite("contact_layer", &RigidActorDesc::contactLayer)
      .def_readwrite("grid_sdf", &RigidActorDesc::gridSdf, "GridSdfParams for an Sdf collider");
}

void BindStepReport(py::module_& m) {
  py::class_<StepReport>(m, "StepReport", "What one step did.")
      .def_readonly("time", &StepReport::time)
      .def_readonly("dt", &StepReport::dt)
      .def_readonly("stages", &StepReport::stages)
      .def_readonly("newton_iterations", &StepReport::newtonIterations)
      .def_readonly("free_stages", &StepReport::freeStages,
                    "Stages solved in closed form (no active contact sample).")
      .def_property_readonly("status", [](const StepReport& r) { return ToString(r.status); })
      .def_readonly("message", &StepReport::message)
      .def_property_readonly("active_samples", [](const StepReport& r) { return r.contact.activeSamples; })
      .def_property_readonly("min_signed_distance",
                             [](const StepReport& r) { return r.contact.minSignedDistance; })
      .def_readonly("max_coulomb_ratio", &StepReport::maxCoulombRatio)
      .def_readonly("min_det_f", &StepReport::minDetF,
                    "smallest det F over the soft tets at the end of the step (<= 0: an inverted "
                    "tet); inf without soft actors")
      .def_readonly("wall_seconds", &StepReport::wallSeconds);
}

}  // namespace superdex::python
