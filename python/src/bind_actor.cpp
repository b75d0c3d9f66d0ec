// The Python Actor: rigid and soft actors' state and properties.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>

#include "actor.h"
#include "bindings.h"
#include "core/model/rigid_math.h"

namespace superdex::python {
namespace {

/// A 3-vector value of `field`; ValueError unless finite.
Eigen::Vector3d Finite3(const Eigen::Vector3d& v, const char* field) {
  if (!v.allFinite()) throw py::value_error(std::string(field) + ": must be finite");
  return v;
}

/// Changes a rigid actor's state through Scene::SetState (the integrator's history restarts);
/// ValueError naming `field` for a static actor or a refused state.
template <typename Edit>
void EditRigid(Actor& a, const char* field, Edit&& edit) {
  if (a.scene->IsAttached(a.Handle()))
    throw py::value_error(std::string(field) + ": '" + a.Name() +
                          "' is a link's shape: it follows its articulation's joints");
  RigidBodyState s = a.RigidState(field);
  if (a.scene->Model(a.Handle()).kinematic)
    throw py::value_error(std::string(field) + ": '" + a.Name() +
                          "' is a kinematic actor: its motion is prescribed (path or velocity)");
  if (!a.scene->Model(a.Handle()).dynamic)
    throw py::value_error(std::string(field) + ": '" + a.Name() +
                          "' is a static actor, held where it was created");
  edit(&s);
  Error e;
  if (!a.scene->SetState(a.Handle(), s, &e))
    throw py::value_error(std::string(field) + ": " + e.message);
}

/// Changes a soft actor's node positions or velocities (3 per node) through
/// Scene::SetSoftState.
template <typename Edit>
void EditSoft(Actor& a, const char* field, Edit&& edit) {
  SoftBodyState s = a.SoftState(field);
  edit(&s);
  Error e;
  if (!a.scene->SetSoftState(a.Handle(), s, &e))
    throw py::value_error(std::string(field) + ": " + e.message);
}

/// Shifts every node's entry of a stacked vector by d.
void Shift(const Eigen::Vector3d& d, Eigen::VectorXd* x) {
  for (Eigen::Index i = 0; i + 2 < x->size(); i += 3) x->segment<3>(i) += d;
}

/// Moves the centre of mass to `value` (velocity = false) or gives it the velocity `value`: a
/// rigid actor's p or v; a soft actor's nodes all shifted by the same amount.
void SetCentre(Actor& a, const char* field, const Eigen::Vector3d& value, bool velocity) {
  const Eigen::Vector3d to = Finite3(value, field);
  if (a.IsKind())
    throw py::type_error(std::string(field) + ": '" + a.Name() + "' is an " +
                         a.scene->Kind(a.Handle()).KindName() + " actor; set joint_positions " +
                         "and joint_velocities");
  if (!a.IsSoft())
    return EditRigid(a, field, [&](RigidBodyState* s) { (velocity ? s->v : s->p) = to; });
  const Eigen::Vector3d now = velocity ? a.scene->CenterOfMassVelocity(a.Handle())
                                       : a.scene->CenterOfMass(a.Handle());
  EditSoft(a, field, [&](SoftBodyState* s) { Shift(to - now, velocity ? &s->v : &s->x); });
}

/// An (n, 3) array for the n nodes of a soft actor as a stacked vector.
Eigen::VectorXd NodeRows(const Actor& a, const py::handle& obj, const char* field) {
  const auto rows = RowsFromArray<3>(obj, field);
  const int n = a.Soft(field).NumNodes();
  if (static_cast<int>(rows.size()) != n)
    throw py::value_error(std::string(field) + ": needs " + std::to_string(n) + " rows (one per node), got " +
                          std::to_string(rows.size()));
  Eigen::VectorXd x(3 * n);
  for (int i = 0; i < n; ++i) x.segment<3>(3 * i) = Finite3(rows[i], field);
  return x;
}

// The soft actors' properties of Actor (TypeError on a rigid actor).
void DefSoftProperties(py::class_<Actor>& actor) {
  actor
      .def_property_readonly(
          "num_nodes", [](const Actor& a) { return a.Soft("num_nodes").NumNodes(); },
          "number of tet mesh nodes (soft actors)")
      .def_property(
          "node_positions", [](const Actor& a) { return StackedToArray(a.NodeState("node_positions").x); },
          [](Actor& a, const py::handle& x) {
            const Eigen::VectorXd to = NodeRows(a, x, "node_positions");
            EditSoft(a, "node_positions", [&](SoftBodyState* s) { s->x = to; });
          },
          "(n, 3) current node positions [m] (soft and shell actors; a copy; assignable for soft "
          "actors: a whole array)")
      .def_property(
          "node_velocities",
          [](const Actor& a) { return StackedToArray(a.NodeState("node_velocities").v); },
          [](Actor& a, const py::handle& v) {
            const Eigen::VectorXd to = NodeRows(a, v, "node_velocities");
            EditSoft(a, "node_velocities", [&](SoftBodyState* s) { s->v = to; });
          },
          "(n, 3) current node velocities [m/s] (soft actors; a copy, assign a whole array)")
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
          "(world frame; zero out of contact), from contact_samples() (normal traction and the\n"
          "last step's friction and damping): sum(face_tractions() * face_areas[:, None]) is the\n"
          "contact force (soft actors).")
      .def_property_readonly(
          "min_det_f",
          [](const Actor& a) {
            double minDetF = INFINITY;
            ElasticEnergy(a.Soft("min_det_f"), a.SoftState("min_det_f").x, &minDetF);
            return minDetF;
          },
          "smallest det F over the tets at the current state (<= 0: an inverted tet; soft actors)");
}

/// The joint coordinates and velocities of an articulated actor's state, set together.
void SetJoints(Actor& a, const char* field, const Eigen::VectorXd* qJ, const Eigen::VectorXd* u) {
  const ArticulatedKind& k = a.Articulated(field);
  const KindState& now = a.scene->KindStateOf(a.Handle());
  const Eigen::VectorXd q = qJ ? *qJ : k.JointPositions(now.x);
  const Eigen::VectorXd v = u ? *u : k.JointVelocities(now);
  const Eigen::Index want = qJ ? k.Tree().NumCoordinates() : k.NumTangentDofs();
  const Eigen::Index got = qJ ? qJ->size() : u->size();
  if (got != want || !(qJ ? *qJ : *u).allFinite())
    throw py::value_error(std::string(field) + ": must have " + std::to_string(want) +
                          " finite entries, got " + std::to_string(got));
  Error e;
  if (!a.scene->SetKindState(a.Handle(), k.StateAt(q, v), &e))
    throw py::value_error(std::string(field) + ": " + e.message);
}

// The articulated actors' properties of Actor (TypeError on another actor).
void DefArticulatedProperties(py::class_<Actor>& actor) {
  actor
      .def_property_readonly("is_articulated", [](const Actor& a) { return a.AsArticulated() != nullptr; })
      .def_property(
          "joint_positions",
          [](const Actor& a) {
            return a.Articulated("joint_positions").JointPositions(a.scene->KindStateOf(a.Handle()).x);
          },
          [](Actor& a, const Eigen::VectorXd& q) { SetJoints(a, "joint_positions", &q, nullptr); },
          "joint coordinates (articulated actors; the tree's layout: an angle [rad] or offset [m] "
          "per 1-dof joint, 9 entries of a spherical joint's rotation matrix, 12 of a free "
          "joint's position and rotation; assigning restarts the integrator's history)")
      .def_property(
          "joint_velocities",
          [](const Actor& a) {
            return a.Articulated("joint_velocities").JointVelocities(a.scene->KindStateOf(a.Handle()));
          },
          [](Actor& a, const Eigen::VectorXd& u) { SetJoints(a, "joint_velocities", nullptr, &u); },
          "one rate per joint dof [rad/s or m/s] (articulated actors)")
      .def_property_readonly(
          "drive_forces",
          [](const Actor& a) {
            return a.Articulated("drive_forces").DriveForces(a.scene->KindStateOf(a.Handle()), a.scene->Time());
          },
          "drive force or torque per joint dof at the current state [N or N·m], 0 where no drive "
          "(articulated actors)")
      .def_property_readonly(
          "link_names",
          [](const Actor& a) {
            const ArticulatedKind& k = a.Articulated("link_names");
            std::vector<std::string> names;
            for (int l = 0; l < k.NumLinks(); ++l) names.push_back(k.LinkName(l));
            return names;
          })
      .def_property_readonly(
          "link_positions",
          [](const Actor& a) {
            const ArticulatedKind& k = a.Articulated("link_positions");
            std::vector<Eigen::Vector3d> p;
            for (const RigidPose& pose : k.LinkPoses(a.scene->KindStateOf(a.Handle()).x))
              p.push_back(pose.p);
            return RowsToArray(p);
          },
          "(L, 3) each link frame's origin [m] (articulated actors)")
      .def_property_readonly(
          "link_orientations",
          [](const Actor& a) {
            const ArticulatedKind& k = a.Articulated("link_orientations");
            std::vector<Eigen::Vector4d> q;
            for (const RigidPose& pose : k.LinkPoses(a.scene->KindStateOf(a.Handle()).x))
              q.push_back(Quaternion(pose.R));
            return RowsToArray(q);
          },
          "(L, 4) each link frame's quaternion [x, y, z, w] (articulated actors)");
}

/// An actor's mass [kg]: a rigid body's, a soft body's lumped total, an articulation's links'.
double MassOf(const Actor& a) {
  if (a.IsSoft()) return a.scene->SoftModel(a.Handle()).mass;
  if (a.scene->IsAttached(a.Handle())) return 0.0;  // its link's mass is its articulation's
  if (const ArticulatedKind* k = a.AsArticulated()) {
    double m = 0.0;
    for (int l = 0; l < k->NumLinks(); ++l) m += k->LinkMass(l);
    return m;
  }
  return a.scene->Model(a.Handle()).mass;
}

}  // namespace

void BindActor(py::module_& m) {
  py::class_<Actor> actor(m, "Actor",
                    "A handle to an actor of a Scene: rigid, soft (is_soft) or articulated\n"
                    "(is_articulated). Rigid-only properties (rotation, orientation,\n"
                    "angular_velocity) raise TypeError on the others, soft-only ones\n"
                    "(node_positions, ...) and articulated-only ones (joint_positions, ...) on the\n"
                    "others.");
  actor.def_property_readonly("index", [](const Actor& a) { return a.index; })
      .def_property_readonly("name", [](const Actor& a) { return a.Name(); })
      .def_property_readonly("is_soft", &Actor::IsSoft)
      .def_property_readonly(
          "is_attached", [](const Actor& a) { return a.scene->IsAttached(a.Handle()); },
          "True for a link's collision shape (an actor nested under its articulation, moving "
          "with the link; mass 0, its state read-only)")
      .def_property_readonly(
          "carrier",
          [](const Actor& a) -> std::optional<Actor> {
            const ActorHandle c = a.scene->Carrier(a.Handle());
            if (!c.IsValid()) return std::nullopt;
            return Actor{a.scene, c.index};
          },
          "The articulated actor whose links carry this actor (a link shape's, or a soft "
          "skin's skeleton), or None")
      .def_property_readonly("mass", &MassOf, "[kg]")
      .def_property_readonly(
          "dynamic",
          [](const Actor& a) {
            return a.IsSoft() || a.IsKind() || a.scene->Model(a.Handle()).dynamic;
          },
          "False for a static or kinematic rigid actor; soft and articulated actors are always "
          "dynamic")
      .def_property_readonly(
          "kinematic",
          [](const Actor& a) {
            return !a.IsSoft() && !a.IsKind() && a.scene->Model(a.Handle()).kinematic;
          },
          "True for a rigid actor whose motion is prescribed (RigidActorDesc.kinematic)")
      .def_property_readonly("contact_layer",
                             [](const Actor& a) { return a.scene->ContactLayer(a.Handle()); })
      .def(
          "set_contact_layer",
          [](Actor& a, const std::string& layer) {
            Error e;
            if (!a.scene->SetContactLayer(a.Handle(), layer, &e)) throw py::value_error(e.message);
          },
          py::arg("layer"), "Actor::SetContactLayer: any string.")
      .def_property("contact_params", &ActorContactParamsOf, &SetActorContactParams,
                    "the actor's contact parameters, live: `a.contact_params.x = v` changes the "
                    "actor's (validated); assign a ContactParams to replace them all; "
                    "`.copy()` gives a ContactParams")
      // Assigning position, orientation, velocity or angular_velocity (or a soft actor's nodes)
      // changes the state now and restarts the multistep integrator's history, as a new
      // initial state; static actors refuse it.
      .def_property(
          "position", [](const Actor& a) { return a.scene->CenterOfMass(a.Handle()); },
          [](Actor& a, const Eigen::Vector3d& p) { SetCentre(a, "position", p, false); },
          "centre of mass [m] (soft: of the lumped node masses; assigning it translates every "
          "node)")
      .def_property_readonly("rotation",
                             [](const Actor& a) { return a.RigidState("rotation").R; },
                             "rotation matrix (rigid actors)")
      .def_property(
          "orientation", [](const Actor& a) { return Quaternion(a.RigidState("orientation").R); },
          [](Actor& a, const Eigen::Vector4d& q) {
            if (!(q.allFinite() && q.norm() > 0))
              throw py::value_error("orientation: must be a finite non-zero quaternion");
            const Eigen::Matrix3d R =
                Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized().toRotationMatrix();
            EditRigid(a, "orientation", [&](RigidBodyState* s) {
              const Eigen::Vector3d w = s->AngularVelocity();  // kept
              s->R = R;
              s->Rdot = Skew(w) * R;
            });
          },
          "quaternion [x, y, z, w] (rigid actors; assigned ones are normalized, the angular "
          "velocity is kept)")
      .def_property(
          "velocity", [](const Actor& a) { return a.scene->CenterOfMassVelocity(a.Handle()); },
          [](Actor& a, const Eigen::Vector3d& v) { SetCentre(a, "velocity", v, true); },
          "centre-of-mass velocity [m/s] (soft: assigning it adds the same velocity to every "
          "node)")
      .def_property(
          "angular_velocity",
          [](const Actor& a) { return a.RigidState("angular_velocity").AngularVelocity(); },
          [](Actor& a, const Eigen::Vector3d& w) {
            const Eigen::Vector3d to = Finite3(w, "angular_velocity");
            EditRigid(a, "angular_velocity",
                      [&](RigidBodyState* s) { s->Rdot = Skew(to) * s->R; });
          },
          "world angular velocity [rad/s] (rigid actors)");
  DefSoftProperties(actor);
  DefArticulatedProperties(actor);
  actor.def("__repr__", [](const Actor& a) {
    return "<superdex.Actor " + std::to_string(a.index) + " '" + a.Name() + "'" +
           (a.IsSoft() ? " soft" : a.IsKind() ? " " + a.scene->Kind(a.Handle()).KindName() : "") +
           ">";
  });
}

}  // namespace superdex::python
