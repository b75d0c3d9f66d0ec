// A two-finger prismatic gripper (an articulation: a fixed palm and two fingers sliding along x,
// each a box link driven inward by a force-limited PD drive) holding a 0.2 kg box by friction.
//
// Expectations (explicit normals, BDF2, Δt = 2e-3 s, penalty k = 1e9, V_f = 1e-3 m/s):
//   - each finger squeezes with its drive's force limit F = 10 N (the drive's target lies 2 cm
//     inside the box, k_p Δx = 200 N > F; joint damping, which the limit does not cap, keeps the
//     finger from ringing on the contact): the reported normal force of each finger's pair is F
//     within 1 % while held (measured 1e-8 relative);
//   - with μ = 0.5 the grip's capacity 2 μ F = 10 N exceeds the weight m g = 1.962 N: the box
//     drops less than 2 mm while the grip closes (measured 0.045 mm) and slips less than 1 mm
//     over the next 2 s (t = 0.2 s to 2.2 s; measured 0.21 mm, the creep of the regularized
//     friction), every stage converged; the same in the default dissipation mode (current
//     geometry, reconstructed load: a residual solve; 0.048 mm and 0.21 mm);
//   - with μ = 0.05 the capacity 1.0 N is short of the weight and the box slides down at the
//     Coulomb rate a = g − 2 μ F / m = 4.81 m/s², within 2 % (from its velocities at 0.04 s and
//     0.14 s, sliding at 0.2–0.7 m/s ≫ V_f; measured 4.864, 1.1 %: the sampled faces' pops make
//     the grip force ring by ±2 % as the box's edges cross the finger's sample rows).
#include <catch2/catch.hpp>

#include <cmath>

#include "core/contact/contact_report.h"
#include "core/model/articulated_kind.h"
#include "core/scene.h"

namespace superdex {
namespace {

constexpr double kGrip = 10.0;       // drive force limit [N]
constexpr double kBoxMass = 0.2;     // [kg]
constexpr double kG = 9.81;          // [m/s²]

ContactParams FingerContact(double mu) {
  ContactParams c;
  c.penaltyCoefficient = 1e9;
  c.coulombFrictionCoefficient = mu;
  c.frictionFalloffVel = 1e-3;
  return c;
}

struct Gripper {
  Scene scene;
  ActorHandle gripper, box;

  explicit Gripper(double mu, bool explicitNormals = true) : scene(Settings(explicitNormals)) {
    ArticulatedActorDesc d;
    d.name = "gripper";
    ArticulatedLinkDesc palm;
    palm.name = "palm";
    palm.joint.type = JointType::Fixed;
    palm.joint.origin.p = Eigen::Vector3d(0, 0, 0.4);
    palm.mass = 0.5;
    palm.inertia = Eigen::Matrix3d::Identity() * 1e-3;
    d.links.push_back(palm);
    for (int side = 0; side < 2; ++side) {
      const double sign = side == 0 ? -1.0 : 1.0;  // left at −x, right at +x
      ArticulatedLinkDesc finger;
      finger.name = side == 0 ? "left" : "right";
      finger.joint.type = JointType::Prismatic;
      finger.joint.parent = 0;
      // The finger's centre starts touching the box's face (box half width 0.03, finger 0.01).
      // It reaches 2 cm above the box's top and 8 cm below its bottom (its edges stay clear of
      // the box's faces while it slides).
      finger.joint.origin.p = Eigen::Vector3d(sign * 0.04, 0, -0.13);
      finger.joint.axis = Eigen::Vector3d(-sign, 0, 0);  // positive: inward
      finger.mass = 0.1;
      finger.inertia = Eigen::Vector3d(2.27e-4, 2.17e-4, 1.67e-5).asDiagonal();
      finger.jointParams.driveStiffness = 1e4;
      finger.jointParams.damping = 20.0;  // the saturated drive damps nothing
      finger.jointParams.driveForceLimit = kGrip;
      finger.jointParams.driveTargetPosition = {{0.0, 0.02}};
      LinkShapeDesc shape;
      shape.shape.kind = RigidShapeKind::Box;
      shape.shape.halfExtents = Eigen::Vector3d(0.01, 0.02, 0.08);
      shape.shape.surfaceResolution = 16;
      shape.contact = FingerContact(mu);
      finger.shapes.push_back(shape);
      d.links.push_back(finger);
    }
    Error e;
    gripper = scene.AddArticulatedActor(d, &e);
    INFO(e.message);
    REQUIRE(gripper.IsValid());
    RigidActorDesc b;
    b.name = "box";
    b.shape.kind = RigidShapeKind::Box;
    b.shape.halfExtents = Eigen::Vector3d::Constant(0.03);
    b.shape.surfaceResolution = 8;
    b.mass = kBoxMass;
    b.position = Eigen::Vector3d(0, 0, 0.3);
    b.contact = FingerContact(mu);
    box = scene.AddRigidActor(b, &e);
    REQUIRE(box.IsValid());
  }
  static SceneSettings Settings(bool explicitNormals) {
    SceneSettings s;
    s.eval.explicitNormals = explicitNormals;
    s.gravity = Eigen::Vector3d(0, 0, -kG);
    return s;
  }
  // Steps to time t [s] at Δt = 2e-3 s; false if a stage did not converge.
  bool RunTo(double t) {
    while (scene.Time() < t - 1e-9) {
      StepReport r;
      Error e;
      if (!scene.Step(2e-3, &r, &e) || r.status != StageStatus::Converged) {
        UNSCOPED_INFO("t = " << scene.Time() << ": " << e.message << r.message);
        return false;
      }
    }
    return true;
  }
  double BoxZ() const { return scene.State(box).p.z(); }
  double BoxVz() const { return scene.State(box).v.z(); }
};

}  // namespace

TEST_CASE("a two-finger gripper holds a box by friction", "[core][articulated][attached][gripper]") {
  const bool explicitNormals = GENERATE(true, false);
  INFO("explicit normals " << explicitNormals);
  Gripper g(0.5, explicitNormals);
  REQUIRE(g.RunTo(0.2));
  const double held = g.BoxZ();
  INFO("dropped " << (0.3 - held) * 1e3 << " mm while the grip closed");
  CHECK(0.3 - held < 2e-3);
  // The grip force, from the contact report: each finger's pair carries F along x.
  for (const ContactPairSummary& p : SummarizeContactPairs(g.scene.ContactSamples())) {
    INFO("pair " << p.a << "-" << p.b << " normal force " << p.normalForce.transpose());
    CHECK(std::abs(std::abs(p.normalForce.x()) - kGrip) < 0.01 * kGrip);
  }
  REQUIRE(g.RunTo(2.2));
  const double slip = held - g.BoxZ();
  INFO("slip over 2 s: " << slip * 1e3 << " mm");
  CHECK(std::abs(slip) < 1e-3);
}

TEST_CASE("a gripper with too little friction lets the box slide at the Coulomb rate",
          "[core][articulated][attached][gripper]") {
  const double mu = 0.05;
  Gripper g(mu);
  REQUIRE(g.RunTo(0.04));
  const double v1 = g.BoxVz();
  REQUIRE(g.RunTo(0.14));
  const double v2 = g.BoxVz();
  const double a = -(v2 - v1) / 0.1;
  const double expected = kG - 2.0 * mu * kGrip / kBoxMass;
  INFO("a = " << a << " m/s², Coulomb " << expected << ", v " << v1 << " → " << v2);
  CHECK(std::abs(a - expected) < 0.02 * expected);
}

}  // namespace superdex
