// The cap quadrature of an exact sphere's dissipation (core/contact/sphere_cap.h): the rule's
// geometry, its load integral against the closed form of the penalty (energies/sphere_penalty.h),
// the dissipation it gives through the assembler against the icosphere's at a fine resolution
// with finite-difference checks of the exact potential (explicit normals), and the restitution
// of a dropped ball against the spec's sampled rule at a fine resolution.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "core/contact/kind_contact.h"
#include "core/contact/sphere_cap.h"
#include "core/model/rigid_math.h"
#include "core/scene.h"
#include "derivative_check.h"
#include "energies/sphere_penalty.h"
#include "rigid_pair_eval.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

// λ_n at s = δ − φ (zero for s <= 0).
double Load(double s, const PenaltyParams& p) {
  return s > 0.0 ? NormalPenaltyDensity(p.delta - s, p).lambdaN : 0.0;
}

// The cap's samples in the cap's own frame (toBody = I) about axis e.
std::vector<SurfaceSample> Samples(const SphereCap& cap, double r, const Eigen::Vector3d& e) {
  std::vector<SurfaceSample> out(kSphereCapMaxSamples);
  out.resize(SphereCapSamples(cap, r, e, Eigen::Matrix3d::Identity(), out.data()));
  return out;
}

// A pair's configuration: A now, at x_n and at x⁰; B likewise.
struct Stage {
  RigidBodyModel B;
  bool bDynamic = false;
  RigidPose a, b;
  RigidStageStart aStart, bStart;
};

// The pair's dissipation summed over its stencils, A's samples fed into a FrameEvaluation (the
// pipeline's way, which is where the cap replaces the samples).
test::RigidPairDissipation Dissipation(const RigidBodyModel& A, const Stage& c,
                                       const DissipationSetup& setup, int order) {
  const PairStencils out =
      test::EvaluateRigidPair(A, c.a, &c.aStart, c.B, c.b, &c.bStart, c.bDynamic, setup.penalty,
                              setup.maxAlignment, &setup, order, nullptr, /*streamed=*/true);
  test::RigidPairDissipation d;
  test::SumDissipation(out, c.bDynamic ? 12 : 6, order, &d);
  return d;
}

DissipationSetup Setup(DissipationMode mode) {
  DissipationSetup s;
  s.mode = mode;
  s.dt = 1e-2;
  s.coefficients.mu = 0.5;
  s.coefficients.ct = 0.3;
  s.coefficients.cn = 2.0;
  return s;
}

// A sliding, spinning ball of radius 0.1 m pressed `depth` past δ into B at x_n, moving on
// between x⁰, x_n and now (on a plane tilted about x; on a sphere of radius 0.15 m that moves).
Stage Sliding(bool onSphere, double depth) {
  const PenaltyParams p;
  const double r = 0.1;
  Stage c;
  Eigen::Vector3d n, tangent;
  if (onSphere) {
    c.B = test::SphereModel(0.15, true, SurfaceIntegral::Quadrature, 2);
    c.bDynamic = true;
    c.b.p = Eigen::Vector3d(0.02, -0.01, 0.03);
    c.b.R = ExpSo3(Eigen::Vector3d(0.2, -0.4, 0.1));
    n = Eigen::Vector3d(0.2, 0.3, 1.0).normalized();
  } else {
    c.B = test::BodyModel(test::StaticGround());
    c.b.R = ExpSo3(Eigen::Vector3d(0.3, 0.0, 0.0));
    c.b.p = Eigen::Vector3d(0.1, 0.2, -0.05);
    n = c.b.R * Eigen::Vector3d::UnitZ();
  }
  tangent = n.unitOrthogonal();
  const double reach = onSphere ? r + 0.15 : r;
  RigidPose last;
  last.p = c.b.p + (reach + p.delta - depth) * n;
  last.R = ExpSo3(Eigen::Vector3d(0.5, 0.1, -0.3));
  c.a.p = last.p + 0.004 * tangent - 0.0005 * n;  // sliding 0.4 m/s at Δt = 1e-2
  c.a.R = ExpSo3(Eigen::Vector3d(0.0, 0.03, 0.02)) * last.R;
  c.aStart = test::StartAt(last, last);
  c.aStart.p = last.p - 0.003 * tangent;
  c.bStart = test::StartAt(c.b, c.b);
  if (onSphere) c.bStart.p -= Eigen::Vector3d(0.001, 0.0, 0.0);
  return c;
}

}  // namespace

TEST_CASE("sphere cap: its samples lie on the sphere inside the cap and weigh its area",
          "[core][contact][sphere][quadrature]") {
  const PenaltyParams p;  // ε = 5 mm, δ = 1 mm
  const double r = 0.1;
  const Eigen::Vector3d e = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  struct Case {
    const char* name;
    SphereCap cap;
    int panels;
  };
  const Case cases[] = {
      {"plane, ramp only", PlaneCap(r + p.delta - 0.3 * p.eps, r, 0.0, p), 1},
      {"plane, both panels", PlaneCap(r + p.delta - 4.0 * p.eps, r, 0.0, p), 2},
      {"plane, cut in the linear part", PlaneCap(0.02, r, -0.5, p), 1},
      {"sphere field, both panels", SphereFieldCap(0.25 + p.delta - 3.0 * p.eps, r, 0.15, 0.0, p), 2},
  };
  for (const Case& c : cases) {
    DYNAMIC_SECTION(c.name) {
      const std::vector<SurfaceSample> s = Samples(c.cap, r, e);
      const int n = static_cast<int>(s.size());
      if (c.panels == 2) CHECK(n == kSphereCapMaxSamples);
      else CHECK((n == kCapRampPoints * kCapAzimuths || n == kCapLinearPoints * kCapAzimuths));
      double area = 0.0;
      for (const SurfaceSample& q : s) {
        CHECK(q.normal.norm() == Approx(1.0).epsilon(1e-14));
        CHECK((q.X - r * q.normal).norm() < 1e-15);
        const double t = q.normal.dot(e);
        CHECK(t > c.cap.lo);
        CHECK(t < c.cap.hi);
        CHECK(q.weight > 0.0);
        area += q.weight;
      }
      CHECK(area == Approx(2.0 * M_PI * r * r * (c.cap.hi - c.cap.lo)).epsilon(1e-13));
    }
  }
  CHECK(PlaneCap(r + p.delta + 1e-6, r, 0.0, p).Empty());  // above the threshold: no cap
  CHECK(Samples(PlaneCap(r + p.delta + 1e-6, r, 0.0, p), r, e).empty());
}

TEST_CASE("sphere cap: its load integral is the closed form's force, exactly on a plane",
          "[core][contact][sphere][quadrature]") {
  const PenaltyParams p;
  const double r = 0.1;
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
  SECTION("on a plane: Σ w λ_n = −E'(h), to round-off (λ_n is a polynomial in t per panel)") {
    for (double m : {0.0, -0.5}) {
      for (double depth : {0.3 * p.eps, 1.5 * p.eps, 4.0 * p.eps, 0.09}) {
        const double h = r + p.delta - depth;
        double force = 0.0;
        for (const SurfaceSample& q : Samples(PlaneCap(h, r, m, p), r, n))
          force += q.weight * Load(p.delta - (h + q.X.dot(n)), p);
        const double exact = -SpherePlanePenalty(h, r, m, p).dE;
        INFO("m = " << m << ", depth " << depth);
        CHECK(force == Approx(exact).epsilon(1e-12));
      }
    }
  }
  SECTION("on a sphere's field: Σ w λ_n ∂ρ/∂d = −E'(d) within 1e-4 (s(t) is not polynomial)") {
    const double rB = 0.15;
    for (double depth : {0.3 * p.eps, 1.5 * p.eps, 4.0 * p.eps}) {
      const double d = r + rB + p.delta - depth;
      const Eigen::Vector3d c = d * n;  // A's centre; B's at the origin
      double force = 0.0;
      for (const SurfaceSample& q : Samples(SphereFieldCap(d, r, rB, 0.0, p), r, n)) {
        const double rho = (c + q.X).norm();
        force += q.weight * Load(p.delta - (rho - rB), p) * (c + q.X).dot(n) / rho;
      }
      const double exact = -SphereSpherePenalty(d, r, rB, 0.0, p).dE;
      INFO("depth " << depth << ": " << force << " against " << exact);
      CHECK(force == Approx(exact).epsilon(1e-4));
    }
  }
}

TEST_CASE("sphere cap: the explicit normals' dissipation is the icosphere's at resolution 6, and "
          "an exact potential", "[core][contact][sphere][gradient]") {
  const PenaltyParams p;
  const RigidBodyModel exact = test::SphereModel(0.1, true, SurfaceIntegral::ExactSphere, 2);
  const RigidBodyModel fine = test::SphereModel(0.1, true, SurfaceIntegral::Quadrature, 6);
  const DissipationSetup setup = Setup(DissipationMode::ExplicitNormals);
  for (bool onSphere : {false, true}) {
    for (double depth : {0.6 * p.eps, 3.0 * p.eps}) {
      DYNAMIC_SECTION((onSphere ? "on a moving sphere" : "on a tilted plane") << ", depth "
                                                                             << depth) {
        const Stage c = Sliding(onSphere, depth);
        const test::RigidPairDissipation cap = Dissipation(exact, c, setup, 2);
        const test::RigidPairDissipation ref = Dissipation(fine, c, setup, 1);
        INFO("value " << cap.value << " against " << ref.value << "; residual "
                      << cap.residual.transpose() << " against " << ref.residual.transpose());
        CHECK(cap.activeSamples <= kSphereCapMaxSamples);
        CHECK(cap.value == Approx(ref.value).epsilon(2e-4));
        CHECK((cap.residual - ref.residual).norm() < 2e-4 * ref.residual.norm());
        // The exact potential Δt R of the points fixed at x_n: its gradient and Hessian.
        auto valueAt = [&](const Eigen::VectorXd& d) {
          Stage moved = c;
          test::RetractPair(d, c.bDynamic, &moved.a, &moved.b);
          return Dissipation(exact, moved, setup, 0).value;
        };
        const auto check = test::CheckDerivatives(valueAt, cap.residual, cap.jacobian, 1e-7);
        INFO("gradient error " << check.gradientError << ", Hessian error " << check.hessianError);
        CHECK(check.gradientError < 1e-6);
        CHECK(check.hessianError < 1e-4);
      }
    }
  }
}

TEST_CASE("sphere cap: the default mode's dissipation on a plane is the icosphere's at resolution 6",
          "[core][contact][sphere]") {
  // The reconstructed load φ + G·(Y_n − Y) is φ(Y_n) on a plane: the cap at x_n holds it all.
  const PenaltyParams p;
  const RigidBodyModel exact = test::SphereModel(0.1, true, SurfaceIntegral::ExactSphere, 2);
  const RigidBodyModel fine = test::SphereModel(0.1, true, SurfaceIntegral::Quadrature, 6);
  const DissipationSetup setup = Setup(DissipationMode::ReconstructedLoad);
  for (double depth : {0.6 * p.eps, 3.0 * p.eps}) {
    const Stage c = Sliding(false, depth);
    const test::RigidPairDissipation cap = Dissipation(exact, c, setup, 1);
    const test::RigidPairDissipation ref = Dissipation(fine, c, setup, 1);
    INFO("depth " << depth << ": residual " << cap.residual.transpose() << " against "
                  << ref.residual.transpose());
    CHECK(cap.activeSamples <= kSphereCapMaxSamples);
    CHECK((cap.residual - ref.residual).norm() < 2e-4 * ref.residual.norm());
  }
}

namespace {

// A 1 kg ball of radius 0.1 m (k = 1e9 Pa/m, c_n [s/m]) reaching a plane at the speed of a drop
// from 1 m: its rebound speed over its impact speed once no sample is active (Δt = 5e-5, BDF2).
double Restitution(SurfaceIntegral integral, int resolution, double cn, int mode) {
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BDF2;
  settings.eval = test::EvalParamsForMode(mode);
  Scene scene(settings);
  Error e;
  REQUIRE(scene.AddRigidActor(test::Ground(Eigen::Vector3d::UnitZ(), 1e9, 0.0, cn), &e).IsValid());
  RigidActorDesc ball = test::Ball(0.1, 0.0);
  ball.surfaceIntegral = integral;
  ball.shape.surfaceResolution = resolution;
  ball.contact.normalViscousDampingCoefficient = cn;
  const double v = std::sqrt(2.0 * 9.81 * 1.0);
  ball.position = Eigen::Vector3d(0.01, -0.02, 0.1 + ball.contact.penaltyThresholdDefault + 1e-4);
  ball.linearVelocity = Eigen::Vector3d(0, 0, -v);
  const ActorHandle h = scene.AddRigidActor(ball, &e);
  REQUIRE(h.IsValid());
  bool touched = false;
  for (int i = 0; i < 2000; ++i) {
    StepReport r;
    REQUIRE(scene.Step(5e-5, &r, &e));
    INFO("step " << i << ": " << r.message);
    REQUIRE(r.status == StageStatus::Converged);
    if (r.contact.activeSamples > 0) touched = true;
    else if (touched) return scene.State(h).v.z() / v;
  }
  FAIL("the ball never left the plane");
  return 0.0;
}

}  // namespace

TEST_CASE("sphere cap: a dropped exact ball's restitution is the fine icosphere's within 0.005",
          "[core][contact][sphere][physics][restitution]") {
  for (int mode : {0, 1}) {
    for (double cn : {0.5, 2.0}) {
      const double cap = Restitution(SurfaceIntegral::ExactSphere, 3, cn, mode);
      const double fine = Restitution(SurfaceIntegral::Quadrature, 6, cn, mode);
      INFO(test::kModeNames[mode] << ", c_n = " << cn << ": e = " << cap << " against " << fine);
      CHECK(std::abs(cap - fine) < 0.005);
      CHECK(cap > 0.05);  // a rebound, not a stop (Hunt–Crossley: e ≈ 0.37 and 0.12)
    }
  }
}

TEST_CASE("sphere cap: on a box face its dissipation is the face plane's", "[core][contact][sphere]") {
  // A box whose top face lies on the tilted plane of Sliding: inside the face's region the box's
  // field is the plane's, and so is every term of the explicit normals' dissipation.
  const PenaltyParams p;
  const RigidBodyModel exact = test::SphereModel(0.1, true, SurfaceIntegral::ExactSphere, 2);
  const DissipationSetup setup = Setup(DissipationMode::ExplicitNormals);
  RigidActorDesc box;
  box.name = "box";
  box.dynamic = false;
  box.shape.kind = RigidShapeKind::Box;
  box.shape.halfExtents = Eigen::Vector3d(1.0, 1.0, 0.2);
  for (double depth : {0.6 * p.eps, 3.0 * p.eps}) {
    const Stage onPlane = Sliding(false, depth);
    Stage onBox = onPlane;
    onBox.B = test::BodyModel(box);
    onBox.b.p -= 0.2 * (onPlane.b.R * Eigen::Vector3d::UnitZ());
    onBox.bStart = test::StartAt(onBox.b, onBox.b);
    const test::RigidPairDissipation plane = Dissipation(exact, onPlane, setup, 2);
    const test::RigidPairDissipation face = Dissipation(exact, onBox, setup, 2);
    INFO("depth " << depth);
    CHECK(face.activeSamples == plane.activeSamples);
    CHECK(face.value == Approx(plane.value).epsilon(1e-10));
    CHECK((face.residual - plane.residual).norm() < 1e-10 * plane.residual.norm());
    CHECK((face.jacobian - plane.jacobian).norm() < 1e-10 * plane.jacobian.norm());
  }
}
