// Actors whose derived quantities do not fit in double precision are refused when added, naming
// the field (core/model validation; regression tests for the findings of issue 38).
#include <catch2/catch.hpp>
#include <memory>
#include <string>

#include "core/scene.h"

using namespace superdex;

namespace {

std::string AddRigid(const RigidActorDesc& d) {
  Scene scene;
  Error e;
  return scene.AddRigidActor(d, &e).IsValid() ? "<added>" : e.message;
}

std::string AddSoft(const SoftActorDesc& d) {
  Scene scene;
  Error e;
  return scene.AddSoftActor(d, &e).IsValid() ? "<added>" : e.message;
}

SoftActorDesc SoftBox(double half) {
  SoftActorDesc d;
  d.name = "jelly";
  d.mesh = std::make_shared<TetMesh>(MakeTetBox(Eigen::Vector3d::Constant(half), {1, 1, 1}));
  return d;
}

}  // namespace

TEST_CASE("bad input: rigid shapes too small for their mass properties", "[core][bad_input]") {
  // These used to give q = [0.5, 0, 0, 0] and energy -nan at exit code 0.
  RigidActorDesc ball;
  ball.name = "ball";
  ball.shape.kind = RigidShapeKind::Sphere;
  ball.shape.radius = 1e-200;
  CHECK(AddRigid(ball) ==
        "shape: its mass properties are not representable in double precision (mass 0 kg, "
        "second moment trace 0 kg m^2): the shape is too small or too large");
  RigidActorDesc box;
  box.name = "box";
  box.shape.kind = RigidShapeKind::Box;
  box.shape.halfExtents = Eigen::Vector3d::Constant(5e-321);
  box.mass = 1.0;
  CHECK(AddRigid(box).rfind("shape: its mass properties are not representable", 0) == 0);
  box.shape.halfExtents = Eigen::Vector3d::Constant(0.1);
  CHECK(AddRigid(box) == "<added>");
}

TEST_CASE("bad input: a rigid grid SDF whose padding overflows the node count",
          "[core][bad_input]") {
  // boundary_padding_dist 1e308 used to wrap the node count and crash in GMP (SIGFPE).
  RigidActorDesc rock;
  rock.name = "rock";
  rock.dynamic = false;
  rock.shape.kind = RigidShapeKind::Box;
  rock.shape.halfExtents = Eigen::Vector3d::Constant(0.1);
  rock.colliderType = ColliderType::Sdf;
  rock.gridSdf.boundaryPaddingDist = 1e308;
  CHECK(AddRigid(rock) ==
        "grid_sdf: the grid would hold inf nodes (limit 64e6); raise resolution_delta");
  rock.gridSdf.boundaryPaddingDist = 1e3;
  CHECK(AddRigid(rock).rfind("grid_sdf: the grid would hold 1.", 0) == 0);
}

TEST_CASE("bad input: soft material errors name material.<field>", "[core][bad_input]") {
  // They used to name actors[i].poisson_ratio for actors[i].material.poisson_ratio.
  SoftActorDesc d = SoftBox(0.1);
  d.material.poissonRatio = 0.5;
  CHECK(AddSoft(d) == "material.poisson_ratio: must be in (-1, 0.5), got 0.5");
  d = SoftBox(0.1);
  d.material.youngsModulus = -1;
  CHECK(AddSoft(d).rfind("material.youngs_modulus: must be finite and > 0, got -1", 0) == 0);
  d = SoftBox(0.1);
  d.material.density = 0;
  CHECK(AddSoft(d).rfind("material.density: must be finite and > 0, got 0", 0) == 0);
  d = SoftBox(0.1);
  d.material.stiffnessDamping = -1;
  CHECK(AddSoft(d).rfind("material.stiffness_damping: must be >= 0", 0) == 0);
  d = SoftBox(1e3);
  d.material.density = 1e300;
  CHECK(AddSoft(d) == "mesh: mesh: the mass (density x volume) is not representable in double "
                      "precision");
}

TEST_CASE("bad input: a second actor of the same name is refused, naming the field",
          "[core][bad_input]") {
  Scene scene;
  Error e;
  RigidActorDesc ball;
  ball.name = "ball";
  ball.shape.kind = RigidShapeKind::Sphere;
  ball.shape.radius = 0.1;
  REQUIRE(scene.AddRigidActor(ball, &e).IsValid());
  CHECK_FALSE(scene.AddRigidActor(ball, &e).IsValid());
  CHECK(e.message == "name: duplicate actor name \"ball\" (actor names are unique)");
  SoftActorDesc jelly = SoftBox(0.1);
  jelly.name = "ball";
  CHECK_FALSE(scene.AddSoftActor(jelly, &e).IsValid());
  CHECK(e.message == "name: duplicate actor name \"ball\" (actor names are unique)");
  CHECK(scene.NumActors() == 1);
  jelly.name = "jelly";
  CHECK(scene.AddSoftActor(jelly, &e).IsValid());
}
