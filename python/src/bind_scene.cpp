// Scene, actors, stepping and running, with states and trajectories as numpy arrays.
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "core/model/rigid_math.h"
#include "core/scene.h"
#include "geometry/mesh_io.h"
#include "geometry/triangle_mesh.h"
#include "scenes/scene_file.h"

namespace superdex::python {
namespace {

/// A handle to an actor of a Scene (the Python Actor). Keeps its scene alive.
struct Actor {
  Scene* scene = nullptr;
  int index = -1;
  ActorHandle Handle() const { return {index}; }
  bool IsSoft() const { return scene->IsSoft(Handle()); }
  const std::string& Name() const {
    return IsSoft() ? scene->SoftModel(Handle()).name : scene->Model(Handle()).name;
  }
  /// The rigid state; TypeError naming `field` for a soft actor.
  const RigidBodyState& RigidState(const char* field) const {
    if (IsSoft())
      throw py::type_error(std::string(field) + ": '" + Name() +
                           "' is a soft actor; rotation, orientation and angular_velocity are "
                           "defined for rigid actors only (see node_positions)");
    return scene->State(Handle());
  }
  /// The soft model; TypeError naming `field` for a rigid actor.
  const SoftBodyModel& Soft(const char* field) const {
    if (!IsSoft())
      throw py::type_error(std::string(field) + ": '" + Name() +
                           "' is a rigid actor; " + field + " is defined for soft actors only");
    return scene->SoftModel(Handle());
  }
  const SoftBodyState& SoftState(const char* field) const {
    Soft(field);
    return scene->SoftState(Handle());
  }
};

Eigen::Vector4d Quaternion(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q(R);
  return Eigen::Vector4d(q.x(), q.y(), q.z(), q.w());
}

void RaiseOnFailure(const StepReport& r) {
  if (r.status != StageStatus::Converged)
    throw std::runtime_error(std::string("stage ") + ToString(r.status) + " at t = " +
                             std::to_string(r.time) + " s: " + r.message);
}

py::dict Energies(Scene& s) {
  const EnergyReport e = s.Energies();
  py::dict d;
  d["kinetic"] = e.kinetic;
  d["gravity"] = e.gravity;
  d["contact"] = e.contact;
  d["elastic"] = e.elastic;
  d["total"] = e.Total();
  return d;
}

// Runs for `duration` with step dt, recording every `every`-th state (and the first and last)
// straight into numpy arrays.
py::dict Run(Scene& s, double duration, double dt, int every,
             const std::function<void(double, const StepReport&)>& progress) {
  if (!(duration > 0) || !(dt > 0)) throw py::value_error("duration, dt: must be > 0");
  if (every < 1) throw py::value_error("every: must be >= 1, got " + std::to_string(every));
  const int steps = static_cast<int>(std::ceil(duration / dt - 1e-9));
  const int frames = 1 + (steps + every - 1) / every + ((steps % every) != 0 ? 0 : 0);
  const int A = s.NumActors();
  py::array_t<double> t(frames), p({frames, A, 3}), q({frames, A, 4}), v({frames, A, 3}),
      w({frames, A, 3}), energy(frames);
  auto T = t.mutable_unchecked<1>();
  auto P = p.mutable_unchecked<3>();
  auto Q = q.mutable_unchecked<3>();
  auto V = v.mutable_unchecked<3>();
  auto W = w.mutable_unchecked<3>();
  auto E = energy.mutable_unchecked<1>();
  int frame = 0;
  auto record = [&]() {
    T(frame) = s.Time();
    for (int a = 0; a < A; ++a) {
      // Soft actors: centre of mass and its velocity; no orientation or angular velocity (NaN).
      const ActorHandle h{a};
      const bool soft = s.IsSoft(h);
      const Eigen::Vector3d pa = s.CenterOfMass(h), va = s.CenterOfMassVelocity(h);
      const Eigen::Vector4d qa =
          soft ? Eigen::Vector4d::Constant(NAN) : Quaternion(s.State(h).R);
      const Eigen::Vector3d wa =
          soft ? Eigen::Vector3d::Constant(NAN) : s.State(h).AngularVelocity();
      for (int k = 0; k < 3; ++k) {
        P(frame, a, k) = pa[k];
        V(frame, a, k) = va[k];
        W(frame, a, k) = wa[k];
      }
      for (int k = 0; k < 4; ++k) Q(frame, a, k) = qa[k];
    }
    E(frame) = s.Energies().Total();
    ++frame;
  };
  record();
  for (int i = 1; i <= steps; ++i) {
    StepReport r;
    Error e;
    const double h = std::min(dt, duration - (i - 1) * dt);
    bool ok;
    {
      py::gil_scoped_release release;
      ok = s.Step(h > 1e-12 * dt ? h : dt, &r, &e);
    }
    if (!ok) throw py::value_error(e.message);
    RaiseOnFailure(r);
    if ((i % every == 0 || i == steps) && frame < frames) record();
    if (progress) progress(double(i) / steps, r);
  }
  py::dict d;
  d["t"] = t[py::slice(0, frame, 1)];
  d["p"] = p[py::slice(0, frame, 1)];
  d["q"] = q[py::slice(0, frame, 1)];
  d["v"] = v[py::slice(0, frame, 1)];
  d["w"] = w[py::slice(0, frame, 1)];
  d["energy"] = energy[py::slice(0, frame, 1)];
  return d;
}

py::dict ContactSamples(Scene& s) {
  const std::vector<ContactSampleRecord> r = s.ContactSamples();
  const py::ssize_t n = static_cast<py::ssize_t>(r.size());
  py::array_t<int> colliding(n), collider(n), face(n);
  py::array_t<double> position({n, py::ssize_t(3)}), normal({n, py::ssize_t(3)}),
      traction({n, py::ssize_t(3)}), phi(n), lambdaN(n), weight(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    colliding.mutable_at(i) = r[i].colliding;
    collider.mutable_at(i) = r[i].collider;
    face.mutable_at(i) = r[i].face;
    phi.mutable_at(i) = r[i].phi;
    lambdaN.mutable_at(i) = r[i].lambdaN;
    weight.mutable_at(i) = r[i].weight;
    for (int k = 0; k < 3; ++k) {
      position.mutable_at(i, k) = r[i].position[k];
      normal.mutable_at(i, k) = r[i].normal[k];
      traction.mutable_at(i, k) = r[i].traction[k];
    }
  }
  py::dict d;
  d["colliding"] = colliding;
  d["collider"] = collider;
  d["position"] = position;
  d["normal"] = normal;
  d["phi"] = phi;
  d["lambda_n"] = lambdaN;
  d["traction"] = traction;
  d["weight"] = weight;
  d["face"] = face;  // soft colliding actors: the boundary face; −1 for rigid ones
  return d;
}

RigidShape MakeShape(RigidShapeKind kind) {
  RigidShape s;
  s.kind = kind;
  return s;
}

}  // namespace

void BindScene(py::module_& m) {
  py::class_<RigidShape>(m, "RigidShape",
                         "Geometry of a rigid actor in its own frame; make one with sphere(), "
                         "box(), plane() or mesh().")
      .def_static(
          "sphere",
          [](double radius, int surfaceResolution) {
            RigidShape s = MakeShape(RigidShapeKind::Sphere);
            s.radius = radius;
            s.surfaceResolution = surfaceResolution;
            return s;
          },
          py::arg("radius"), py::arg("surface_resolution") = 3,
          "A sphere of the given radius [m]; surface_resolution icosphere subdivisions (0-7).")
      .def_static(
          "box",
          [](const Eigen::Vector3d& size, int surfaceResolution) {
            RigidShape s = MakeShape(RigidShapeKind::Box);
            s.halfExtents = 0.5 * size;
            s.surfaceResolution = surfaceResolution;
            return s;
          },
          py::arg("size"), py::arg("surface_resolution") = 2,
          "A box of edge lengths size = [x, y, z] [m]; surface_resolution cells per edge.")
      .def_static(
          "plane",
          [](const Eigen::Vector3d& normal) {
            RigidShape s = MakeShape(RigidShapeKind::Plane);
            s.planeNormal = normal;
            return s;
          },
          py::arg("normal") = Eigen::Vector3d::UnitZ(),
          "The half space below the plane through the actor's position (static actors only).")
      .def_static(
          "mesh",
          [](const std::string& path, double scale) {
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
      .def_property_readonly("kind", [](const RigidShape& s) {
        const char* names[] = {"sphere", "box", "mesh", "plane"};
        return std::string(names[static_cast<int>(s.kind)]);
      });

  py::class_<RigidActorDesc>(m, "RigidActorDesc",
                             "What a rigid actor is made from. Units: kg, m, m/s, rad/s.")
      .def(py::init([](const std::string& name, const RigidShape& shape, bool dynamic) {
             RigidActorDesc d;
             d.name = name;
             d.shape = shape;
             d.dynamic = dynamic;
             return d;
           }),
           py::arg("name"), py::arg("shape"), py::arg("dynamic") = true)
      .def_readwrite("name", &RigidActorDesc::name)
      .def_readwrite("dynamic", &RigidActorDesc::dynamic)
      .def_readwrite("shape", &RigidActorDesc::shape)
      .def_readwrite("density", &RigidActorDesc::density, "[kg/m^3], used without mass")
      .def_readwrite("mass", &RigidActorDesc::mass, "[kg] or None (then from density)")
      .def_readwrite("position", &RigidActorDesc::position, "shape frame origin [m]")
      .def_property(
          "orientation",
          [](const RigidActorDesc& d) {
            return Eigen::Vector4d(d.orientation.x(), d.orientation.y(), d.orientation.z(),
                                   d.orientation.w());
          },
          [](RigidActorDesc& d, const Eigen::Vector4d& q) {
            if (!(q.norm() > 0)) throw py::value_error("orientation: must be a non-zero quaternion");
            d.orientation = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized();
          },
          "quaternion [x, y, z, w]")
      .def_readwrite("velocity", &RigidActorDesc::linearVelocity, "of the centre of mass [m/s]")
      .def_readwrite("angular_velocity", &RigidActorDesc::angularVelocity, "world frame [rad/s]")
      .def_readwrite("contact", &RigidActorDesc::contact, "ContactParams")
      .def_readwrite("collider_type", &RigidActorDesc::colliderType)
      .def_readwrite("boundary_element_type", &RigidActorDesc::boundaryElementType)
      .def_readwrite("contact_layer", &RigidActorDesc::contactLayer)
      .def_readwrite("grid_sdf", &RigidActorDesc::gridSdf, "GridSdfParams for an Sdf collider");

  py::class_<NonlinearSolverParams>(m, "NonlinearSolverParams", "Stage solver settings.")
      .def(py::init<>())
      .def_readwrite("max_iterations", &NonlinearSolverParams::maxIterations)
      .def_readwrite("absolute_tolerance", &NonlinearSolverParams::absoluteTolerance,
                     "Newton decrement tolerance [J]. Default 1e-12.")
      .def_readwrite("relative_tolerance", &NonlinearSolverParams::relativeTolerance,
                     "gradient reduction tolerance [-]. Default 1e-10.")
      .def_readwrite("step_tolerance", &NonlinearSolverParams::stepTolerance,
                     "step velocity tolerance [m/s]. Default 1e-9.")
      .def_readwrite("part_line_search", &NonlinearSolverParams::partLineSearch,
                     "one line-search step length per independent part of a stage (bodies no "
                     "contact joins). Default True.")
      .def_property(
          "linear_solver",
          [](const NonlinearSolverParams& p) { return std::string(ToString(p.linear.kind)); },
          [](NonlinearSolverParams& p, const std::string& name) {
            if (!ParseLinearSolverKind(name, &p.linear.kind))
              throw py::value_error("linear_solver: unknown value \"" + name +
                                    "\" (expected one of: auto, direct, iterative)");
          },
          "'auto' (default: Krylov from 3000 unknowns up), 'direct' or 'iterative'.")
      .def_property(
          "linear_tolerance", [](const NonlinearSolverParams& p) { return p.linear.tolerance; },
          [](NonlinearSolverParams& p, double t) { p.linear.tolerance = t; },
          "Krylov relative residual tolerance, in (0, 1). Default 1e-8.")
      .def_property(
          "linear_max_iterations",
          [](const NonlinearSolverParams& p) { return p.linear.maxIterations; },
          [](NonlinearSolverParams& p, int n) { p.linear.maxIterations = n; },
          "Krylov iterations before the direct fallback. Default 500.");

  py::class_<SceneSettings>(m, "SceneSettings", "Scene-wide settings.")
      .def(py::init<>())
      .def_readwrite("gravity", &SceneSettings::gravity, "[m/s^2]. Default [0, 0, -9.81].")
      .def_readwrite("integrator", &SceneSettings::integrator, "Default IntegrationMethod.BDF2.")
      .def_readwrite("solver", &SceneSettings::solver)
      .def_readwrite("experimental_eval_params", &SceneSettings::eval)
      .def_readwrite("warm_start", &SceneSettings::warmStart,
                     "Newton stage solves of rigid bodies start from the motion's prediction "
                     "(the last step's acceleration continued). Default True.")
      .def_readwrite("closed_form_free_stages", &SceneSettings::closedFormFreeStages,
                     "A Newton stage with no contact sample active at the minimizer of inertia "
                     "and gravity is solved in closed form (0 Newton iterations). Default True.")
      .def_property(
          "stage_solver", [](const SceneSettings& s) { return std::string(ToString(s.stageSolver)); },
          [](SceneSettings& s, const std::string& name) {
            if (!ParseStageSolver(name, &s.stageSolver))
              throw py::value_error("stage_solver: unknown value \"" + name +
                                    "\" (expected one of: newton, ipopt, ceres)");
          },
          "'newton' (default), 'ipopt' (potential stages) or 'ceres'.");

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

  py::class_<Scene>(m, "Scene", "Actors, settings and time stepping.")
      .def(py::init([](const SceneSettings& s) {
             CheckValue(Validate(s, "settings."));
             return std::make_unique<Scene>(s);
           }),
           py::arg("settings") = SceneSettings())
      .def(
          "add_rigid_actor",
          [](Scene& s, const RigidActorDesc& d, std::optional<Actor> parent) {
            Error e;
            const ActorHandle h =
                s.AddRigidActor(d, &e, parent ? parent->Handle() : ActorHandle());
            if (!h.IsValid()) throw py::value_error(e.message);
            return Actor{&s, h.index};
          },
          py::arg("desc"), py::arg("parent") = py::none(), py::keep_alive<0, 1>(),
          "Adds a rigid actor (nested under `parent` if given); raises ValueError on bad input.")
      .def(
          "add_soft_actor",
          [](Scene& s, const SoftActorDesc& d, std::optional<Actor> parent) {
            Error e;
            const ActorHandle h =
                s.AddSoftActor(d, &e, parent ? parent->Handle() : ActorHandle());
            if (!h.IsValid()) throw py::value_error(e.message);
            return Actor{&s, h.index};
          },
          py::arg("desc"), py::arg("parent") = py::none(), py::keep_alive<0, 1>(),
          "Adds a soft (tet FEM) actor (nested under `parent` if given); raises ValueError\n"
          "naming the field and the rule on bad input. The mesh is copied.")
      .def_property_readonly("actors",
                             [](Scene& s) {
                               std::vector<Actor> out;
                               for (int i = 0; i < s.NumActors(); ++i) out.push_back({&s, i});
                               return out;
                             },
                             py::return_value_policy::reference_internal)
      .def(
          "actor",
          [](Scene& s, const std::string& name) {
            for (int i = 0; i < s.NumActors(); ++i)
              if (Actor{&s, i}.Name() == name) return Actor{&s, i};
            throw py::value_error("no actor named \"" + name + "\"");
          },
          py::arg("name"), py::keep_alive<0, 1>())
      .def_property_readonly("time", &Scene::Time, "simulated time [s]")
      .def(
          "step",
          [](Scene& s, double dt, bool check) {
            StepReport r;
            Error e;
            bool ok;
            {
              py::gil_scoped_release release;
              ok = s.Step(dt, &r, &e);
            }
            if (!ok) throw py::value_error(e.message);
            if (check) RaiseOnFailure(r);
            return r;
          },
          py::arg("dt"), py::arg("check") = true,
          "Advances by dt [s]. A stage that does not converge raises RuntimeError (check=False\n"
          "returns the report instead).")
      .def("run", &Run, py::arg("duration"), py::arg("dt"), py::arg("every") = 1,
           py::arg("progress") = nullptr,
           "Runs for `duration` [s] with step `dt` [s]; returns a dict of numpy arrays over the\n"
           "recorded frames (the initial state, every `every`-th step and the last):\n"
           "t (F,), p (F, A, 3), q (F, A, 4) quaternions [x, y, z, w], v (F, A, 3),\n"
           "w (F, A, 3) world angular velocities, energy (F,). Soft actors: p and v of the\n"
           "centre of mass, q and w NaN. progress(fraction, report) is called after every\n"
           "step. A non-converged stage raises RuntimeError.")
      .def("energies", &Energies, "kinetic, gravity, contact, elastic and total energy [J]")
      .def("total_linear_momentum", &Scene::TotalLinearMomentum)
      .def("total_angular_momentum", &Scene::TotalAngularMomentum)
      .def("contact_samples", &ContactSamples,
           "Active contact samples at the current state as numpy arrays: colliding, collider\n"
           "(actor indices), position (n, 3) [m], normal (n, 3), phi [m], lambda_n [Pa],\n"
           "traction (n, 3) normal traction on the colliding actor [Pa], weight [m^2]\n"
           "(force = weight * traction).")
      .def("has_dissipation", &Scene::HasDissipation)
      .def("notices", &Scene::Notices,
           "one-time notes about the scene (grid SDF sizes and memory, unsupported colliders)")
      .def(
          "set_integrator",
          [](Scene& s, IntegrationMethod m) {
            Error e;
            if (!s.SetIntegrator(m, &e)) throw py::value_error(e.message);
          },
          py::arg("method"))
      .def(
          "set_stage_solver",
          [](Scene& s, const std::string& name) {
            StageSolverKind k;
            Error e;
            if (!ParseStageSolver(name, &k))
              throw py::value_error("stage_solver: unknown value \"" + name + "\"");
            if (!s.SetStageSolver(k, &e)) throw py::value_error(e.message);
          },
          py::arg("name"))
      .def(
          "enable_layer_contact_asymmetric",
          [](Scene& s, const std::string& a, const std::string& b, bool enable) {
            Error e;
            if (!s.EnableLayerContactAsymmetric(a, b, enable, &e)) throw py::value_error(e.message);
          },
          py::arg("layer_a"), py::arg("layer_b"), py::arg("enable"),
          "Layer A colliding against layer B as collider; not the reverse.")
      .def(
          "enable_layer_contact_symmetric",
          [](Scene& s, const std::string& a, const std::string& b, bool enable) {
            Error e;
            if (!s.EnableLayerContactSymmetric(a, b, enable, &e)) throw py::value_error(e.message);
          },
          py::arg("layer_a"), py::arg("layer_b"), py::arg("enable"))
      .def(
          "enable_actor_contact_asymmetric",
          [](Scene& s, const Actor& a, const Actor& b, bool enable, IncludeNestedActors n) {
            Error e;
            if (!s.EnableActorContactAsymmetric(a.Handle(), b.Handle(), enable, n, &e))
              throw py::value_error(e.message);
          },
          py::arg("a"), py::arg("b"), py::arg("enable"),
          py::arg("include_nested_actors") = IncludeNestedActors::No,
          "The actor-pair gate for A colliding against B (cannot re-enable a layer-disabled pair).")
      .def(
          "enable_actor_contact_symmetric",
          [](Scene& s, const Actor& a, const Actor& b, bool enable, IncludeNestedActors n) {
            Error e;
            if (!s.EnableActorContactSymmetric(a.Handle(), b.Handle(), enable, n, &e))
              throw py::value_error(e.message);
          },
          py::arg("a"), py::arg("b"), py::arg("enable"),
          py::arg("include_nested_actors") = IncludeNestedActors::No)
      .def(
          "contact_allowed",
          [](const Scene& s, const Actor& a, const Actor& b) {
            return s.ContactAllowed(a.Handle(), b.Handle());
          },
          py::arg("a"), py::arg("b"));

  py::class_<SceneFile>(m, "SceneFile", "A loaded superdex-scene/1 file.")
      .def_property_readonly("scene", [](SceneFile& f) { return f.scene.get(); },
                             py::return_value_policy::reference_internal)
      .def_readonly("dt", &SceneFile::dt)
      .def_readonly("duration", &SceneFile::duration)
      .def_readonly("description", &SceneFile::description)
      .def_readonly("actor_names", &SceneFile::actorNames);
  m.def(
      "load_scene",
      [](const std::string& path) {
        auto f = std::make_unique<SceneFile>();
        Error e;
        if (!LoadSceneFile(path, f.get(), &e)) throw py::value_error(e.message);
        return f;
      },
      py::arg("path"), "Loads a scene file; raises ValueError naming the JSON path and the rule.");
}

}  // namespace superdex::python
