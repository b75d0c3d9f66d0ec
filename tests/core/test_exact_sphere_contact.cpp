// SurfaceIntegral::ExactSphere (core/model/enums.h): a sphere's penalty integrated exactly against
// a plane's or a sphere's field, through the contact assembler (FrameEvaluation) as the pipeline
// evaluates it: its value is the closed form's, its gradient and Hessian on [δp_A, δθ_A (, δp_B,
// δθ_B)] pass the finite-difference check through both retractions, its sampled dissipation is
// untouched, and a resting sphere sits at the analytic height.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "core/contact/kind_contact.h"
#include "core/model/rigid_kind.h"
#include "core/model/rigid_math.h"
#include "core/scene.h"
#include "derivative_check.h"
#include "energies/sphere_penalty.h"
#include "rigid_pair_eval.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

RigidBodyModel Build(RigidShapeKind kind, double radius, bool dynamic, SurfaceIntegral integral) {
  if (kind == RigidShapeKind::Sphere) return test::SphereModel(radius, dynamic, integral, 2);
  RigidActorDesc d;
  d.name = "a";
  d.dynamic = dynamic;
  d.shape.kind = kind;
  return test::BodyModel(d);
}

struct Pair {
  RigidBodyModel A, B;
  RigidPose a, b;
  bool bDynamic = false;
};

// The pair's stencils with A's samples fed straight into a FrameEvaluation (the pipeline's way).
PairStencils Evaluate(const Pair& c, const PenaltyParams& p, double m, int order,
                      std::vector<ContactSampleRecord>* records = nullptr) {
  return test::EvaluateRigidPair(c.A, c.a, nullptr, c.B, c.b, nullptr, c.bDynamic, p, m, nullptr,
                                 order, records, /*streamed=*/true);
}

double ValueAt(Pair c, const PenaltyParams& p, double m, const Eigen::VectorXd& d) {
  test::RetractPair(d, c.bDynamic, &c.a, &c.b);
  return Evaluate(c, p, m, 0).penaltyValue;
}

void CheckDerivatives(const Pair& c, const PenaltyParams& p, double m, double exactValue) {
  INFO("exact value " << exactValue);
  const PairStencils r = Evaluate(c, p, m, 2);
  REQUIRE(r.count == 1);
  CHECK(r.activeSamples == 1);
  // The same closed form at a height formed from the poses in another order: round-off only.
  CHECK(r.penaltyValue == Approx(exactValue).epsilon(1e-9));
  const ContactStencil& st = r.stencils[0];
  const auto check = test::CheckDerivatives(
      [&](const Eigen::VectorXd& d) { return ValueAt(c, p, m, d); },
      Eigen::VectorXd(st.penaltyGradient), Eigen::MatrixXd(st.penaltyHessian), 1e-6);
  INFO("gradient error " << check.gradientError << ", Hessian error " << check.hessianError);
  CHECK(check.gradientError < 1e-5);
  CHECK(check.hessianError < 1e-4);
  CHECK(st.penaltyGradient.segment<3>(3).norm() == 0.0);  // no torque on a sphere
}

// E'(d) of a sphere on a sphere's field (negative where they press: the force −E' pushes apart).
double SphereSphereNormalForceSign(double d, double rA, double rB, const PenaltyParams& p) {
  return SphereSpherePenalty(d, rA, rB, 0.0, p).dE;
}

// A 1 kg exact ball of radius 0.1 m (c_n = 2 s/m) dropped from height z [m] above the origin
// onto `support` (static, at the origin): its position after 2 s at Δt = 5e-3 (BDF2).
Eigen::Vector3d RestingPosition(const RigidActorDesc& support, double z) {
  Scene scene;
  Error e;
  REQUIRE(scene.AddRigidActor(support, &e).IsValid());
  RigidActorDesc ball = test::Ball(0.1, 0.0);
  ball.surfaceIntegral = SurfaceIntegral::ExactSphere;
  ball.position = Eigen::Vector3d(0, 0, z);
  ball.contact.normalViscousDampingCoefficient = 2.0;
  const ActorHandle h = scene.AddRigidActor(ball, &e);
  REQUIRE(h.IsValid());
  for (int i = 0; i < 400; ++i) {
    StepReport rep;
    REQUIRE(scene.Step(5e-3, &rep, &e));
    REQUIRE(rep.status == StageStatus::Converged);
  }
  return scene.State(h).p;
}

}  // namespace

TEST_CASE("an exact sphere's penalty through the assembler: the closed form and its derivatives",
          "[core][contact][sphere][gradient]") {
  PenaltyParams p;
  p.k = 1e5;  // keeps the differences well conditioned; nothing depends on k
  std::mt19937 rng(11);
  std::normal_distribution<double> n01;
  auto rot = [&]() { return ExpSo3(Eigen::Vector3d(n01(rng), n01(rng), n01(rng))); };
  const double r = 0.1;
  for (double depth : {0.3 * p.eps, 1.5 * p.eps, 4.0 * p.eps}) {  // past δ: ramp, both, linear
    DYNAMIC_SECTION("on a tilted plane, depth " << depth) {
      Pair c{Build(RigidShapeKind::Sphere, r, true, SurfaceIntegral::ExactSphere),
             Build(RigidShapeKind::Plane, 0.0, false, SurfaceIntegral::Quadrature), {}, {}, false};
      c.b.R = rot();
      c.b.p = Eigen::Vector3d(0.3, -0.2, 0.1);
      const Eigen::Vector3d n = c.b.R * Eigen::Vector3d::UnitZ();
      const double h = r + p.delta - depth;
      c.a.R = rot();
      c.a.p = c.b.p + h * n + 0.2 * n.unitOrthogonal();
      CheckDerivatives(c, p, 0.0, SpherePlanePenalty(h, r, 0.0, p).E);
    }
    DYNAMIC_SECTION("on a moving sphere, depth " << depth) {
      Pair c{Build(RigidShapeKind::Sphere, r, true, SurfaceIntegral::ExactSphere),
             Build(RigidShapeKind::Sphere, 0.15, true, SurfaceIntegral::Quadrature), {}, {}, true};
      c.a.R = rot();
      c.b.R = rot();
      const double d = r + 0.15 + p.delta - depth;
      c.b.p = c.a.p + Eigen::Vector3d(0.05, 0.2, 0.1).normalized() * d;
      CheckDerivatives(c, p, 0.35, SphereSpherePenalty(d, r, 0.15, 0.35, p).E);
    }
  }
}

TEST_CASE("an exact sphere on a box face is the plane's closed form, near an edge its samples",
          "[core][contact][sphere]") {
  PenaltyParams p;
  const double r = 0.1;
  RigidActorDesc bd;
  bd.name = "box";
  bd.dynamic = false;
  bd.shape.kind = RigidShapeKind::Box;
  bd.shape.halfExtents = Eigen::Vector3d(0.5, 0.4, 0.1);
  Pair box{Build(RigidShapeKind::Sphere, r, true, SurfaceIntegral::ExactSphere),
           test::BodyModel(bd), {}, {}, false};
  const double h = r - 0.002;  // the centre's height over the face
  SECTION("inside the top face's region") {
    box.a.p = Eigen::Vector3d(0.01, 0.02, 0.1 + h);
    const PairStencils exact = Evaluate(box, p, 0.0, 0);
    CHECK(exact.activeSamples == 1);
    CHECK(exact.penaltyValue == Approx(SpherePlanePenalty(h, r, 0.0, p).E).epsilon(1e-12));
  }
  SECTION("on the -y face of a turned box") {
    box.b.R = ExpSo3(Eigen::Vector3d(0.2, -0.1, 0.4));
    box.b.p = Eigen::Vector3d(0.3, 0.1, -0.2);
    box.a.p = box.b.p + box.b.R * Eigen::Vector3d(0.1, -0.4 - h, 0.0);
    const PairStencils exact = Evaluate(box, p, 0.0, 0);
    CHECK(exact.activeSamples == 1);
    CHECK(exact.penaltyValue == Approx(SpherePlanePenalty(h, r, 0.0, p).E).epsilon(1e-9));
  }
  SECTION("its cap reaching past an edge: the samples") {
    // The cap's radius √(2 r s) ≈ 2.4 cm at s = 3 mm: 2 cm from the edge it crosses it.
    box.a.p = Eigen::Vector3d(0.48, 0.0, 0.1 + h);
    CHECK(Evaluate(box, p, 0.0, 0).activeSamples > 1);
  }
  SECTION("derivatives on a moving box's face, through both retractions") {
    box.bDynamic = true;
    box.b.R = ExpSo3(Eigen::Vector3d(-0.3, 0.2, 0.1));
    box.a.p = box.b.R * Eigen::Vector3d(-0.1, 0.05, 0.1 + h);
    CheckDerivatives(box, p, 0.0, SpherePlanePenalty(h, r, 0.0, p).E);
  }
}

TEST_CASE("an exact sphere reports one record for its cap", "[core][contact][sphere]") {
  PenaltyParams p;
  const double r = 0.1;
  Pair plane{Build(RigidShapeKind::Sphere, r, true, SurfaceIntegral::ExactSphere),
             Build(RigidShapeKind::Plane, 0.0, false, SurfaceIntegral::Quadrature), {}, {},
             false};
  plane.a.p = Eigen::Vector3d(0, 0, r - 0.002);
  std::vector<ContactSampleRecord> records;
  const PairStencils exact = Evaluate(plane, p, 0.0, 0, &records);
  REQUIRE(records.size() == 1);
  const SpherePenalty e0 = SpherePlanePenalty(r - 0.002, r, 0.0, p);
  // Its traction times its area is the whole force −E' n, at the deepest point.
  CHECK((records[0].traction * records[0].weight - Eigen::Vector3d(0, 0, -e0.dE)).norm() <
        1e-12 * std::abs(e0.dE));
  CHECK(records[0].position.z() == Approx(-0.002).margin(1e-15));
  CHECK(records[0].phi == Approx(-0.002).margin(1e-15));
  CHECK(exact.penaltyValue == Approx(e0.E).epsilon(1e-12));
}

TEST_CASE("an exact sphere sunk past its radius into a sphere's field falls back to its samples",
          "[core][contact][sphere]") {
  // Centres closer than A's radius: outside the closed form's domain (d > r_A). A's surface
  // there faces away from B's centre (s_al = 1), so only m = 1 keeps its samples.
  PenaltyParams p;
  Pair c{Build(RigidShapeKind::Sphere, 0.1, true, SurfaceIntegral::ExactSphere),
         Build(RigidShapeKind::Sphere, 0.03, true, SurfaceIntegral::Quadrature), {}, {}, true};
  c.b.p = Eigen::Vector3d(0.08, 0.0, 0.0);
  const PairStencils r = Evaluate(c, p, 1.0, 2);
  CHECK(r.activeSamples > 1);  // the samples, one by one
  CHECK(std::isfinite(r.penaltyValue));
  CHECK(r.penaltyValue > 0.0);
}

TEST_CASE("an exact sphere rests at the analytic height on a plane and on a sphere",
          "[core][contact][sphere][physics]") {
  // Static equilibrium: the total force 2π r W(s) at the deepest penetration s = δ − φ_min
  // (on a plane; on a sphere the ρ-weighted integral) balances m g. The height is solved here
  // from W alone by bisection, the simulation reaches it from a drop of 1 mm.
  const PenaltyParams p;  // k = 1e9, ε = 5 mm, δ = 1 mm: the defaults
  const double r = 0.1, g = 9.81, mass = 1.0;
  auto bisect = [](auto&& f, double lo, double hi) {  // f(lo) < 0 < f(hi)
    for (int k = 0; k < 200; ++k) {
      const double mid = 0.5 * (lo + hi);
      (f(mid) < 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  auto W = [&](double s) { return NormalPenaltyDensity(p.delta - s, p).W; };
  SECTION("on a plane") {
    const double s = bisect([&](double x) { return 2.0 * M_PI * r * W(x) - mass * g; }, 0.0, 0.05);
    const double restHeight = r + p.delta - s;
    const Eigen::Vector3d rest = RestingPosition(test::StaticGround(1e9, 0.0), restHeight + 1e-3);
    INFO("rest height " << rest.z() << ", analytic " << restHeight);
    CHECK(std::abs(rest.z() - restHeight) < 1e-6);
  }
  SECTION("on a fixed sphere") {
    // The balance −E'(d) = m g of the closed form (checked against a surface quadrature and
    // finite differences in tests/energies/test_sphere_penalty.cpp).
    const double rB = 0.15;
    const double d = bisect(
        [&](double x) { return mass * g + SphereSphereNormalForceSign(x, r, rB, p); },
        r + rB + p.delta - 0.05, r + rB + p.delta);
    const Eigen::Vector3d rest = RestingPosition(test::FixedSphere(rB), d + 1e-3);
    INFO("rest height " << rest.z() << ", analytic " << d);
    CHECK(std::abs(rest.z() - d) < 1e-6);
    CHECK(rest.head<2>().norm() < 1e-9);
  }
}
