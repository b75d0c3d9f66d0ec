// Scenes shared by the sensitivity and adjoint tests, solved to tight tolerances (the derivative
// of the discrete map is defined at the converged stage solutions).
#pragma once

#include <catch2/catch.hpp>

#include "core/model/articulated_kind.h"
#include "core/scene.h"
#include "core/sensitivity/sensitivity.h"
#include "scene_builders.h"

namespace superdex::test {

/// The named parameters of `scene` ("ACTOR.NAME"); a test failure naming the one that is wrong.
inline std::vector<SceneParameter> ParseParameters(const Scene& scene,
                                                   const std::vector<std::string>& names) {
  std::vector<SceneParameter> out(names.size());
  Error error;
  for (size_t j = 0; j < names.size(); ++j) {
    INFO(names[j] << ": " << error.message);
    REQUIRE(ParseSceneParameter(scene, names[j], &out[j], &error));
  }
  return out;
}

inline SceneSettings TightSettings(IntegrationMethod method, DissipationMode mode) {
  SceneSettings s;
  s.integrator = method;
  s.eval.explicitNormals = mode == DissipationMode::ExplicitNormals;
  s.eval.implicitNormalForceForDissipation = mode == DissipationMode::ImplicitLoad;
  s.solver.absoluteTolerance = 1e-18;
  s.solver.relativeTolerance = 1e-14;
  s.solver.stepTolerance = 1e-14;
  return s;
}

// A 0.2 m, 1 kg box resting 0.5 mm into the ground, sliding along x at 0.5 m/s (μ = 0.5 on both,
// c_n = 1 s/m on both, c_t = 0.2 s/m on the box and the ground).
inline Scene SlidingBox(IntegrationMethod method, DissipationMode mode) {
  Scene scene(TightSettings(method, mode));
  Error error;
  RigidActorDesc ground = Ground(Eigen::Vector3d::UnitZ(), 1e7, 0.5, 1.0);
  ground.contact.viscousFrictionCoefficient = 0.2;
  REQUIRE(scene.AddRigidActor(ground, &error).IsValid());
  RigidActorDesc box = Cube(1e7, 0.5, 1.0);
  box.contact.viscousFrictionCoefficient = 0.2;
  box.position = Eigen::Vector3d(0, 0, 0.1 - 5e-4);
  box.linearVelocity = Eigen::Vector3d(0.5, 0, 0);
  REQUIRE(scene.AddRigidActor(box, &error).IsValid());
  return scene;
}

// The box of SlidingBox at rest, pushed along x by an applied force of 8 N (μ m g = 4.9 N): it
// accelerates at F/m − μ g, so its path depends on its mass.
inline Scene PushedBox(IntegrationMethod method, DissipationMode mode) {
  Scene scene(TightSettings(method, mode));
  Error error;
  RigidActorDesc ground = Ground(Eigen::Vector3d::UnitZ(), 1e7, 0.5, 1.0);
  REQUIRE(scene.AddRigidActor(ground, &error).IsValid());
  RigidActorDesc box = Cube(1e7, 0.5, 1.0);
  box.position = Eigen::Vector3d(0, 0, 0.1 - 5e-4);
  box.appliedForce = {{0.0, Eigen::Vector3d(8, 0, 0)}};
  REQUIRE(scene.AddRigidActor(box, &error).IsValid());
  return scene;
}

// The box of SlidingBox as a link "block" of an articulation "slider": a massless carriage on a
// vertical slider carries it on a second joint (`second`, axis `axis`, the block's centre and
// shape `out` along x in its frame, joint rate `rate`), its shape 0.5 mm into the ground; the
// ground carries its weight through its attached shape ("slider/block").
inline Scene LinkOnCarriage(IntegrationMethod method, DissipationMode mode, JointType second,
                            const Eigen::Vector3d& axis, double out, double rate) {
  Scene scene(TightSettings(method, mode));
  Error error;
  RigidActorDesc ground = Ground(Eigen::Vector3d::UnitZ(), 1e7, 0.5, 1.0);
  ground.contact.viscousFrictionCoefficient = 0.2;
  REQUIRE(scene.AddRigidActor(ground, &error).IsValid());
  const RigidActorDesc cube = Cube(1e7, 0.5, 1.0);
  ArticulatedActorDesc d;
  d.name = "slider";
  ArticulatedLinkDesc carriage;
  carriage.name = "carriage";
  carriage.joint.type = JointType::Prismatic;
  carriage.joint.axis = Eigen::Vector3d::UnitZ();
  carriage.mass = 0.0;
  carriage.inertia.setZero();
  d.links.push_back(carriage);
  ArticulatedLinkDesc block;
  block.name = "block";
  block.joint.type = second;
  block.joint.parent = 0;
  block.joint.axis = axis;
  block.mass = 1.0;
  block.centerOfMass = Eigen::Vector3d(out, 0, 0);
  block.inertia = Eigen::Matrix3d::Identity() * (1.0 / 6.0) * 0.04;
  LinkShapeDesc shape;
  shape.shape = cube.shape;
  shape.position = Eigen::Vector3d(out, 0, 0);
  shape.contact = cube.contact;
  shape.contact.viscousFrictionCoefficient = 0.2;
  block.shapes.push_back(shape);
  d.links.push_back(block);
  d.jointPositions = Eigen::Vector2d(0.1 - 5e-4, 0.0);
  d.jointVelocities = Eigen::Vector2d(0.0, rate);
  REQUIRE(scene.AddArticulatedActor(d, &error).IsValid());
  return scene;
}

// A driven, damped pendulum "pendulum" (link "bob": 1 kg, 0.5 m below a revolute pivot about y at
// `pivot`, joint damping 0.3 N·m·s/rad, PD drive k_p = 20 N·m/rad, k_d = 2 N·m·s/rad towards
// 0.4 rad) released at 0.1 rad with 1 rad/s.
inline ArticulatedActorDesc DrivenPendulumDesc(const Eigen::Vector3d& pivot) {
  ArticulatedActorDesc d;
  d.name = "pendulum";
  ArticulatedLinkDesc bob;
  bob.name = "bob";
  bob.joint.type = JointType::Revolute;
  bob.joint.axis = Eigen::Vector3d::UnitY();
  bob.joint.origin.p = pivot;
  bob.mass = 1.0;
  bob.centerOfMass = Eigen::Vector3d(0, 0, -0.5);
  bob.inertia = Eigen::Matrix3d::Identity() * 1e-3;
  bob.jointParams.damping = 0.3;
  bob.jointParams.driveStiffness = 20.0;
  bob.jointParams.driveDamping = 2.0;
  bob.jointParams.driveTargetPosition = {{0.0, 0.4}};
  d.links.push_back(bob);
  d.jointPositions = Eigen::VectorXd::Constant(1, 0.1);
  d.jointVelocities = Eigen::VectorXd::Constant(1, 1.0);
  return d;
}

// The driven pendulum alone, its pivot 1 m up; no contact.
inline Scene DrivenPendulum(IntegrationMethod method) {
  Scene scene(TightSettings(method, DissipationMode::ExplicitNormals));
  Error error;
  REQUIRE(scene.AddArticulatedActor(DrivenPendulumDesc(Eigen::Vector3d(0, 0, 1)), &error).IsValid());
  return scene;
}

// Sliding along x at 0.5 m/s on a second prismatic joint.
inline Scene SlidingLink(IntegrationMethod method, DissipationMode mode) {
  return LinkOnCarriage(method, mode, JointType::Prismatic, Eigen::Vector3d::UnitX(), 0.0, 0.5);
}

// Turning at 1.5 rad/s on a revolute joint about z, 0.3 m out: it slides on a circle, and its
// contact reaches the joints through a chart that turns with them.
inline Scene TurningLink(IntegrationMethod method, DissipationMode mode) {
  return LinkOnCarriage(method, mode, JointType::Revolute, Eigen::Vector3d::UnitZ(), 0.3, 1.5);
}

// The box dropped from 2 cm, tilted, with normal damping: impact, bounce, settle.
inline Scene BouncingBox(IntegrationMethod method, DissipationMode mode) {
  Scene scene(TightSettings(method, mode));
  Error error;
  REQUIRE(scene.AddRigidActor(Ground(Eigen::Vector3d::UnitZ(), 1e7, 0.3, 2.0), &error)
              .IsValid());
  RigidActorDesc box = Cube(1e7, 0.3, 2.0);
  box.position = Eigen::Vector3d(0, 0, 0.13);
  box.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 1, 0).normalized()));
  box.linearVelocity = Eigen::Vector3d(0.3, 0, -0.5);
  REQUIRE(scene.AddRigidActor(box, &error).IsValid());
  return scene;
}

// A soft cube (2 × 2 × 2 cells, 0.1 m, E = 1e5 Pa) dropped 1 cm onto the ground, moving sideways.
// The same cube with its centre at height z [m], moving sideways at vx [m/s], the ground's
// friction coefficient mu (the cube's 0.5; combined √(0.5 mu)).
inline Scene SoftCubeOnGround(IntegrationMethod method, DissipationMode mode, double z, double vx,
                              double mu) {
  Scene scene(TightSettings(method, mode));
  Error error;
  REQUIRE(scene.AddRigidActor(Ground(Eigen::Vector3d::UnitZ(), 1e7, mu, 1.0), &error)
              .IsValid());
  SoftActorDesc d;
  d.name = "soft";
  d.mesh = std::make_shared<TetMesh>(
      MakeTetBox(Eigen::Vector3d::Constant(0.05), Eigen::Vector3i::Constant(2)));
  d.position = Eigen::Vector3d(0, 0, z);
  d.linearVelocity = Eigen::Vector3d(vx, 0, 0);
  d.material.youngsModulus = 1e5;
  d.material.poissonRatio = 0.3;
  d.material.density = 1000.0;
  d.contact.penaltyCoefficient = 1e7;
  d.contact.normalViscousDampingCoefficient = 1.0;
  REQUIRE(scene.AddSoftActor(d, &error).IsValid());
  return scene;
}

// A 0.1 × 0.1 × 0.05 m, 0.5 kg rigid box set down on a soft slab (0.3 × 0.3 × 0.05 m, 3 × 3 × 1
// cells, E = 1e5 Pa, its bottom nodes pinned), sliding along x at vx [m/s]; μ = √(0.5 mu) between
// them, penalty 1e7 Pa/m, c_n = 1 s/m. The slab's surface samples meet the box's SDF; with
// `slabCollider` the box's samples also meet the slab's own grid SDF (core/contact/tet_field.h).
inline Scene BoxOnSoftSlab(IntegrationMethod method, DissipationMode mode, double vx, double mu,
                           bool slabCollider = false) {
  Scene scene(TightSettings(method, mode));
  Error error;
  SoftActorDesc slab;
  slab.name = "slab";
  slab.mesh = std::make_shared<TetMesh>(
      MakeTetBox(Eigen::Vector3d(0.15, 0.15, 0.025), Eigen::Vector3i(3, 3, 1)));
  std::vector<int> bottom;
  for (int i = 0; i < slab.mesh->NumVertices(); ++i)
    if (slab.mesh->vertices[i].z() < -0.0249) bottom.push_back(i);
  slab.constraints.push_back({bottom, {}});
  slab.material.youngsModulus = 1e5;
  slab.material.poissonRatio = 0.3;
  slab.material.density = 1000.0;
  slab.contact.penaltyCoefficient = 1e7;
  slab.contact.coulombFrictionCoefficient = mu;
  slab.contact.normalViscousDampingCoefficient = 1.0;
  if (slabCollider) slab.colliderType = ColliderType::Sdf;
  REQUIRE(scene.AddSoftActor(slab, &error).IsValid());
  RigidActorDesc box = Cube(1e7, 0.5, 1.0);
  box.name = "box";
  box.shape.halfExtents = Eigen::Vector3d(0.05, 0.05, 0.025);
  box.mass = 0.5;
  box.position = Eigen::Vector3d(0, 0, 0.025 + 0.025 - 1e-4);
  box.linearVelocity = Eigen::Vector3d(vx, 0, 0);
  REQUIRE(scene.AddRigidActor(box, &error).IsValid());
  return scene;
}

inline Scene SoftCube(IntegrationMethod method) {
  return SoftCubeOnGround(method, DissipationMode::ReconstructedLoad, 0.06, 0.3, 0.5);
}

}  // namespace superdex::test
