// The Python Actor: a handle to an actor of a Scene (shared by bind_actor.cpp and bind_scene.cpp).
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "bindings.h"
#include "core/scene.h"

namespace superdex::python {

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
  RigidBodyState RigidState(const char* field) const {
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

/// Actor.contact_params: the live view (bind_params.cpp), and its assignment from a
/// ContactParams or another actor's view.
py::object ActorContactParamsOf(const Actor& a);
void SetActorContactParams(Actor& a, const py::object& value);

/// [x, y, z, w] of a rotation matrix.
inline Eigen::Vector4d Quaternion(const Eigen::Matrix3d& R) {
  const Eigen::Quaterniond q(R);
  return Eigen::Vector4d(q.x(), q.y(), q.z(), q.w());
}

}  // namespace superdex::python
