// Actor descriptions shared by the physics tests.
#pragma once

#include "core/rigid_body.h"

namespace superdex::test {

/// A static ground plane z <= 0 with penalty coefficient k [Pa/m] and Coulomb coefficient mu.
inline RigidActorDesc StaticGround(double k = 1e9, double mu = 0.5) {
  RigidActorDesc d;
  d.name = "ground";
  d.dynamic = false;
  d.shape.kind = RigidShapeKind::Plane;
  d.contact.penaltyCoefficient = k;
  d.contact.coulombFrictionCoefficient = mu;
  return d;
}

}  // namespace superdex::test
