// The Python Actor: a handle to an actor of a Scene (shared by bind_actor.cpp and bind_scene.cpp).
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "bindings.h"
#include "core/model/articulated_kind.h"
#include "core/scene.h"

namespace superdex::python {

/// A handle to an actor of a Scene (the Python Actor). Keeps its scene alive.
struct Actor {
  Scene* scene = nullptr;
  int index = -1;
  ActorHandle Handle() const { return {index}; }
  bool IsSoft() const { return scene->IsSoft(Handle()); }
  /// An actor of the generic layer (an articulated one), neither rigid nor soft.
  bool IsKind() const { return scene->IsKind(Handle()); }
  const ArticulatedKind* AsArticulated() const {
    return dynamic_cast<const ArticulatedKind*>(&scene->Kind(Handle()));
  }
  const std::string& Name() const { return scene->ActorName(Handle()); }
  /// The rigid state (an attached actor's: its carrier's link pose); TypeError naming `field`
  /// for a soft or articulated actor.
  RigidBodyState RigidState(const char* field) const {
    if (IsSoft())
      throw py::type_error(std::string(field) + ": '" + Name() +
                           "' is a soft actor; rotation, orientation and angular_velocity are "
                           "defined for rigid actors only (see node_positions)");
    if (scene->IsAttached(Handle())) return scene->BodyState(Handle());  // a link's shape
    if (IsKind())
      throw py::type_error(std::string(field) + ": '" + Name() + "' is an " +
                           scene->Kind(Handle()).KindName() + " actor; rotation, orientation "
                           "and angular_velocity are defined for rigid actors only (see "
                           "joint_positions, link_positions)");
    return scene->State(Handle());
  }
  /// The articulated kind; TypeError naming `field` for another actor.
  const ArticulatedKind& Articulated(const char* field) const {
    const ArticulatedKind* k = AsArticulated();
    if (!k)
      throw py::type_error(std::string(field) + ": '" + Name() +
                           "' is not an articulated actor; " + field +
                           " is defined for articulated actors only");
    return *k;
  }
  /// The soft model; TypeError naming `field` for another actor.
  const SoftBodyModel& Soft(const char* field) const {
    if (!IsSoft())
      throw py::type_error(std::string(field) + ": '" + Name() + "' is " +
                           (IsKind() ? "an " + scene->Kind(Handle()).KindName() : std::string("a rigid")) +
                           " actor; " + field + " is defined for soft actors only");
    return scene->SoftModel(Handle());
  }
  const SoftBodyState& SoftState(const char* field) const {
    Soft(field);
    return scene->SoftState(Handle());
  }
  /// The state of a body of nodes (a soft or shell actor); TypeError naming `field` otherwise.
  const KindState& NodeState(const char* field) const {
    if (IsSoft()) return SoftState(field);
    if (!dynamic_cast<const NodeBodyKind*>(&scene->Kind(Handle()))) Soft(field);  // throws
    return scene->KindStateOf(Handle());
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
