// Articulated actors: their descriptions, Scene.add_articulated_actor and read_urdf.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "actor.h"
#include "bindings.h"
#include "core/model/articulated_kind.h"
#include "scenes/urdf_reader.h"

namespace superdex::python {
void BindArticulatedDescs(py::module_& m) {
  py::class_<LinkShapeDesc> shape(
      m, "LinkShapeDesc",
      "A collision shape of a link: a RigidShape (sphere, box or mesh) at position /\n"
      "orientation in the link frame, with its own contact parameters, collider type,\n"
      "boundary element type and surface integral. Each becomes an actor nested under its\n"
      "articulation (name: '<articulation>/<link>', '#k' for a link's k-th shape, unless given).");
  shape
      .def(py::init([](const RigidShape& s, const Eigen::Vector3d& position, const std::string& name) {
             LinkShapeDesc d;
             d.shape = s;
             d.position = position;
             d.name = name;
             return d;
           }),
           py::arg("shape"), py::arg("position") = Eigen::Vector3d::Zero(), py::arg("name") = "")
      .def_readwrite("name", &LinkShapeDesc::name)
      .def_readwrite("shape", &LinkShapeDesc::shape)
      .def_readwrite("position", &LinkShapeDesc::position, "shape frame origin, link frame [m]");
  DefOrientation(shape, "quaternion [x, y, z, w] of the shape frame in the link frame");
  shape.def_readwrite("contact", &LinkShapeDesc::contact, "ContactParams")
      .def_readwrite("collider_type", &LinkShapeDesc::colliderType)
      .def_readwrite("boundary_element_type", &LinkShapeDesc::boundaryElementType)
      .def_readwrite("surface_integral", &LinkShapeDesc::surfaceIntegral)
      .def_readwrite("grid_sdf", &LinkShapeDesc::gridSdf, "GridSdfParams for an Sdf collider");

  py::class_<ArticulatedLinkDesc> link(
      m, "ArticulatedLinkDesc",
      "One link of an articulated actor: its joint to its parent (parent -1: the world) and its\n"
      "mass properties. The joint frame is origin_position / origin_orientation in the\n"
      "parent's frame; the link's frame is the joint frame moved by the joint. Units: m, kg,\n"
      "kg m^2, rad. Validated by Scene.add_articulated_actor (docs/articulated.md).");
  link.def(py::init([](const std::string& name, JointType type, int parent, double mass,
                       const Eigen::Vector3d& com, const Eigen::Matrix3d& inertia,
                       const Eigen::Vector3d& axis) {
             ArticulatedLinkDesc d;
             d.name = name;
             d.joint.type = type;
             d.joint.parent = parent;
             d.joint.axis = axis;
             d.mass = mass;
             d.centerOfMass = com;
             d.inertia = inertia;
             return d;
           }),
           py::arg("name"), py::arg("joint_type") = JointType::Revolute, py::arg("parent") = -1,
           py::arg("mass") = 1.0, py::arg("center_of_mass") = Eigen::Vector3d::Zero(),
           py::arg("inertia") = Eigen::Matrix3d::Identity(),
           py::arg("axis") = Eigen::Vector3d::UnitZ())
      .def_readwrite("name", &ArticulatedLinkDesc::name)
      .def_property(
          "joint_type", [](const ArticulatedLinkDesc& d) { return d.joint.type; },
          [](ArticulatedLinkDesc& d, JointType t) { d.joint.type = t; })
      .def_property(
          "parent", [](const ArticulatedLinkDesc& d) { return d.joint.parent; },
          [](ArticulatedLinkDesc& d, int p) { d.joint.parent = p; },
          "index of an earlier link, -1: the world")
      .def_property(
          "axis", [](const ArticulatedLinkDesc& d) { return d.joint.axis; },
          [](ArticulatedLinkDesc& d, const Eigen::Vector3d& a) { d.joint.axis = a; },
          "unit joint axis in the joint frame (Revolute, Prismatic)")
      .def_property(
          "origin_position", [](const ArticulatedLinkDesc& d) { return d.joint.origin.p; },
          [](ArticulatedLinkDesc& d, const Eigen::Vector3d& p) { d.joint.origin.p = p; },
          "joint frame origin in the parent's frame [m]")
      .def_property(
          "origin_orientation", [](const ArticulatedLinkDesc& d) { return Quaternion(d.joint.origin.R); },
          [](ArticulatedLinkDesc& d, const Eigen::Vector4d& q) {
            if (!(q.allFinite() && q.norm() > 0))
              throw py::value_error("origin_orientation: must be a finite non-zero quaternion");
            d.joint.origin.R = QuaternionFromXyzw(q).normalized().toRotationMatrix();
          },
          "joint frame orientation in the parent's frame, quaternion [x, y, z, w]")
      .def_readwrite("mass", &ArticulatedLinkDesc::mass, "[kg]")
      .def_readwrite("center_of_mass", &ArticulatedLinkDesc::centerOfMass, "link frame [m]")
      .def_readwrite("inertia", &ArticulatedLinkDesc::inertia,
                     "3 x 3 inertia tensor about the centre of mass, link frame [kg m^2]")
      .def_readwrite("joint_params", &ArticulatedLinkDesc::jointParams, "JointParams")
      .def_readwrite("shapes", &ArticulatedLinkDesc::shapes,
                     "list of LinkShapeDesc (a copy; assign the whole list): the link's collision "
                     "shapes");

  py::class_<ArticulatedActorDesc>(
      m, "ArticulatedActorDesc",
      "An articulated actor: its links, parents first, and its initial joint coordinates and\n"
      "velocities in the tree's layout (empty: zero).")
      .def(py::init([](const std::string& name, const std::vector<ArticulatedLinkDesc>& links) {
             ArticulatedActorDesc d;
             d.name = name;
             d.links = links;
             return d;
           }),
           py::arg("name"), py::arg("links") = std::vector<ArticulatedLinkDesc>())
      .def_readwrite("name", &ArticulatedActorDesc::name)
      .def_readwrite("links", &ArticulatedActorDesc::links, "list of ArticulatedLinkDesc (a copy)")
      .def_readwrite("joint_positions", &ArticulatedActorDesc::jointPositions)
      .def_readwrite("joint_velocities", &ArticulatedActorDesc::jointVelocities);

  m.def(
      "read_urdf",
      [](const std::string& path, const std::string& base, const Eigen::Vector3d& position,
         const Eigen::Vector4d& orientation, const std::map<std::string, double>& positions,
         const std::map<std::string, double>& velocities,
         const std::map<std::string, JointParams>& params, bool collisions,
         const ContactParams& contact, double sampleSpacing) {
        if (base != "fixed" && base != "free")
          throw py::value_error("base: must be \"fixed\" or \"free\", got \"" + base + "\"");
        if (!(orientation.allFinite() && orientation.norm() > 0))
          throw py::value_error("orientation: must be a finite non-zero quaternion");
        UrdfPlacement placement;
        placement.freeBase = base == "free";
        placement.base.p = position;
        placement.base.R = QuaternionFromXyzw(orientation).normalized().toRotationMatrix();
        placement.jointPositions = positions;
        placement.jointVelocities = velocities;
        placement.jointParams = params;
        placement.collisions = collisions;
        placement.contact = contact;
        if (!(std::isfinite(sampleSpacing) && sampleSpacing > 0))
          throw py::value_error("sample_spacing: must be > 0");
        placement.sampleSpacing = sampleSpacing;
        ArticulatedActorDesc d;
        Error e;
        if (!ReadUrdfFile(path, placement, &d, &e)) throw py::value_error(e.message);
        return d;
      },
      py::arg("path"), py::arg("base") = "fixed", py::arg("position") = Eigen::Vector3d::Zero(),
      py::arg("orientation") = Eigen::Vector4d(0, 0, 0, 1),
      py::arg("joint_positions") = std::map<std::string, double>(),
      py::arg("joint_velocities") = std::map<std::string, double>(),
      py::arg("joint_params") = std::map<std::string, JointParams>(),
      py::arg("collisions") = true, py::arg("contact") = ContactParams(),
      py::arg("sample_spacing") = 0.01,
      "A URDF robot as an ArticulatedActorDesc (docs/articulated.md, 'URDF'): its root fixed\n"
      "or free at position / orientation [x, y, z, w]; initial values and JointParams by URDF\n"
      "joint name; its <collision> geometry as the links' shapes (collisions=False: none), all\n"
      "with `contact`, boxes and cylinders sampled at most sample_spacing [m] apart. Raises\n"
      "ValueError naming the file, the element and the problem.");
}

void BindArticulatedMethods(py::class_<Scene>& scene) {
  scene.def(
      "add_articulated_actor",
      [](Scene& s, const ArticulatedActorDesc& d, const std::string& layer,
         std::optional<Actor> parent) {
        Error e;
        const ActorHandle h =
            s.AddArticulatedActor(d, &e, layer, parent ? parent->Handle() : ActorHandle());
        if (!h.IsValid()) throw py::value_error(e.message);
        return Actor{&s, h.index};
      },
      py::arg("desc"), py::arg("contact_layer") = "default", py::arg("parent") = py::none(),
      py::keep_alive<0, 1>(),
      "Adds an articulated actor and, nested under it, an actor per link shape (contact between\n"
      "adjacent links' shapes disabled; scene.enable_actor_contact_symmetric overrides it);\n"
      "raises ValueError naming the link, the field and the rule.");
}

}  // namespace superdex::python
