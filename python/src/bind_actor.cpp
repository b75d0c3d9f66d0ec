// The Python Actor: rigid and soft actors' state and properties.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>

#include "actor.h"
#include "bindings.h"

namespace superdex::python {

void BindActor(py::module_& m) {
  py::class_<Actor>(m, "Actor",
                    "A handle to an actor of a Scene, rigid or soft (is_soft). Rigid-only\n"
                    "properties (rotation, orientation, angular_velocity) raise TypeError on a soft\n"
                    "actor, soft-only ones (node_positions, ...) on a rigid actor.")
      .def_property_readonly("index", [](const Actor& a) { return a.index; })
      .def_property_readonly("name", [](const Actor& a) { return a.Name(); })
      .def_property_readonly("is_soft", &Actor::IsSoft)
      .def_property_readonly(
          "mass",
          [](const Actor& a) {
            return a.IsSoft() ? a.scene->SoftModel(a.Handle()).mass
                              : a.scene->Model(a.Handle()).mass;
          },
          "[kg]")
      .def_property_readonly(
          "dynamic",
          [](const Actor& a) { return a.IsSoft() || a.scene->Model(a.Handle()).dynamic; },
          "False for a static rigid actor; soft actors are always dynamic")
      .def_property_readonly("contact_layer",
                             [](const Actor& a) { return a.scene->ContactLayer(a.Handle()); })
      .def(
          "set_contact_layer",
          [](Actor& a, const std::string& layer) {
            Error e;
            if (!a.scene->SetContactLayer(a.Handle(), layer, &e)) throw py::value_error(e.message);
          },
          py::arg("layer"), "Actor::SetContactLayer: any string.")
      .def_property(
          "contact_params",
          [](const Actor& a) { return a.scene->GetContactParams(a.Handle()); },
          [](Actor& a, const ContactParams& c) {
            Error e;
            if (!a.scene->SetContactParams(a.Handle(), c, &e)) throw py::value_error(e.message);
          },
          "the actor's ContactParams (a copy; assign a modified copy back, validated)")
      .def_property_readonly(
          "position", [](const Actor& a) { return a.scene->CenterOfMass(a.Handle()); },
          "centre of mass [m] (soft: of the lumped node masses)")
      .def_property_readonly("rotation",
                             [](const Actor& a) { return a.RigidState("rotation").R; },
                             "rotation matrix (rigid actors)")
      .def_property_readonly(
          "orientation", [](const Actor& a) { return Quaternion(a.RigidState("orientation").R); },
          "quaternion [x, y, z, w] (rigid actors)")
      .def_property_readonly(
          "velocity", [](const Actor& a) { return a.scene->CenterOfMassVelocity(a.Handle()); },
          "centre-of-mass velocity [m/s]")
      .def_property_readonly(
          "angular_velocity",
          [](const Actor& a) { return a.RigidState("angular_velocity").AngularVelocity(); },
          "world angular velocity [rad/s] (rigid actors)")
      // --- Soft actors.
      .def_property_readonly(
          "num_nodes", [](const Actor& a) { return a.Soft("num_nodes").NumNodes(); },
          "number of tet mesh nodes (soft actors)")
      .def_property_readonly(
          "node_positions", [](const Actor& a) { return StackedToArray(a.SoftState("node_positions").x); },
          "(n, 3) current node positions [m] (soft actors; a copy)")
      .def_property_readonly(
          "node_velocities",
          [](const Actor& a) { return StackedToArray(a.SoftState("node_velocities").v); },
          "(n, 3) current node velocities [m/s] (soft actors; a copy)")
      .def_property_readonly(
          "rest_positions",
          [](const Actor& a) { return RowsToArray(a.Soft("rest_positions").rest.vertices); },
          "(n, 3) reference node positions [m]: the mesh placed in the world at creation (soft "
          "actors)")
      .def_property_readonly(
          "node_masses",
          [](const Actor& a) {
            const Eigen::VectorXd& m = a.Soft("node_masses").nodeMass;
            return py::array_t<double>(static_cast<py::ssize_t>(m.size()), m.data());
          },
          "(n,) lumped node masses [kg] (soft actors)")
      .def_property_readonly(
          "faces", [](const Actor& a) { return RowsToArray(a.Soft("faces").faces); },
          "(f, 3) int boundary faces (node indices), counter-clockwise seen from outside (soft "
          "actors)")
      .def_property_readonly(
          "face_areas",
          [](const Actor& a) {
            const std::vector<double>& f = a.Soft("face_areas").faceArea;
            return py::array_t<double>(static_cast<py::ssize_t>(f.size()), f.data());
          },
          "(f,) reference areas of the boundary faces [m^2] (soft actors)")
      .def(
          "face_tractions",
          [](Actor& a) {
            a.Soft("face_tractions");
            std::vector<Eigen::Vector3d> t;
            Error e;
            if (!a.scene->SoftFaceTractions(a.Handle(), &t, &e)) throw py::value_error(e.message);
            return RowsToArray(t);
          },
          "(f, 3) contact traction on each boundary face averaged over its reference area [Pa]\n"
          "(world frame; zero out of contact), from the active penalty samples at the current\n"
          "state: sum(face_tractions() * face_areas[:, None]) is the contact force (soft actors).")
      .def_property_readonly(
          "min_det_f",
          [](const Actor& a) {
            double minDetF = INFINITY;
            ElasticEnergy(a.Soft("min_det_f"), a.SoftState("min_det_f").x, &minDetF);
            return minDetF;
          },
          "smallest det F over the tets at the current state (<= 0: an inverted tet; soft actors)")
      .def("__repr__", [](const Actor& a) {
        return "<superdex.Actor " + std::to_string(a.index) + " '" + a.Name() + "'" +
               (a.IsSoft() ? " soft" : "") + ">";
      });
}

}  // namespace superdex::python
