// Soft-skinned actors: a tet-mesh soft body whose bound nodes ride on links of an articulated
// skeleton (carried Point parts, core/scene_skin.cpp), the rest free soft nodes; the stage
// reduces the skin's own terms and its contact on the bound nodes into the joints
// (core/dynamics/scene_stage.h).
//
// Expectations:
//   - the stage's gradient and exact Hessian, with a skin bound to two links (a planar joint and
//     a tilted one) pressed into the ground and sliding, equal central differences of the stage
//     value (relative 1e-6 and 1e-5, measured 3.0e-7 and 2.5e-6, as for the same block unbound;
//     explicit normals, an exact potential), its projected Hessian is positive semi-definite,
//     and in the reconstructed-load mode the residual Jacobian equals differences of the
//     residual (5e-9, measured 4.2e-10);
//   - a skin bound wholly to a pendulum's link moves it as a rigid link with the skin's lumped
//     mass distribution added (its mass, centre of mass and second moment, computed here from
//     the node masses): joint angles agree within 1e-9 rad over 1.5 s of 2.1 rad swings under
//     BDF2 and SymplecticDIRK22 (measured 8e-13: the two stages are the same function of the
//     joint, the skin's elasticity flat under rigid motion);
//   - a soft cube hanging from a driven vertical carriage: at rest the drive carries the weight
//     of carriage and skin, k_p (z* − z) = (m_c + m_skin) g (1e-6 relative), and the cube's free
//     nodes sag (0.44 mm) as those of the same cube with its top nodes pinned (1e-7 m; measured
//     6e-17); pressed into the ground by the drive (frictionless, so that the bulging bottom
//     comes to rest), the ground's normal force equals k_p (z − z*) + (m_c + m_skin) g (1e-6
//     relative): the contact traction reaches the joint through the bound nodes;
//   - a skin overlapping its own link's shape exerts no force on it until their pair is enabled;
//   - bad bindings: one error each, naming the field and the rule.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/contact/contact_report.h"
#include "core/model/articulated_kind.h"
#include "core/model/rigid_math.h"
#include "core/scene.h"
#include "ground_plane.h"
#include "stage_derivative_recorder.h"

namespace superdex {
namespace {

constexpr double kG = 9.81;

SoftActorDesc SoftBlock(const std::string& name, const Eigen::Vector3d& half,
                        const Eigen::Vector3i& cells, const Eigen::Vector3d& centre) {
  SoftActorDesc d;
  d.name = name;
  d.mesh = std::make_shared<TetMesh>(MakeTetBox(half, cells));
  d.meshSource = "box";
  d.position = centre;
  d.material.youngsModulus = 2e4;
  d.material.density = 500.0;
  d.contact.penaltyCoefficient = 1e6;
  return d;
}

SkinBinding BoxBinding(const std::string& link, const Eigen::Vector3d& lo,
                       const Eigen::Vector3d& hi) {
  SkinBinding b;
  b.link = link;
  b.hasRegion = true;
  b.regionMin = lo;
  b.regionMax = hi;
  return b;
}

using test::AddGround;

ArticulatedLinkDesc RevoluteLink(const std::string& name, int parent, const Eigen::Vector3d& at,
                                 const Eigen::Vector3d& axis) {
  ArticulatedLinkDesc link;
  link.name = name;
  link.joint.type = JointType::Revolute;
  link.joint.parent = parent;
  link.joint.origin.p = at;
  link.joint.axis = axis;
  link.mass = 0.5;
  link.centerOfMass = Eigen::Vector3d(0.1, 0, 0);
  link.inertia = Eigen::Vector3d(1e-4, 2e-3, 2e-3).asDiagonal();
  return link;
}

// A vertical prismatic carriage of mass 0.2 kg driven to z* with gains k_p = 2000 N/m and
// critical damping.
ArticulatedActorDesc Carriage(double zStar) {
  ArticulatedActorDesc a;
  a.name = "rig";
  ArticulatedLinkDesc link;
  link.name = "carriage";
  link.joint.type = JointType::Prismatic;
  link.joint.axis = Eigen::Vector3d::UnitZ();
  link.mass = 0.2;
  link.inertia = Eigen::Matrix3d::Identity() * 1e-4;
  link.jointParams.driveStiffness = 2000.0;
  link.jointParams.driveDamping = 2.0 * std::sqrt(2000.0 * 0.3);
  link.jointParams.driveTargetPosition = {{0.0, zStar}};
  a.links.push_back(link);
  a.jointPositions = Eigen::VectorXd::Constant(1, zStar);
  return a;
}

}  // namespace

TEST_CASE("soft skin: the stage's gradient and Hessian through the joints",
          "[core][articulated][skin][gradient]") {
  const bool explicitNormals = GENERATE(true, false);
  INFO("explicit normals " << explicitNormals);
  SceneSettings settings;
  settings.eval.explicitNormals = explicitNormals;
  Scene scene(settings);
  AddGround(&scene);
  // Two links along x from a pivot at height z0 (the second about a tilted axis); a soft block
  // under their joint, its top nodes at x = 0.15 bound to the upper link and at x = 0.25 to
  // the lower, its bottom 2 mm into the ground.
  const double z0 = 0.058;
  ArticulatedActorDesc arm;
  arm.name = "arm";
  arm.links.push_back(RevoluteLink("upper", -1, Eigen::Vector3d(0, 0, z0), Eigen::Vector3d::UnitY()));
  arm.links.push_back(RevoluteLink("lower", 0, Eigen::Vector3d(0.2, 0, 0),
                                   Eigen::Vector3d(0.3, 0.954, 0.0).normalized()));
  arm.jointVelocities = Eigen::Vector2d(0.3, -0.5);
  Error e;
  const ActorHandle h = scene.AddArticulatedActor(arm, &e);
  REQUIRE(h.IsValid());
  SoftActorDesc skin = SoftBlock("skin", Eigen::Vector3d(0.05, 0.03, 0.03), Eigen::Vector3i(2, 2, 2),
                                 Eigen::Vector3d(0.2, 0.0, z0 - 0.03));
  skin.linearVelocity = Eigen::Vector3d(0.05, 0.02, 0.0);
  skin.contact.viscousFrictionCoefficient = 1e4;
  skin.contact.normalViscousDampingCoefficient = 0.5;
  skin.skin.push_back(BoxBinding("upper", Eigen::Vector3d(0.14, -1, -1e-3), Eigen::Vector3d(0.16, 1, 1e-3)));
  skin.skin.push_back(BoxBinding("lower", Eigen::Vector3d(0.04, -1, -1e-3), Eigen::Vector3d(0.06, 1, 1e-3)));
  const ActorHandle s = scene.AddSoftActor(skin, &e, h);
  INFO(e.message);
  REQUIRE(s.IsValid());
  CHECK(scene.Carrier(s).index == h.index);
  CHECK_FALSE(scene.IsAttached(s));
  REQUIRE(scene.Kind(s).CarriedParts()->size() == 6);
  // The stiff friction's third derivative puts central differences of 1e-7 steps 1.3e-8 off the
  // residual Jacobian, scaling as the step squared (the same block unbound alike); 1e-8 steps
  // leave 4e-10.
  test::StageDerivativeRecorder rec;
  rec.residualStep = 1e-8;
  StepReport r;
  REQUIRE(scene.Step(1e-3, &r, &e, &rec));
  REQUIRE(rec.checked);
  CHECK(rec.dofs == 2 + 3 * (27 - 6));
  rec.CheckAccuracy(explicitNormals);
}

TEST_CASE("soft skin: a skin bound wholly to a link moves it as the rigid link of its mass",
          "[core][articulated][skin]") {
  const IntegrationMethod method =
      GENERATE(IntegrationMethod::BDF2, IntegrationMethod::SymplecticDIRK22);
  SceneSettings settings;
  settings.integrator = method;
  const Eigen::Vector3d pivot(0, 0, 1), half(0.05, 0.04, 0.03);
  const double q0 = 0.5;
  const Eigen::Matrix3d R0 = Eigen::AngleAxisd(q0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  ArticulatedLinkDesc rod = RevoluteLink("rod", -1, pivot, Eigen::Vector3d::UnitY());
  rod.mass = 0.05;
  rod.centerOfMass = Eigen::Vector3d(0.25, 0, 0);
  rod.inertia = Eigen::Vector3d(1e-5, 1e-3, 1e-3).asDiagonal();
  SoftActorDesc block = SoftBlock("skin", half, Eigen::Vector3i(2, 2, 2), Eigen::Vector3d::Zero());
  // The skin's lumped masses in the link frame (the block centred at (0.5, 0, 0)).
  Scene probe;
  Error e;
  const ActorHandle p = probe.AddSoftActor(block, &e);
  REQUIRE(p.IsValid());
  const SoftBodyModel& m = static_cast<const SoftKind&>(probe.Kind(p)).Model();
  const Eigen::Vector3d at(0.5, 0, 0);
  double M = rod.mass;
  Eigen::Vector3d c = rod.mass * rod.centerOfMass;
  for (int a = 0; a < m.NumNodes(); ++a) {
    M += m.nodeMass[a];
    c += m.nodeMass[a] * (m.rest.vertices[a] + at);
  }
  c /= M;
  auto shift = [](double mass, const Eigen::Vector3d& r) {
    return Eigen::Matrix3d(mass * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose()));
  };
  Eigen::Matrix3d I = rod.inertia + shift(rod.mass, rod.centerOfMass - c);
  for (int a = 0; a < m.NumNodes(); ++a) I += shift(m.nodeMass[a], m.rest.vertices[a] + at - c);
  auto run = [&](bool skinned) {
    Scene scene(settings);
    ArticulatedActorDesc arm;
    arm.name = "pendulum";
    ArticulatedLinkDesc link = rod;
    if (!skinned) {
      link.mass = M;
      link.centerOfMass = c;
      link.inertia = I;
    }
    arm.links.push_back(link);
    arm.jointPositions = Eigen::VectorXd::Constant(1, q0);
    Error err;
    const ActorHandle h = scene.AddArticulatedActor(arm, &err);
    REQUIRE(h.IsValid());
    if (skinned) {
      SoftActorDesc d = block;
      d.position = pivot + R0 * at;
      d.orientation = Eigen::Quaterniond(R0);
      d.skin.push_back(BoxBinding("rod", at - half * 1.1, at + half * 1.1));
      const ActorHandle s = scene.AddSoftActor(d, &err, h);
      INFO(err.message);
      REQUIRE(s.IsValid());
      REQUIRE(scene.Kind(s).FullyCarried());
    }
    const auto& kind = static_cast<const ArticulatedKind&>(scene.Kind(h));
    std::vector<double> angle;
    for (int i = 0; i < 150; ++i) {
      StepReport r;
      REQUIRE(scene.Step(1e-2, &r, &err));
      REQUIRE(r.status == StageStatus::Converged);
      angle.push_back(kind.JointPositions(scene.KindStateOf(h).x)[0]);
    }
    return angle;
  };
  const std::vector<double> skinned = run(true), rigid = run(false);
  double worst = 0.0, swing = 0.0;
  for (size_t i = 0; i < skinned.size(); ++i) {
    worst = std::max(worst, std::abs(skinned[i] - rigid[i]));
    swing = std::max(swing, std::abs(rigid[i] - q0));
  }
  INFO("largest angle difference " << worst << " rad over a swing of " << swing << " rad");
  CHECK(swing > 0.5);
  CHECK(worst < 1e-9);
}

TEST_CASE("soft skin: a driven carriage carries a hanging skin's weight and its contact",
          "[core][articulated][skin]") {
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BackwardEuler;
  const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.03);
  const Eigen::Vector3i cells = Eigen::Vector3i::Constant(3);
  const bool ground = GENERATE(false, true);
  // Hanging: the carriage's target at 0.3 m; on the ground: the cube's bottom would be 10 mm
  // below it at the target (the drive presses it down).
  const double zStar = ground ? 0.05 : 0.3;
  Scene scene(settings);
  if (ground) AddGround(&scene);
  Error e;
  const ActorHandle h = scene.AddArticulatedActor(Carriage(zStar), &e);
  REQUIRE(h.IsValid());
  SoftActorDesc cube = SoftBlock("skin", half, cells, Eigen::Vector3d(0, 0, zStar - 0.03));
  cube.material.stiffnessDamping = 0.01;
  cube.contact.coulombFrictionCoefficient = 0.0;  // no creep of the bulging bottom on the ground
  cube.skin.push_back(BoxBinding("carriage", Eigen::Vector3d(-1, -1, -1e-3), Eigen::Vector3d(1, 1, 1e-3)));
  const ActorHandle s = scene.AddSoftActor(cube, &e, h);
  INFO(e.message);
  REQUIRE(s.IsValid());
  REQUIRE(scene.Kind(s).CarriedParts()->size() == 16);
  for (int i = 0; i < 300; ++i) {
    StepReport r;
    REQUIRE(scene.Step(1e-2, &r, &e));
    REQUIRE(r.status == StageStatus::Converged);
  }
  const auto& kind = static_cast<const ArticulatedKind&>(scene.Kind(h));
  const double z = kind.JointPositions(scene.KindStateOf(h).x)[0];
  const double mSkin = static_cast<const SoftKind&>(scene.Kind(s)).Model().mass;
  const double weight = (0.2 + mSkin) * kG;
  CHECK(scene.KindStateOf(s).v.lpNorm<Eigen::Infinity>() < 1e-6);
  if (!ground) {
    INFO("drive force " << 2000.0 * (zStar - z) << " N, weight " << weight << " N");
    CHECK(std::abs(2000.0 * (zStar - z) - weight) < 1e-6 * weight);
    // The same cube with its top nodes pinned sags alike (relative to its top).
    Scene pinned(settings);
    SoftActorDesc free = SoftBlock("cube", half, cells, Eigen::Vector3d(0, 0, zStar - 0.03));
    free.material.stiffnessDamping = 0.01;
    NodeConstraint top;
    for (int a = 0; a < free.mesh->NumVertices(); ++a)
      if (free.mesh->vertices[a].z() > half.z() - 1e-9) top.nodes.push_back(a);
    free.constraints.push_back(top);
    const ActorHandle f = pinned.AddSoftActor(free, &e);
    REQUIRE(f.IsValid());
    for (int i = 0; i < 300; ++i) {
      StepReport r;
      REQUIRE(pinned.Step(1e-2, &r, &e));
      REQUIRE(r.status == StageStatus::Converged);
    }
    const Eigen::VectorXd& xs = scene.KindStateOf(s).x;
    const Eigen::VectorXd& xf = pinned.KindStateOf(f).x;
    double worst = 0.0;
    for (int a = 0; a < free.mesh->NumVertices(); ++a) {
      const Eigen::Vector3d us = xs.segment<3>(3 * a) - Eigen::Vector3d(0, 0, z);
      const Eigen::Vector3d uf = xf.segment<3>(3 * a) - Eigen::Vector3d(0, 0, zStar);
      worst = std::max(worst, (us - uf).norm());
    }
    const double sag = zStar - 0.06 - xf.segment<3>(0).z();
    INFO("largest difference " << worst << " m; the pinned cube's corner sags " << sag << " m");
    CHECK(std::abs(sag) > 1e-4);
    CHECK(worst < 1e-7);
  } else {
    const std::vector<ContactPairSummary> pairs = SummarizeContactPairs(scene.ContactSamples());
    REQUIRE(pairs.size() == 1);
    const double normal = std::abs(pairs[0].normalForce.z());
    const double expected = 2000.0 * (z - zStar) + weight;
    INFO("ground normal force " << normal << " N, drive and weight " << expected << " N");
    CHECK(z > zStar);
    CHECK(std::abs(normal - expected) < 1e-6 * expected);
  }
}

TEST_CASE("soft skin: no force on its own link's shape until the pair is enabled",
          "[core][articulated][skin]") {
  Scene scene;
  ArticulatedActorDesc rig = Carriage(0.3);
  LinkShapeDesc plate;
  plate.shape.kind = RigidShapeKind::Box;
  plate.shape.halfExtents = Eigen::Vector3d(0.04, 0.04, 0.01);
  plate.contact.penaltyCoefficient = 1e6;
  rig.links[0].shapes.push_back(plate);  // overlaps the skin's top layer
  Error e;
  const ActorHandle h = scene.AddArticulatedActor(rig, &e);
  REQUIRE(h.IsValid());
  SoftActorDesc cube = SoftBlock("skin", Eigen::Vector3d::Constant(0.03), Eigen::Vector3i::Constant(2),
                                 Eigen::Vector3d(0, 0, 0.3 - 0.03));
  cube.skin.push_back(BoxBinding("carriage", Eigen::Vector3d(-1, -1, -1e-3), Eigen::Vector3d(1, 1, 1e-3)));
  const ActorHandle s = scene.AddSoftActor(cube, &e, h);
  REQUIRE(s.IsValid());
  const ActorHandle shape = scene.AttachedActors(h)[0];
  CHECK_FALSE(scene.ContactAllowed(s, shape));
  CHECK(scene.ContactState().activeSamples == 0);
  REQUIRE(scene.EnableActorContactSymmetric(s, shape, true, IncludeNestedActors::No, &e));
  CHECK(scene.ContactState().activeSamples > 0);
  StepReport r;
  REQUIRE(scene.Step(1e-3, &r, &e));
  CHECK(r.status == StageStatus::Converged);
}

TEST_CASE("soft skin: bad bindings are refused with the field and the rule", "[core][skin]") {
  Scene scene;
  Error e;
  ArticulatedActorDesc rig = Carriage(0.3);
  const ActorHandle h = scene.AddArticulatedActor(rig, &e);
  REQUIRE(h.IsValid());
  RigidActorDesc ball;
  ball.name = "ball";
  ball.position = Eigen::Vector3d(1, 0, 0);
  const ActorHandle b = scene.AddRigidActor(ball, &e);
  REQUIRE(b.IsValid());
  const SkinBinding top = BoxBinding("carriage", Eigen::Vector3d(-1, -1, -1e-3), Eigen::Vector3d(1, 1, 1e-3));
  auto refused = [&](SoftActorDesc d, ActorHandle parent, const std::string& part) {
    Error err;
    const ActorHandle a = scene.AddSoftActor(d, &err, parent);
    INFO(err.message);
    CHECK_FALSE(a.IsValid());
    CHECK(err.message.find(part) != std::string::npos);
  };
  const SoftActorDesc cube = SoftBlock("skin", Eigen::Vector3d::Constant(0.03), Eigen::Vector3i::Constant(2),
                                       Eigen::Vector3d(0, 0, 0.27));
  SoftActorDesc d = cube;
  d.skin.push_back(top);
  refused(d, ActorHandle(), "skin: a soft-skinned actor needs its skeleton");
  refused(d, b, "is not an articulated actor");
  d.skin[0].link = "wheel";
  refused(d, h, "skin[0].link: no link named \"wheel\"");
  d = cube;
  d.skin.push_back(top);
  d.skin[0].regionMin.z() = 1.0;
  refused(d, h, "skin[0].region: min must be finite and < max");
  d.skin[0] = top;
  d.skin[0].nodes = {27};
  refused(d, h, "skin[0].nodes: 27 is not a node of the mesh (0 .. 26)");
  d.skin[0] = BoxBinding("carriage", Eigen::Vector3d::Constant(5), Eigen::Vector3d::Constant(6));
  refused(d, h, "skin[0]: binds no node");
  d.skin[0] = top;
  d.skin[0].shapeDistance = 0.01;
  refused(d, h, "skin[0].shape_distance: link \"carriage\" has no collision shape");
  d.skin[0] = top;
  d.constraints.push_back(NodeConstraint{{26}, {}});  // node 26 is on the top face
  refused(d, h, "skin[0]: node 26 is pinned or driven by constraints[0]");
  // Two links: a node bound to both.
  ArticulatedActorDesc two;
  two.name = "two";
  two.links.push_back(RevoluteLink("a", -1, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY()));
  two.links.push_back(RevoluteLink("b", 0, Eigen::Vector3d(0.2, 0, 0), Eigen::Vector3d::UnitY()));
  const ActorHandle t = scene.AddArticulatedActor(two, &e);
  REQUIRE(t.IsValid());
  d = cube;
  d.skin.push_back(top);
  d.skin[0] = BoxBinding("a", Eigen::Vector3d(-1, -1, 0.299), Eigen::Vector3d(1, 1, 0.301));
  d.skin.push_back(d.skin[0]);
  d.skin[1].link = "b";
  refused(d, t, "is bound to link \"a\" by skin[0] already");
  CHECK(scene.NumActors() == 3);  // nothing was added
}

}  // namespace superdex
