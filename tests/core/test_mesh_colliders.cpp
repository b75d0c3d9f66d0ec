// The same drop against a static sphere described by an analytic Sphere, an exact Mesh
// (icosphere) and a grid Sdf collider: rebound heights within 1% of each other.
#include <catch2/catch.hpp>

#include "core/scene.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

// A 0.2 m, 1 kg cube (k = 1e6 Pa/m, frictionless, undamped) dropped flat from 0.2 m onto the top
// of a static sphere of radius 0.5 m. Returns the highest point of the first rebound [m].
double Rebound(ColliderType type, std::string* notes) {
  SceneSettings settings;
  Scene scene(settings);
  Error e;
  RigidActorDesc ball;
  ball.name = "ball";
  ball.dynamic = false;
  ball.shape.kind = RigidShapeKind::Sphere;
  ball.shape.radius = 0.5;
  ball.shape.surfaceResolution = 4;  // the Mesh and Sdf colliders' icosphere
  ball.colliderType = type;
  ball.contact.penaltyCoefficient = 1e6;
  ball.gridSdf.resolutionMode = GridSdfResolutionMode::BoundingExtent;
  ball.gridSdf.resolutionDelta = 0.5;
  REQUIRE(scene.AddRigidActor(ball, &e).IsValid());
  RigidActorDesc cube = test::Cube(1e6, 0.0, 0.0);
  cube.position = Eigen::Vector3d(0, 0, 0.5 + 0.1 + 0.2);
  REQUIRE(scene.AddRigidActor(cube, &e).IsValid());
  for (const auto& n : scene.Notices()) *notes += n + "; ";
  bool touched = false, left = false;
  double top = 0.0;
  for (int i = 0; i < 20000; ++i) {
    StepReport r;
    REQUIRE(scene.Step(2e-4, &r, &e));
    REQUIRE(r.status == StageStatus::Converged);
    const double z = scene.State(ActorHandle{1}).p.z();
    if (r.contact.activeSamples > 0) touched = true;
    else if (touched) left = true;
    if (left) {
      if (scene.State(ActorHandle{1}).v.z() < 0) return top;
      top = std::max(top, z);
    }
  }
  FAIL("no rebound apex");
  return 0.0;
}

}  // namespace

TEST_CASE("Sphere, Mesh and Sdf colliders give the same rebound within 1%",
          "[core][colliders][mesh]") {
  std::string notes;
  const double sphere = Rebound(ColliderType::Sphere, &notes);
  const double mesh = Rebound(ColliderType::Mesh, &notes);
  const double sdf = Rebound(ColliderType::Sdf, &notes);
  const double drop = 0.2;  // rebound heights above the contact point
  const double base = 0.5 + 0.1;
  INFO("apex above contact: sphere " << sphere - base << ", mesh " << mesh - base << ", sdf "
                                     << sdf - base << " m (dropped from " << drop << " m); "
                                     << notes);
  CHECK(std::abs((mesh - base) - (sphere - base)) < 0.01 * (sphere - base));
  CHECK(std::abs((sdf - base) - (sphere - base)) < 0.01 * (sphere - base));
  CHECK(sphere - base > 0.5 * drop);  // it did bounce
  WARN("rebound apex above contact: sphere " << sphere - base << ", mesh " << mesh - base
                                              << ", sdf " << sdf - base << " m; " << notes);
}
