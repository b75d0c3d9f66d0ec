// Scene: construction, stepping and running with trajectories as numpy arrays, contact filtering;
// scene files. The types it takes and gives are bound in bind_params.cpp,
// bind_settings.cpp and bind_actor.cpp.
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <sstream>

#include "actor.h"
#include "bindings.h"
#include "core/contact/contact_report.h"
#include "core/scene.h"
#include "scenes/limits.h"
#include "scenes/scene_file.h"
#include "scenes/scene_writer.h"

namespace superdex::python {
namespace {

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
  // Counted in double first: a huge duration / dt must not wrap the int.
  const double stepCount = std::ceil(duration / dt - 1e-9);
  const int A = s.NumActors();
  const double bytes = (stepCount / every + 2) * std::max(A, 1) * 14 * sizeof(double);
  if (!(stepCount <= limits::kMaxSteps) || !(bytes <= limits::kMaxRecordBytes))
  {
    std::ostringstream m;
    m << "duration / dt: " << stepCount << " steps (limit " << limits::kMaxSteps
      << ") recorded in " << bytes / 1e9 << " GB of arrays (limit "
      << limits::kMaxRecordBytes / 1e9 << " GB)";
    throw py::value_error(m.str());
  }
  const int steps = static_cast<int>(stepCount);
  const int frames = 1 + (steps + every - 1) / every + ((steps % every) != 0 ? 0 : 0);
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
      // Soft and articulated actors: centre of mass and its velocity; no orientation or angular
      // velocity (NaN).
      const ActorHandle h{a};
      const bool soft = s.IsSoft(h) || s.IsKind(h);  // no single orientation
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
    const bool ok = WithoutGil([&] { return s.Step(h > 1e-12 * dt ? h : dt, &r, &e); });
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

py::list ContactPairs(Scene& s) {
  py::list out;
  for (const ContactPairSummary& p : SummarizeContactPairs(s.ContactSamples())) {
    py::dict d;
    d["a"] = p.a;
    d["b"] = p.b;
    d["force"] = p.force;
    d["normal_force"] = p.normalForce;
    d["friction_force"] = p.frictionForce;
    d["damping_force"] = p.dampingForce;
    d["torque"] = p.torque;
    d["centre_of_pressure"] = p.centreOfPressure;
    d["area"] = p.area;
    d["max_penetration"] = p.maxPenetration;
    d["samples"] = p.samples;
    out.append(d);
  }
  return out;
}

py::dict ContactSamples(Scene& s) {
  const std::vector<ContactSampleRecord> r = s.ContactSamples();
  const py::ssize_t n = static_cast<py::ssize_t>(r.size());
  py::array_t<int> colliding(n), collider(n), face(n);
  py::array_t<double> position({n, py::ssize_t(3)}), normal({n, py::ssize_t(3)}),
      traction({n, py::ssize_t(3)}), friction({n, py::ssize_t(3)}), damping({n, py::ssize_t(3)}),
      phi(n), lambdaN(n), weight(n);
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
      friction.mutable_at(i, k) = r[i].friction[k];
      damping.mutable_at(i, k) = r[i].damping[k];
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
  d["friction"] = friction;
  d["damping"] = damping;
  d["weight"] = weight;
  d["face"] = face;  // soft colliding actors: the boundary face; −1 for rigid ones
  return d;
}

// Scene.add_rigid_actor, Scene.add_soft_actor.
template <typename Desc>
Actor AddActor(Scene& s, const Desc& d, std::optional<Actor> parent) {
  Error e;
  const ActorHandle p = parent ? parent->Handle() : ActorHandle();
  ActorHandle h;
  if constexpr (std::is_same_v<Desc, RigidActorDesc>) h = s.AddRigidActor(d, &e, p);
  else h = s.AddSoftActor(d, &e, p);
  if (!h.IsValid()) throw py::value_error(e.message);
  return Actor{&s, h.index};
}

// The layer and actor-pair gates: Scene::Enable...(…, &error), ValueError on failure.
using LayerGate = bool (Scene::*)(const std::string&, const std::string&, bool, Error*);
using ActorGate = bool (Scene::*)(ActorHandle, ActorHandle, bool, IncludeNestedActors, Error*);

template <LayerGate gate>
void EnableLayers(Scene& s, const std::string& a, const std::string& b, bool enable) {
  Error e;
  if (!(s.*gate)(a, b, enable, &e)) throw py::value_error(e.message);
}

template <ActorGate gate>
void EnableActors(Scene& s, const Actor& a, const Actor& b, bool enable, IncludeNestedActors n) {
  Error e;
  if (!(s.*gate)(a.Handle(), b.Handle(), enable, n, &e)) throw py::value_error(e.message);
}

void BindContactFilter(py::class_<Scene>& scene) {
  scene
      .def("enable_layer_contact_asymmetric", &EnableLayers<&Scene::EnableLayerContactAsymmetric>,
           py::arg("layer_a"), py::arg("layer_b"), py::arg("enable"),
           "Layer A colliding against layer B as collider; not the reverse.")
      .def("enable_layer_contact_symmetric", &EnableLayers<&Scene::EnableLayerContactSymmetric>,
           py::arg("layer_a"), py::arg("layer_b"), py::arg("enable"))
      .def("enable_actor_contact_asymmetric", &EnableActors<&Scene::EnableActorContactAsymmetric>,
           py::arg("a"), py::arg("b"), py::arg("enable"),
           py::arg("include_nested_actors") = IncludeNestedActors::No,
           "The actor-pair gate for A colliding against B (cannot re-enable a layer-disabled "
           "pair).")
      .def("enable_actor_contact_symmetric", &EnableActors<&Scene::EnableActorContactSymmetric>,
           py::arg("a"), py::arg("b"), py::arg("enable"),
           py::arg("include_nested_actors") = IncludeNestedActors::No)
      .def(
          "contact_allowed",
          [](const Scene& s, const Actor& a, const Actor& b) {
            return s.ContactAllowed(a.Handle(), b.Handle());
          },
          py::arg("a"), py::arg("b"));
}

}  // namespace

void BindSceneClass(py::module_& m) {
  py::class_<Scene> scene(m, "Scene", "Actors, settings and time stepping.");
  scene.def(py::init([](const SceneSettings& s) {
             CheckValue(Validate(s, "settings."));
             return std::make_unique<Scene>(s);
           }),
           py::arg("settings") = SceneSettings())
      .def("add_rigid_actor", &AddActor<RigidActorDesc>, py::arg("desc"),
           py::arg("parent") = py::none(), py::keep_alive<0, 1>(),
           "Adds a rigid actor (nested under `parent` if given); raises ValueError on bad input.")
      .def("add_soft_actor", &AddActor<SoftActorDesc>, py::arg("desc"),
           py::arg("parent") = py::none(), py::keep_alive<0, 1>(),
          "Adds a soft (tet FEM) actor (nested under `parent` if given); raises ValueError\n"
          "naming the field and the rule on bad input. The mesh is copied. With desc.skin it\n"
          "is a soft-skinned actor: `parent` is its skeleton (an articulated actor), whose\n"
          "links carry the bound nodes from its current configuration on.")
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
            const bool ok = WithoutGil([&] { return s.Step(dt, &r, &e); });
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
      .def(
          "write_scene_file",
          [](const Scene& s, const std::string& path, double dt, double duration,
             const std::string& description) {
            SceneWriteOptions options;
            options.dt = dt;
            options.duration = duration;
            options.description = description;
            Error e;
            if (!WriteSceneFile(s, path, options, &e)) throw py::value_error(e.message);
          },
          py::arg("path"), py::arg("dt"), py::arg("duration"), py::arg("description") = "",
          "Writes the scene as a scene file (docs/scene-format.md, \"Writing a scene\") that\n"
          "`superdex run`, superdex.load_scene and the fitting take: loading it gives the same\n"
          "scene and the same trajectory, bit for bit. Meshes are written beside it. Raises\n"
          "ValueError naming the actor and the rule for what has no scene-file form (a scene\n"
          "that has stepped, a soft actor whose state was set).")
      .def("energies", &Energies, "kinetic, gravity, contact, elastic and total energy [J]")
      .def("total_linear_momentum", &Scene::TotalLinearMomentum)
      .def("total_angular_momentum", &Scene::TotalAngularMomentum)
      .def("contact_samples", &ContactSamples,
           "Active contact samples at the current state as numpy arrays: colliding, collider\n"
           "(actor indices), position (n, 3) [m], normal (n, 3), phi [m], lambda_n [Pa],\n"
           "traction (n, 3) normal traction on the colliding actor [Pa], friction and damping\n"
           "(n, 3) the last step's dissipation tractions on it [Pa] (zero after a state change),\n"
           "weight [m^2]. Force on the colliding actor: weight * (traction + friction + damping);\n"
           "the collider takes its opposite. A pair of two colliding actors appears in both\n"
           "passes, each with its share of the load (contact_pairs() sums them).")
      .def("contact_pairs", &ContactPairs,
           "Per actor pair a < b with contact, a dict: force, normal_force, friction_force,\n"
           "damping_force [N] on a (b takes the opposite), torque on a about the origin [N m],\n"
           "centre_of_pressure [m], area [m^2], max_penetration [m], samples; both passes summed.")
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
            if (!ParseName(name, &k))
              throw py::value_error("stage_solver: unknown value \"" + name + "\"");
            if (!s.SetStageSolver(k, &e)) throw py::value_error(e.message);
          },
          py::arg("name"));
  BindContactFilter(scene);
  BindSceneStateMethods(scene);
  BindArticulatedMethods(scene);
  BindShellMethods(scene);
}

void BindSceneFile(py::module_& m) {
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
