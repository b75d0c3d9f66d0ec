// Contact filtering (spec: "Contact Filtering"), table-driven: every control, both directions,
// nested and not, override order, layer-versus-actor precedence; and its effect on contact.
#include <catch2/catch.hpp>

#include "core/scene.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

// Actors: 0 ground (layer "ground"), 1 P (parent), 2 C1 (child of P), 3 C2 (child of P),
// 4 G (child of C1), 5 O (layer "other").
struct Fixture {
  Scene scene;
  ActorHandle ground, P, C1, C2, G, O;
  Fixture() {
    Error e;
    RigidActorDesc g = test::StaticGround(1e6, 0.0);
    g.contactLayer = "ground";
    ground = scene.AddRigidActor(g, &e);
    RigidActorDesc box = test::Cube(1e6, 0.0, 0.0);
    box.name = "P";
    P = scene.AddRigidActor(box, &e);
    box.name = "C1";
    C1 = scene.AddRigidActor(box, &e, P);
    box.name = "C2";
    C2 = scene.AddRigidActor(box, &e, P);
    box.name = "G";
    G = scene.AddRigidActor(box, &e, C1);
    box.name = "O";
    box.contactLayer = "other";
    O = scene.AddRigidActor(box, &e);
    REQUIRE(O.index == 5);
  }
  // The full 6×6 matrix of Allowed(colliding = row, collider = column) as a string of 0/1 rows.
  std::string Matrix() const {
    std::string m;
    for (int a = 0; a < 6; ++a) {
      for (int b = 0; b < 6; ++b) m += scene.ContactAllowed({a}, {b}) ? '1' : '0';
      if (a < 5) m += ' ';
    }
    return m;
  }
};

const std::string kAll = "111111 111111 111111 111111 111111 111111";

// A ground (k = 1e9, frictionless) and a cube resting on it at its equilibrium depth.
void AddRestingCube(Scene* scene, ActorHandle* ground, ActorHandle* cube) {
  Error e;
  *ground = scene->AddRigidActor(test::StaticGround(1e9, 0.0), &e);
  RigidActorDesc box = test::Cube(1e9, 0.0, 0.0);
  box.position = Eigen::Vector3d(0, 0, 0.1000165);
  *cube = scene->AddRigidActor(box, &e);
  REQUIRE(cube->IsValid());
}

}  // namespace

TEST_CASE("contact filter: every control, as a table of allowed ordered pairs", "[core][filter]") {
  Error e;
  SECTION("defaults: everything eligible") { CHECK(Fixture().Matrix() == kAll); }
  SECTION("layer, asymmetric: only default (colliding) against ground (collider)") {
    Fixture f;
    REQUIRE(f.scene.EnableLayerContactAsymmetric("default", "ground", false, &e));
    CHECK(f.Matrix() == "111111 011111 011111 011111 011111 111111");
  }
  SECTION("layer, symmetric: both directions") {
    Fixture f;
    REQUIRE(f.scene.EnableLayerContactSymmetric("default", "ground", false, &e));
    CHECK(f.Matrix() == "100001 011111 011111 011111 011111 111111");
  }
  SECTION("layer against itself") {
    Fixture f;
    REQUIRE(f.scene.EnableLayerContactSymmetric("default", "default", false, &e));
    CHECK(f.Matrix() == "111111 100001 100001 100001 100001 111111");
  }
  SECTION("actor, asymmetric, not nested: the exact ordered pair only") {
    Fixture f;
    REQUIRE(f.scene.EnableActorContactAsymmetric(f.P, f.O, false, IncludeNestedActors::No, &e));
    CHECK(f.Matrix() == "111111 111110 111111 111111 111111 111111");
  }
  SECTION("actor, symmetric, not nested") {
    Fixture f;
    REQUIRE(f.scene.EnableActorContactSymmetric(f.P, f.O, false, IncludeNestedActors::No, &e));
    CHECK(f.Matrix() == "111111 111110 111111 111111 111111 101111");
  }
  SECTION("actor, asymmetric, nested: cross-product of {P, C1, C2, G} and {O}") {
    Fixture f;
    REQUIRE(f.scene.EnableActorContactAsymmetric(f.P, f.O, false, IncludeNestedActors::Yes, &e));
    CHECK(f.Matrix() == "111111 111110 111110 111110 111110 111111");
  }
  SECTION("actor, symmetric, nested, with a nested subtree: {C1, G} and {O}") {
    Fixture f;
    REQUIRE(f.scene.EnableActorContactSymmetric(f.C1, f.O, false, IncludeNestedActors::Yes, &e));
    CHECK(f.Matrix() == "111111 111111 111110 111111 111110 110101");
  }
  SECTION("parent with itself, nested: every pair inside the family, self-pairs included") {
    Fixture f;
    REQUIRE(f.scene.EnableActorContactSymmetric(f.P, f.P, false, IncludeNestedActors::Yes, &e));
    CHECK(f.Matrix() == "111111 100001 100001 100001 100001 111111");
  }
  SECTION("a later setting overrides an earlier one, the automatic adjacent disable included") {
    Fixture f;
    f.scene.DisableAdjacentContact(f.P, f.C1);
    f.scene.DisableAdjacentContact(f.C1, f.G);
    CHECK(f.Matrix() == "111111 110111 101101 111111 110111 111111");
    // Enabling the parent with itself, nested, re-enables the adjacent pairs ...
    REQUIRE(f.scene.EnableActorContactSymmetric(f.P, f.P, true, IncludeNestedActors::Yes, &e));
    CHECK(f.Matrix() == kAll);
    // ... until a later setting disables one again.
    REQUIRE(f.scene.EnableActorContactAsymmetric(f.G, f.C1, false, IncludeNestedActors::No, &e));
    CHECK(f.Matrix() == "111111 111111 111111 111111 110111 111111");
  }
  SECTION("actor pairs cannot re-enable a layer-disabled pair") {
    Fixture f;
    REQUIRE(f.scene.EnableLayerContactSymmetric("default", "other", false, &e));
    REQUIRE(f.scene.EnableActorContactSymmetric(f.P, f.O, true, IncludeNestedActors::Yes, &e));
    CHECK(f.Matrix() == "111111 111110 111110 111110 111110 100001");
    // Re-enabling the layers restores the pairs (the actor gate never disabled them).
    REQUIRE(f.scene.EnableLayerContactSymmetric("default", "other", true, &e));
    CHECK(f.Matrix() == kAll);
  }
  SECTION("changing an actor's layer moves it under the layer gates") {
    Fixture f;
    REQUIRE(f.scene.EnableLayerContactSymmetric("ghost", "ground", false, &e));
    CHECK(f.Matrix() == kAll);
    REQUIRE(f.scene.SetContactLayer(f.O, "ghost", &e));
    CHECK(f.scene.ContactLayer(f.O) == "ghost");
    CHECK(f.Matrix() == "111110 111111 111111 111111 111111 011111");
  }
  SECTION("invalid handles are errors naming the argument") {
    Fixture f;
    CHECK_FALSE(f.scene.EnableActorContactSymmetric(f.P, ActorHandle{17}, false,
                                                     IncludeNestedActors::No, &e));
    CHECK(e.message == "B: invalid actor handle 17");
    CHECK_FALSE(f.scene.SetContactLayer(ActorHandle{-1}, "x", &e));
    CHECK(e.message == "actor: invalid actor handle -1");
    CHECK(f.Matrix() == kAll);
  }
}

TEST_CASE("contact filter: a filtered pair exerts no force", "[core][filter][physics]") {
  // A cube resting on the ground; with ground contact disabled (asymmetric, cube colliding
  // against ground) it falls freely: after 0.1 s it has dropped g t²/2.
  for (bool filtered : {false, true}) {
    Scene scene;
    Error e;
    ActorHandle ground, cube;
    AddRestingCube(&scene, &ground, &cube);
    if (filtered)
      REQUIRE(scene.EnableActorContactAsymmetric(cube, ground, false, IncludeNestedActors::No, &e));
    for (int i = 0; i < 100; ++i) {
      StepReport r;
      REQUIRE(scene.Step(1e-3, &r, &e));
      REQUIRE(r.status == StageStatus::Converged);
    }
    const double drop = 0.1000165 - scene.State(cube).p.z();
    INFO((filtered ? "filtered" : "not filtered") << ": dropped " << drop << " m");
    if (filtered) CHECK(drop == Approx(0.5 * 9.81 * 0.01).epsilon(0.02));
    else CHECK(std::abs(drop) < 1e-6);
  }
}

TEST_CASE("contact filter: a setting changed between steps takes effect at the next evaluation",
          "[core][filter][physics]") {
  // A cube resting on the ground: its contact is found and evaluated, then disabled (the pairs
  // the pipeline keeps from evaluation to evaluation must follow), then enabled again, each
  // by a setting between two evaluations with the boxes unchanged.
  Scene scene;
  Error e;
  ActorHandle ground, cube;
  AddRestingCube(&scene, &ground, &cube);
  CHECK(scene.ContactState().activeSamples > 0);
  REQUIRE(scene.EnableActorContactAsymmetric(cube, ground, false, IncludeNestedActors::No, &e));
  CHECK(scene.ContactState().activeSamples == 0);
  CHECK(scene.ContactState().candidatePairs == 0);
  REQUIRE(scene.EnableActorContactSymmetric(cube, ground, true, IncludeNestedActors::No, &e));
  CHECK(scene.ContactState().activeSamples > 0);
  REQUIRE(scene.SetContactLayer(cube, "c", &e));
  REQUIRE(scene.EnableLayerContactAsymmetric("c", scene.ContactLayer(ground), false, &e));
  CHECK(scene.ContactState().activeSamples == 0);
}
