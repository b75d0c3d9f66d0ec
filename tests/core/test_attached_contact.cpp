// Links in contact: an articulation's collision shapes as attached actors (core/model/
// attached_body_kind.h), whose contact the stage reduces into the joints (core/dynamics/
// scene_stage.h: g = g_real + Aᵀ g_body, H = Pᵀ H_ext P + the chart's curvature).
//
// Expectations:
//   - the stage's gradient and exact Hessian in the joints, with a link box pressed into the
//     ground and a free sphere pressed into the other link, sliding (friction and damping in the
//     explicit-normals mode, an exact potential), equal central differences of the stage value
//     (relative 1e-6 and 1e-5); the projected Hessian is positive semi-definite; in the
//     reconstructed-load mode (a residual) its Jacobian equals differences of the residual
//     (5e-9; measured 7e-10 and 9e-10), for a planar tree and one whose second joint is tilted,
//     with strong viscous friction (c_t = 1e4 s/m): without the trivialization term of the
//     dissipative torque the tilted tree's Jacobian is 2.9e-8 off;
//   - a box on a vertical prismatic joint comes to rest on a plane (Backward Euler, 3 s at
//     Δt = 1e-2 s) with the ground's normal force equal to its weight (1e-6 relative) and at the
//     height a free rigid box of the same shape and mass settles to (within 1e-5 m: the free box
//     still rocks on its faces' one-way triangulations, 1.3e-6 m apart measured);
//   - attached actors follow their carriers: their configuration is the link frame's, and they
//     are refused a state of their own;
//   - adjacent links whose shapes overlap at their joint exert no force on each other (no active
//     pair, joints at rest after 10 steps); enabling their pair afterwards (the spec's actor-
//     contact override) brings the force back (both passes active, the joints set moving).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include <Eigen/Eigenvalues>

#include "core/contact/contact_report.h"
#include "core/dynamics/stage_recorder.h"
#include "core/model/articulated_kind.h"
#include "core/model/rigid_math.h"
#include "core/scene.h"
#include "ground_plane.h"
#include "stage_derivative_recorder.h"

namespace superdex {
namespace {

LinkShapeDesc BoxShape(const Eigen::Vector3d& half, const Eigen::Vector3d& at) {
  LinkShapeDesc s;
  s.shape.kind = RigidShapeKind::Box;
  s.shape.halfExtents = half;
  s.shape.surfaceResolution = 4;
  s.position = at;
  s.contact.penaltyCoefficient = 1e6;
  return s;
}

using test::AddGround;

}  // namespace

TEST_CASE("links in contact: the stage's gradient and Hessian through the joints",
          "[core][articulated][attached][gradient]") {
  // Explicit normals (an exact potential: gradient and Hessian), and the reconstructed load (a
  // residual: its Jacobian), the second joint about y or tilted towards x (a non-planar tree).
  const bool explicitNormals = GENERATE(true, false);
  const bool tilted = GENERATE(false, true);
  INFO("explicit normals " << explicitNormals << ", tilted " << tilted);
  SceneSettings settings;
  settings.eval.explicitNormals = explicitNormals;
  Scene scene(settings);
  AddGround(&scene);
  {  // strong viscous friction, on the ground too (a pair takes the geometric mean): the residual
     // modes' dissipative torque on the link bodies then shows in their Jacobian (without the
     // ½ Aᵀ[τ_d]×A term of core/dynamics/scene_stage.cpp the tilted tree's is 2.9e-8 off)
    ContactParams c = scene.GetContactParams({0});
    c.viscousFrictionCoefficient = 1e4;
    Error e;
    REQUIRE(scene.SetContactParams({0}, c, &e));
  }
  // Two revolute links about y, the first level from a pivot at height z0, the second at its
  // end turned down by 1.2 rad, so that its box's lowest edge,
  // z0 − 0.2 sin 1.2 − 0.02 cos 1.2 = z0 − 0.1936 m, is 2 mm into the ground.
  // Tilted (the second joint about (0.3, 0.954, 0)), its lowest corner is 0.1907 m below the
  // first joint: z0 = 0.1887 m puts it 2 mm into the ground.
  const double z0 = tilted ? 0.1887 : 0.1916;
  ArticulatedActorDesc arm;
  arm.name = "arm";
  for (int l = 0; l < 2; ++l) {
    ArticulatedLinkDesc link;
    link.name = l == 0 ? "upper" : "lower";
    link.joint.type = JointType::Revolute;
    link.joint.parent = l - 1;
    link.joint.origin.p = l == 0 ? Eigen::Vector3d(0, 0, z0) : Eigen::Vector3d(0.2, 0, 0);
    link.joint.axis = l == 1 && tilted ? Eigen::Vector3d(0.3, 0.954, 0.0).normalized()
                                        : Eigen::Vector3d::UnitY();
    link.mass = 0.5;
    link.centerOfMass = Eigen::Vector3d(0.1, 0, 0);
    link.inertia = Eigen::Vector3d(1e-4, 2e-3, 2e-3).asDiagonal();
    LinkShapeDesc box = BoxShape(Eigen::Vector3d(0.1, 0.02, 0.02), Eigen::Vector3d(0.1, 0, 0));
    box.contact.penaltyCoefficient = 1e8;
    box.contact.viscousFrictionCoefficient = 1e4;  // [s/m]
    box.contact.normalViscousDampingCoefficient = 0.5;
    link.shapes.push_back(box);
    arm.links.push_back(link);
  }
  arm.jointPositions = Eigen::Vector2d(0.0, 1.2);
  arm.jointVelocities = Eigen::Vector2d(0.3, -0.5);
  Error e;
  const ActorHandle h = scene.AddArticulatedActor(arm, &e);
  INFO(e.message);
  REQUIRE(h.IsValid());
  REQUIRE(scene.AttachedActors(h).size() == 2);
  // A free sphere resting on the upper link's box, moving.
  RigidActorDesc ball;
  ball.name = "ball";
  ball.shape.radius = 0.03;
  ball.shape.surfaceResolution = 2;
  ball.mass = 0.1;
  ball.position = Eigen::Vector3d(0.08, 0.0, z0 + 0.02 + 0.03 - 0.002);
  ball.linearVelocity = Eigen::Vector3d(0.1, 0.05, 0.0);
  ball.contact.penaltyCoefficient = 1e6;
  ball.contact.viscousFrictionCoefficient = 0.2;
  REQUIRE(scene.AddRigidActor(ball, &e).IsValid());
  test::StageDerivativeRecorder rec;
  StepReport r;
  REQUIRE(scene.Step(1e-3, &r, &e, &rec));
  REQUIRE(rec.checked);
  CHECK(rec.dofs == 2 + 6);
  rec.CheckAccuracy(explicitNormals);
}

TEST_CASE("links in contact: a link on a vertical slider rests where a free box rests",
          "[core][articulated][attached]") {
  const Eigen::Vector3d half(0.05, 0.05, 0.05);
  // Backward Euler damps the bounce out (BDF2 keeps the free box rocking at 1e-5 m after 3 s).
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BackwardEuler;
  auto rest = [&](bool articulated) {
    Scene scene(settings);
    AddGround(&scene);
    Error e;
    ActorHandle h;
    if (articulated) {
      ArticulatedActorDesc slider;
      slider.name = "slider";
      ArticulatedLinkDesc link;
      link.name = "block";
      link.joint.type = JointType::Prismatic;
      link.joint.axis = Eigen::Vector3d::UnitZ();
      link.mass = 1.0;
      link.inertia = Eigen::Matrix3d::Identity() * (1.0 / 6.0) * 0.01;
      link.shapes.push_back(BoxShape(half, Eigen::Vector3d::Zero()));
      slider.links.push_back(link);
      slider.jointPositions = Eigen::VectorXd::Constant(1, 0.06);
      h = scene.AddArticulatedActor(slider, &e);
    } else {
      RigidActorDesc box;
      box.name = "block";
      box.shape.kind = RigidShapeKind::Box;
      box.shape.halfExtents = half;
      box.shape.surfaceResolution = 4;
      box.mass = 1.0;
      box.position = Eigen::Vector3d(0, 0, 0.06);
      box.contact = BoxShape(half, Eigen::Vector3d::Zero()).contact;
      h = scene.AddRigidActor(box, &e);
    }
    INFO(e.message);
    REQUIRE(h.IsValid());
    for (int i = 0; i < 300; ++i) {
      StepReport r;
      REQUIRE(scene.Step(1e-2, &r, &e));
      REQUIRE(r.status == StageStatus::Converged);
    }
    if (articulated) {  // at rest, the ground carries the link's weight through its shape
      const std::vector<ContactPairSummary> pairs = SummarizeContactPairs(scene.ContactSamples());
      REQUIRE(pairs.size() == 1);
      CHECK(pairs[0].b == scene.AttachedActors(h)[0].index);
      CHECK(std::abs(-pairs[0].normalForce.z() - 9.81) < 1e-6 * 9.81);
      CHECK(scene.KindStateOf(h).v.norm() < 1e-9);
    }
    return scene.CenterOfMass(h).z();
  };
  const double free = rest(false), joint = rest(true);
  INFO("free box " << free << " m, on the slider " << joint << " m");
  CHECK(joint < 0.05);  // below its half height: the penalty holds it
  // The free box is not quite at rest: its faces' triangulations (all diagonals one way) tilt it
  // by 2.4e-6 rad and it still moves at 3e-4 m/s after 3 s; its height agrees within 1.3e-6 m.
  CHECK(std::abs(free - joint) < 1e-5);
}

TEST_CASE("links in contact: attached actors follow their carrier", "[core][articulated][attached]") {
  Scene scene;
  ArticulatedActorDesc arm;
  arm.name = "arm";
  ArticulatedLinkDesc link;
  link.name = "link";
  link.joint.type = JointType::Revolute;
  link.joint.axis = Eigen::Vector3d::UnitZ();
  link.centerOfMass = Eigen::Vector3d(0.1, 0, 0);
  link.shapes.push_back(BoxShape(Eigen::Vector3d(0.1, 0.01, 0.01), Eigen::Vector3d(0.15, 0, 0)));
  arm.links.push_back(link);
  arm.jointPositions = Eigen::VectorXd::Constant(1, 0.5);
  Error e;
  const ActorHandle h = scene.AddArticulatedActor(arm, &e);
  REQUIRE(h.IsValid());
  const std::vector<ActorHandle> bodies = scene.AttachedActors(h);
  REQUIRE(bodies.size() == 1);
  CHECK(scene.ActorName(bodies[0]) == "arm/link");
  CHECK(scene.Parent(bodies[0]).index == h.index);
  // The box centre is 0.15 m along the link turned by 0.5 rad about z.
  const Eigen::Vector3d expected(0.15 * std::cos(0.5), 0.15 * std::sin(0.5), 0.0);
  CHECK((scene.KindStateOf(bodies[0]).x.head<3>() - expected).norm() < 1e-12);
  KindState s = scene.KindStateOf(bodies[0]);
  CHECK_FALSE(scene.SetKindState(bodies[0], s, &e));
  CHECK(e.message.find("attached") != std::string::npos);
  // A shape that cannot be built names the link and the shape.
  arm.name = "bad";
  arm.links[0].shapes[0].shape.halfExtents.x() = -1.0;
  CHECK_FALSE(scene.AddArticulatedActor(arm, &e).IsValid());
  CHECK(e.message.find("link 0 ('link'): shapes[0].") != std::string::npos);
}

}  // namespace superdex

namespace superdex {

TEST_CASE("links in contact: adjacent links overlap without force until their pair is enabled",
          "[core][articulated][attached]") {
  // Two links in a row about z (no gravity); the second link's box reaches 2 cm back over the
  // first's, which ends at their joint, and sits 1.5 cm to its side: they overlap there by
  // 2 cm along the links and 5 mm across, so that the pair pushes them apart across the links
  // (a torque on both joints).
  SceneSettings settings;
  settings.gravity = Eigen::Vector3d::Zero();
  settings.eval.explicitNormals = true;
  Scene scene(settings);
  ArticulatedActorDesc arm;
  arm.name = "arm";
  for (int l = 0; l < 2; ++l) {
    ArticulatedLinkDesc link;
    link.name = l == 0 ? "a" : "b";
    link.joint.type = JointType::Revolute;
    link.joint.parent = l - 1;
    link.joint.origin.p = l == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.1, 0, 0);
    link.joint.axis = Eigen::Vector3d::UnitZ();
    link.mass = 0.2;
    link.centerOfMass = Eigen::Vector3d(0.05, 0, 0);
    link.inertia = Eigen::Vector3d(1e-5, 2e-4, 2e-4).asDiagonal();
    link.shapes.push_back(BoxShape(Eigen::Vector3d(0.05, 0.01, 0.01),
                                   Eigen::Vector3d(l == 0 ? 0.05 : 0.03, l == 0 ? 0.0 : 0.015, 0)));
    arm.links.push_back(link);
  }
  Error e;
  const ActorHandle h = scene.AddArticulatedActor(arm, &e);
  REQUIRE(h.IsValid());
  const std::vector<ActorHandle> bodies = scene.AttachedActors(h);
  REQUIRE(bodies.size() == 2);
  CHECK_FALSE(scene.ContactAllowed(bodies[0], bodies[1]));
  CHECK_FALSE(scene.ContactAllowed(bodies[1], bodies[0]));
  auto jointSpeed = [&] {
    const auto& kind = static_cast<const ArticulatedKind&>(scene.Kind(h));
    return kind.JointVelocities(scene.KindStateOf(h)).norm();
  };
  for (int i = 0; i < 10; ++i) {
    StepReport r;
    REQUIRE(scene.Step(1e-2, &r, &e));
    REQUIRE(r.status == StageStatus::Converged);
    CHECK(r.contact.activePairs == 0);
  }
  CHECK(jointSpeed() == 0.0);
  // The spec's override: an actor-contact setting after creation brings the pair back.
  REQUIRE(scene.EnableActorContactSymmetric(bodies[0], bodies[1], true, IncludeNestedActors::No,
                                            &e));
  CHECK(scene.ContactAllowed(bodies[0], bodies[1]));
  StepReport r;
  REQUIRE(scene.Step(1e-2, &r, &e));
  CHECK(r.contact.activePairs == 2);
  CHECK(jointSpeed() > 1e-3);
  // Disabling the articulation with its nested actors against itself removes them again.
  REQUIRE(scene.EnableActorContactSymmetric(h, h, false, IncludeNestedActors::Yes, &e));
  CHECK_FALSE(scene.ContactAllowed(bodies[0], bodies[1]));
}

}  // namespace superdex
