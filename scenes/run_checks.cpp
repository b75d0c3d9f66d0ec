#include "scenes/run_checks.h"

#include <cmath>

#include "geometry/number_text.h"

namespace superdex {
namespace {

std::string Num(double x) { return NumberText(x, 4); }

std::string Name(const SceneFile& file, int i) { return "'" + file.actorNames[i] + "'"; }

// The smallest half extent of actor i [m]; +∞ for a plane.
double HalfExtent(const Scene& scene, int i) {
  if (scene.IsSoft({i})) {
    const Aabb b = scene.SoftModel({i}).rest.Bounds();
    return 0.5 * (b.max - b.min).minCoeff();
  }
  if (!scene.BodyModel({i})) return INFINITY;  // no shape of its own
  const RigidBodyModel& m = *scene.BodyModel({i});
  switch (m.shape.kind) {
    case RigidShapeKind::Sphere: return m.shape.radius;
    case RigidShapeKind::Box: return m.shape.halfExtents.minCoeff();
    case RigidShapeKind::Capsule: return m.shape.radius;
    case RigidShapeKind::Mesh: return 0.5 * (m.localBounds.max - m.localBounds.min).minCoeff();
    case RigidShapeKind::Plane: break;
  }
  return INFINITY;
}

// "" when actor i's state, kinetic and gravity energy are finite.
std::string CheckActor(const SceneFile& file, int i) {
  const Scene& scene = *file.scene;
  const Eigen::Vector3d g = scene.Settings().gravity;
  double kinetic = 0.0, gravity = 0.0;
  bool finite = true;
  if (scene.IsKind({i})) {
    const ActorKind& kind = scene.Kind({i});
    const KindState& s = scene.KindStateOf({i});
    finite = s.x.allFinite() && s.v.allFinite();
    if (finite) {
      kinetic = kind.KineticEnergy(s);
      gravity = kind.GravityEnergy(s, g);
    }
  } else if (scene.IsSoft({i})) {
    const SoftBodyModel& m = scene.SoftModel({i});
    const SoftBodyState& s = scene.SoftState({i});
    finite = s.x.allFinite() && s.v.allFinite();
    if (finite) {
      kinetic = KineticEnergy(m, s);
      for (int a = 0; a < m.NumNodes(); ++a) gravity -= m.nodeMass[a] * g.dot(s.x.segment<3>(3 * a));
    }
  } else {
    const RigidBodyModel& m = scene.Model({i});
    if (!m.dynamic) return "";
    const RigidBodyState& s = scene.State({i});
    finite = s.p.allFinite() && s.R.allFinite() && s.v.allFinite() && s.Rdot.allFinite();
    if (finite) {
      kinetic = KineticEnergy(m, s);
      gravity = -m.mass * g.dot(s.p);
    }
  }
  if (!finite) return "the state of actor " + Name(file, i) + " is not finite (NaN or infinity)";
  if (!std::isfinite(kinetic))
    return "the kinetic energy of actor " + Name(file, i) + " is not finite (its velocity is " +
           "beyond double precision)";
  if (!std::isfinite(gravity))
    return "the gravity energy of actor " + Name(file, i) + " is not finite (gravity, mass " +
           "and height overflow double precision)";
  return "";
}

std::string CheckPenetration(double minSignedDistance, const PenetrationBound& bound) {
  const double depth = -minSignedDistance;
  if (!(depth > bound.value)) return "";
  return "the penetration " + Num(depth * 1e3) + " mm exceeds the bound " +
         Num(bound.value * 1e3) + " mm (" + bound.reason + "): the contact does not hold " +
         "the load; raise contact.penalty_coefficient, lower the masses or the step, or set " +
         "settings.penetration_bound";
}

}  // namespace

PenetrationBound MakePenetrationBound(const SceneFile& file) {
  PenetrationBound b;
  if (file.penetrationBound) {
    b.value = *file.penetrationBound;
    b.reason = "settings.penetration_bound";
    return b;
  }
  const Scene& scene = *file.scene;
  for (int i = 0; i < scene.NumActors(); ++i) {
    const double h = HalfExtent(scene, i);
    if (h < b.value) {
      b.value = h;
      b.reason = "the smallest half extent of the actors, of " + Name(file, i);
    }
  }
  return b;
}

std::string CheckInitialState(SceneFile* file, const PenetrationBound& bound) {
  for (int i = 0; i < file->scene->NumActors(); ++i)
    if (std::string m = CheckActor(*file, i); !m.empty()) return "at t = 0: " + m;
  const double phi = file->scene->ContactState().minSignedDistance;
  if (std::string m = CheckPenetration(phi, bound); !m.empty()) return "at t = 0: " + m;
  return "";
}

std::string CheckStep(const SceneFile& file, long long step, const StepReport& rep,
                      const PenetrationBound& bound, bool* finite) {
  const Scene& scene = *file.scene;
  // The message's prefix, formed only for a message (every step passes through here).
  auto where = [&] { return "step " + std::to_string(step) + " (t = " + Num(rep.time) + " s): "; };
  *finite = true;
  for (int i = 0; i < scene.NumActors(); ++i)
    if (std::string m = CheckActor(file, i); !m.empty()) {
      *finite = false;
      return where() + m;
    }
  if (!std::isfinite(rep.contact.energy)) {
    *finite = false;
    return where() + "the contact energy is not finite";
  }
  if (rep.minDetF <= 0) {
    for (const ActorHandle h : scene.SoftActors()) {
      double minDetF = INFINITY;
      ElasticEnergy(scene.SoftModel(h), scene.SoftState(h).x, &minDetF);
      if (minDetF <= 0)
        return where() + "a tet of soft actor " + Name(file, h.index) + " inverted (min det F = " +
               Num(minDetF) + " <= 0): the material is too soft for its load (raise " +
               "material.youngs_modulus) or the step too large";
    }
    return where() + "a soft tet inverted (min det F = " + Num(rep.minDetF) + " <= 0)";
  }
  if (std::string m = CheckPenetration(rep.contact.minSignedDistance, bound); !m.empty())
    return where() + m;
  return "";
}

}  // namespace superdex
