// penaltyThresholdExtraPadding (spec, ContactParams): "additional contribution to δ when the
// colliding actor uses None or PointCloud". A soft actor colliding with a grid Sdf of its own
// does not get it.
#include <catch2/catch.hpp>
#include <memory>

#include "core/scene.h"
#include "geometry/tet_mesh.h"
#include "scene_builders.h"

using namespace superdex;

TEST_CASE("the threshold padding applies to a soft colliding actor only without its own collider",
          "[core][contact][soft]") {
  // Ground: δ = 1 mm plus a 4 mm padding. The soft cube's bottom face hovers 3 mm above it:
  // inside δ + padding (5 mm), outside δ.
  for (const ColliderType type : {ColliderType::None, ColliderType::Sdf}) {
    DYNAMIC_SECTION("soft collider " << ToString(type)) {
      Scene scene;
      Error error;
      RigidActorDesc ground = test::StaticGround();
      ground.contact.penaltyThresholdExtraPadding = 0.004;
      REQUIRE(scene.AddRigidActor(ground, &error).IsValid());
      SoftActorDesc d;
      d.name = "soft";
      d.mesh = std::make_shared<TetMesh>(
          MakeTetBox(Eigen::Vector3d::Constant(0.05), Eigen::Vector3i::Constant(2)));
      d.position = Eigen::Vector3d(0, 0, 0.05 + 0.003);
      d.colliderType = type;
      INFO(error.message);
      REQUIRE(scene.AddSoftActor(d, &error).IsValid());
      const ContactStats st = scene.ContactState();
      CHECK(st.minSignedDistance == Approx(0.003).margin(1e-9));
      if (type == ColliderType::None)
        CHECK(st.activeSamples > 0);  // φ = 3 mm < δ + padding = 5 mm
      else
        CHECK(st.activeSamples == 0);  // φ = 3 mm >= δ = 1 mm
    }
  }
}
