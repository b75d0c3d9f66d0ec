// The static ground of the scene tests: a plane z = 0 named "ground" with penalty k = 1e6 N/m³.
#pragma once

#include <catch2/catch.hpp>

#include "core/scene.h"

namespace superdex::test {

inline void AddGround(Scene* scene) {
  RigidActorDesc g;
  g.name = "ground";
  g.dynamic = false;
  g.shape.kind = RigidShapeKind::Plane;
  g.contact.penaltyCoefficient = 1e6;
  Error e;
  REQUIRE(scene->AddRigidActor(g, &e).IsValid());
}

}  // namespace superdex::test
