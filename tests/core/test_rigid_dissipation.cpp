#include <catch2/catch.hpp>
#include <random>

#include "core/contact/rigid_dissipation.h"
#include "core/model/rigid_math.h"
#include "derivative_check.h"
#include "rigid_pair_eval.h"

using namespace superdex;
using test::EvaluateRigidPairDissipation;
using test::EvaluateRigidPairPenalty;
using test::RigidPairDissipation;
using test::RigidPairPenalty;

namespace {

RigidBodyModel Build(RigidShape shape, bool dynamic) {
  RigidActorDesc d;
  d.name = "a";
  d.dynamic = dynamic;
  d.shape = shape;
  RigidBodyModel m;
  RigidBodyState s;
  Error e;
  REQUIRE(BuildRigidBody(d, "", &m, &s, &e));
  return m;
}

RigidShape Box(Eigen::Vector3d h, int res) {
  RigidShape s;
  s.kind = RigidShapeKind::Box;
  s.halfExtents = h;
  s.surfaceResolution = res;
  return s;
}

RigidStageStart StartOf(const RigidPose& p) {
  RigidStageStart s;
  s.p = p.p;
  s.R = p.R;
  s.Rinv = p.R.inverse();
  s.last = p;
  return s;
}

/// The pair setup the derivative and culling cases share: Δt = 0.01 s, k = 1e5 Pa/m,
/// μ = 0.5, c_t = 0.2 s/m, c_n = 1.5 s/m, V_f = 0.01 m/s, aligned contacts accepted (m = 0).
DissipationSetup CaseSetup(DissipationMode mode) {
  DissipationSetup setup;
  setup.dt = 0.01;
  setup.mode = mode;
  setup.penalty.k = 1e5;
  setup.coefficients = {0.5, 0.2, 1.5, 0.01};
  setup.maxAlignment = 0.0;
  return setup;
}

struct Case {
  RigidBodyModel A, B;
  RigidPose a, b;        // current
  RigidStageStart a0, b0;// stage start
  bool bDynamic = false;
  DissipationSetup setup;
};

RigidPose Retracted(const RigidPose& p, const Eigen::VectorXd& d, int o) {
  RigidPose q = p;
  q.p += d.segment<3>(o);
  q.R = ExpSo3(d.segment<3>(o + 3)) * q.R;
  return q;
}

RigidPairDissipation Eval(const Case& c, const Eigen::VectorXd& d, int order) {
  RigidPairDissipation out;
  const RigidPose a = Retracted(c.a, d, 0);
  const RigidPose b = c.bDynamic ? Retracted(c.b, d, 6) : c.b;
  EvaluateRigidPairDissipation(c.A, a, c.a0, c.B, b, c.b0, c.bDynamic, c.setup, order, &out);
  return out;
}

void CheckCase(const Case& c) {
  const int n = c.bDynamic ? 12 : 6;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const RigidPairDissipation out = Eval(c, zero, 2);
  REQUIRE(out.activeSamples > 0);
  CHECK(out.maxCoulombRatio <= 1.0 + 1e-12);
  if (c.setup.mode == DissipationMode::ExplicitNormals) {
    // Exact potential: residual = ∇(Δt Σ w R), Jacobian = its Hessian.
    const auto check = test::CheckDerivatives(
        [&](const Eigen::VectorXd& d) { return Eval(c, d, 0).value; },
        Eigen::VectorXd(out.residual), Eigen::MatrixXd(out.jacobian), 1e-6);
    INFO("gradient error " << check.gradientError << ", Hessian error " << check.hessianError);
    CHECK(check.gradientError < 1e-6);
    CHECK(check.hessianError < 1e-4);
  } else {
    // Not a potential: the Jacobian is checked against differences of the residual itself.
    const Eigen::MatrixXd Jfd = FiniteDifferenceJacobian(
        [&](const Eigen::VectorXd& d) { return Eigen::VectorXd(Eval(c, d, 1).residual); }, zero,
        1e-7);
    const double err = (Eigen::MatrixXd(out.jacobian) - Jfd).norm() / Jfd.norm();
    INFO("Jacobian error " << err);
    CHECK(err < 1e-5);
    // And it is not symmetric (the residual is not a gradient) once friction acts.
    CHECK((Jfd - Jfd.transpose()).norm() > 1e-6 * Jfd.norm());
  }
  if (c.bDynamic) {
    // Balanced pair: forces sum to zero and torques about the origin sum to zero.
    const Eigen::Vector3d fA = out.residual.segment<3>(0), fB = out.residual.segment<3>(6);
    const Eigen::Vector3d tA = out.residual.segment<3>(3), tB = out.residual.segment<3>(9);
    CHECK((fA + fB).norm() < 1e-12 * fA.norm());
    CHECK((c.a.p.cross(fA) + tA + c.b.p.cross(fB) + tB).norm() < 1e-11 * fA.norm());
  }
}

/// w ∂(J_Yᵀ f)/∂δ of one sample with plain matrix products: the stencil rows
/// [df; [r]× df − [f]× dr; −df; [f]× dd − [d]× df], dr = [0, −[r]×, 0, 0],
/// dd = [I, −[r]×, −I, 0] (δ = [δp_A, δθ_A, δp_B, δθ_B]; with a static B the first 6 × 6 block).
void AddForceJacobianRows(const Eigen::Vector3d& r, const Eigen::Vector3d& d,
                          const Eigen::Vector3d& f, const Eigen::Matrix<double, 3, 12>& df,
                          bool bDynamic, double w, PairMatrix* J) {
  const Eigen::Matrix3d Sr = Skew(r), Sd = Skew(d), Sf = Skew(f);
  if (!bDynamic) {
    const Eigen::Matrix<double, 3, 6> dfA = df.leftCols<6>();
    J->block<3, 6>(0, 0) += w * dfA;
    J->block<3, 6>(3, 0) += w * Sr * dfA;
    J->block<3, 3>(3, 3) += w * Sf * Sr;
    return;
  }
  Eigen::Matrix<double, 3, 12> dr, dd;
  dr << Eigen::Matrix3d::Zero(), -Sr, Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero();
  dd << Eigen::Matrix3d::Identity(), -Sr, -Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Zero();
  J->block<3, 12>(0, 0) += w * df;
  J->block<3, 12>(3, 0) += w * (Sr * df - Sf * dr);
  J->block<3, 12>(6, 0) -= w * df;
  J->block<3, 12>(9, 0) += w * (Sf * dd - Sd * df);
}

}  // namespace

TEST_CASE("PairForceJacobianSums: a pair's summed force Jacobian equals the per-sample one",
          "[core][dissipation]") {
  // 40 samples of one pair with the current-mode kernel's df (rigid_dissipation.h) built per
  // sample in world coordinates and assembled row by row with plain products, against the moments
  // summed in B's frame: the same sums regrouped, equal to rounding.
  std::mt19937 rng(17);
  std::normal_distribution<double> n01;
  auto vec = [&]() { return Eigen::Vector3d(n01(rng), n01(rng), n01(rng)); };
  auto mat = [&]() {
    Eigen::Matrix3d M;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) M(i, j) = n01(rng);
    return M;
  };
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Matrix3d RB = ExpSo3(vec());
    const Eigen::Vector3d c = 2.0 * vec();  // p_A − p_B
    for (bool bDynamic : {false, true}) {
      const int n = bDynamic ? 12 : 6;
      PairMatrix reference = PairMatrix::Zero(), summed = PairMatrix::Zero();
      PairForceJacobianSums sums(bDynamic);
      for (int k = 0; k < 40; ++k) {
        const Eigen::Vector3d rB = 0.3 * vec(), nB = vec().normalized(), g = 1e3 * vec();
        const Eigen::Matrix3d GY = 1e6 * mat(), GN = 1e3 * mat();  // not symmetric
        const double w = std::abs(n01(rng)) * 1e-3;
        const Eigen::Vector3d r = RB * rB, d = c + r, f = RB * g;
        const Eigen::Matrix3d RBGY = RB * GY * RB.transpose();
        const Eigen::Matrix3d RBGN = RB * GN * RB.transpose() * Skew(RB * nB);
        Eigen::Matrix<double, 3, 12> df;
        df << RBGY, -RBGY * Skew(r) - RBGN, -RBGY, RBGY * Skew(d) + RBGN - Skew(f);
        AddForceJacobianRows(r, d, f, df, bDynamic, w, &reference);
        sums.Add(rB, nB, g, GY, GN, w);
      }
      sums.AddTo(RB, c, &summed);
      INFO("trial " << trial << (bDynamic ? ", dynamic B" : ", static B"));
      const double scale = reference.topLeftCorner(n, n).norm();
      CHECK((summed - reference).topLeftCorner(n, n).norm() <= 1e-13 * scale);
      if (!bDynamic) CHECK(summed.bottomRows(6).norm() == 0.0);
      PairMatrix shifted = PairMatrix::Zero();  // a wrong lever arm is visible
      sums.AddTo(RB, c + Eigen::Vector3d(0, 1e-3, 0), &shifted);
      if (bDynamic) CHECK((shifted - reference).topLeftCorner(n, n).norm() > 1e-8 * scale);
    }
  }
}

TEST_CASE("rigid pair dissipation: derivatives in every mode, both friction branches",
          "[core][gradient][dissipation]") {
  std::mt19937 rng(11);
  std::normal_distribution<double> n01;
  auto smallRot = [&](double s) {
    return ExpSo3(s * Eigen::Vector3d(n01(rng), n01(rng), n01(rng)));
  };
  const DissipationMode modes[3] = {DissipationMode::ExplicitNormals,
                                    DissipationMode::ReconstructedLoad,
                                    DissipationMode::ImplicitLoad};
  for (DissipationMode mode : modes) {
    for (double slip : {0.004, 0.3}) {  // below and above V_f = 0.01 m/s
      for (bool dynamicCollider : {false, true}) {
        for (bool colliderNormal : {true, false}) {
          Case c;
          c.A = Build(Box({0.1, 0.08, 0.06}, 2), true);
          c.B = Build(Box({0.5, 0.4, 0.2}, 1), dynamicCollider);
          c.bDynamic = dynamicCollider;
          c.b.R = smallRot(0.3);
          c.b.p = Eigen::Vector3d(0.02, -0.01, 0.0);
          // A rests slightly tilted on B's top face, penetrating a little.
          c.a.R = c.b.R * smallRot(0.05);
          c.a.p = c.b.p + c.b.R * Eigen::Vector3d(0.05, 0.03, 0.2 + 0.06 - 0.003);
          // Stage start: A displaced tangentially (slip·Δt) and normally, B a little rotated.
          c.setup = CaseSetup(mode);
          c.setup.frictionWithColliderNormal = colliderNormal;
          RigidPose a0 = c.a, b0 = c.b;
          a0.p -= c.b.R * Eigen::Vector3d(slip * c.setup.dt, 0.3 * slip * c.setup.dt, 0.002);
          a0.R = smallRot(0.01) * a0.R;
          if (dynamicCollider) b0.R = smallRot(0.01) * b0.R;
          c.a0 = StartOf(a0);
          c.b0 = StartOf(b0);
          DYNAMIC_SECTION(ToString(mode) << " slip " << slip << (dynamicCollider ? " dynamic" : " static")
                                         << (colliderNormal ? " N_B" : " -N_A")) {
            CheckCase(c);
          }
        }
      }
    }
  }
}

TEST_CASE("rigid pair dissipation: derivatives on every alignment branch",
          "[core][gradient][dissipation]") {
  // Fading on with m = 0 and m = 0.5, fading off (a = 1), and m = −1 (a = 1 by the spec's
  // m > −1 rule; every sample with s > −1 rejected): a box tilted by 0.2 rad so that its bottom
  // and side samples have distinct alignments.
  const DissipationMode modes[3] = {DissipationMode::ExplicitNormals,
                                    DissipationMode::ReconstructedLoad,
                                    DissipationMode::ImplicitLoad};
  struct Branch { double m; bool fade; const char* name; };
  const Branch branches[4] = {{0.0, true, "fade m=0"}, {0.5, true, "fade m=0.5"},
                              {0.0, false, "no fade"}, {-1.0, true, "m=-1"}};
  for (DissipationMode mode : modes) {
    for (const Branch& br : branches) {
      Case c;
      c.A = Build(Box({0.1, 0.1, 0.1}, 2), true);
      RigidShape plane;
      plane.kind = RigidShapeKind::Plane;
      c.B = Build(plane, false);
      c.a.R = ExpSo3(Eigen::Vector3d(0.0, 0.2, 0.05));
      c.a.p = Eigen::Vector3d(0, 0, 0.1 * (std::cos(0.2) + std::sin(0.2)) - 0.004);
      c.setup = CaseSetup(mode);
      c.setup.maxAlignment = br.m;
      c.setup.fadeFriction = br.fade;
      RigidPose a0 = c.a;
      a0.p -= Eigen::Vector3d(0.003, 0.001, 0.001);
      c.a0 = StartOf(a0);
      c.b0 = StartOf(c.b);
      if (br.m == -1.0) {
        CHECK(Eval(c, Eigen::VectorXd::Zero(6), 1).activeSamples == 0);
        continue;
      }
      DYNAMIC_SECTION(ToString(mode) << " " << br.name) { CheckCase(c); }
    }
  }
}

TEST_CASE("rigid pair dissipation: alignment rejection and fading", "[core][dissipation]") {
  Case c;
  c.A = Build(Box({0.1, 0.1, 0.1}, 1), true);
  RigidShape plane;
  plane.kind = RigidShapeKind::Plane;
  c.B = Build(plane, false);
  c.a.p = Eigen::Vector3d(0, 0, 0.1 - 0.002);
  c.setup.dt = 0.01;
  c.setup.penalty.k = 1e5;
  c.setup.coefficients = {0.5, 0.0, 0.0, 0.01};
  c.setup.mode = DissipationMode::ImplicitLoad;
  RigidPose a0 = c.a;
  a0.p.x() -= 0.001;  // sliding at 0.1 m/s along +x
  c.a0 = StartOf(a0);
  c.b0 = StartOf(c.b);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  // Bottom-face samples: s = G·N_A = −1 → a = (m − s)/(m + 1) = 1 at m = 0. The friction force
  // is μ times the normal force of the same samples.
  RigidPairDissipation full = Eval(c, zero, 1);
  RigidPairPenalty pen;
  PenaltyParams pp = c.setup.penalty;
  EvaluateRigidPairPenalty(c.A, c.a, c.B, c.b, false, pp, 1, &pen, 0.0);
  REQUIRE(full.activeSamples > 0);
  CHECK(full.residual[0] == Approx(0.5 * std::abs(pen.gradient[2])).epsilon(1e-12));
  // Tilt the box by 60° about y: the faces that reach the plane have normals with
  // s = −cos 60° = −0.5 (bottom face) and s = −cos 30° ≈ −0.866 (+x face).
  c.a.R = ExpSo3(Eigen::Vector3d(0, M_PI / 3, 0));
  a0.R = c.a.R;
  a0.p = c.a.p + Eigen::Vector3d(-0.001, 0, 0);
  c.a0 = StartOf(a0);
  c.setup.maxAlignment = -0.9;  // s > m everywhere: every sample rejected
  REQUIRE(Eval(c, zero, 1).activeSamples == 0);
  c.setup.maxAlignment = -0.6;  // only the +x face's samples remain
  const int plusX = Eval(c, zero, 1).activeSamples;
  CHECK(plusX > 0);
  c.setup.maxAlignment = 0.0;
  CHECK(Eval(c, zero, 1).activeSamples > plusX);  // accepted with factor 0.5 (and the edge region's own normals)
  c.setup.fadeFriction = false;
  const double unfaded = Eval(c, zero, 1).residual.norm();
  c.setup.fadeFriction = true;
  const double faded = Eval(c, zero, 1).residual.norm();
  CHECK(faded < unfaded);
  CHECK(faded > 0.0);
}

TEST_CASE("rigid pair dissipation: a plane's reconstructed-load culling keeps every loaded sample",
          "[core][dissipation]") {
  // The reconstructed load φ + G·(Y_n − Y) of a plane is Φ(Y_n), so its samples are culled by the
  // last actual pose alone; a box collider's flat top face gives the same φ, G and ∇²Φ = 0 there
  // but is culled by the general bound φ − L|Y_n − Y|. A tilted box that slid 6 cm and turned
  // 0.3 rad during the stage (most of its samples inside that bound, few loaded), resting in the
  // plane or lifted 2 mm off it since the last pose, must get the same residual and Jacobian from
  // both (to the rounding of the box field's z + 5 − 5 against the plane's z).
  RigidShape plane;
  plane.kind = RigidShapeKind::Plane;
  for (DissipationMode mode : {DissipationMode::ReconstructedLoad, DissipationMode::ImplicitLoad}) {
    for (double lift : {0.0, 0.002}) {
      Case c;
      c.A = Build(Box({0.1, 0.1, 0.1}, 3), true);
      c.B = Build(plane, false);
      c.a.R = ExpSo3(Eigen::Vector3d(0.0, 0.15, 0.1));
      c.a.p = Eigen::Vector3d(0.1, 0.05, 0.1 * (std::cos(0.15) + std::sin(0.15)) - 0.003 + lift);
      c.setup = CaseSetup(mode);
      RigidPose last = c.a;
      last.R = ExpSo3(Eigen::Vector3d(0.0, 0.3, 0.0)) * c.a.R;
      last.p += Eigen::Vector3d(-0.06, 0.02, -lift);
      c.a0 = StartOf(last);
      c.b0 = StartOf(c.b);
      Case boxCase = c;
      boxCase.B = Build(Box({5.0, 5.0, 5.0}, 1), false);
      boxCase.b.p = Eigen::Vector3d(0, 0, -5.0);  // top face at z = 0
      boxCase.b0 = StartOf(boxCase.b);
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
      const RigidPairDissipation onPlane = Eval(c, zero, 2), onBox = Eval(boxCase, zero, 2);
      DYNAMIC_SECTION(ToString(mode) << " lifted " << lift) {
        REQUIRE(onBox.activeSamples > 0);
        CHECK(onPlane.activeSamples == onBox.activeSamples);
        CHECK(onPlane.value == Approx(onBox.value).epsilon(1e-9));
        CHECK((onPlane.residual - onBox.residual).norm() <= 1e-9 * onBox.residual.norm());
        CHECK((onPlane.jacobian - onBox.jacobian).norm() <= 1e-9 * onBox.jacobian.norm());
      }
    }
  }
}

TEST_CASE("rigid pair dissipation: the sample tree's culling keeps every sample the samples' own "
          "tests keep",
          "[core][dissipation]") {
  // Two balls of 960 samples each in the current-geometry modes: A grazes B now and was 4 cm to
  // the side (and turned) at the last actual pose, so the stage's motion is large against the
  // contact cap — the pile's landing. The tree (leaves of 16 samples, culled by the reach of B and by the
  // reconstructed-load bound) must give what one leaf holding every sample gives, bit for bit:
  // the same samples summed in the same order.
  RigidShape ball;
  ball.kind = RigidShapeKind::Sphere;
  ball.radius = 0.05;
  ball.surfaceResolution = 2;
  for (DissipationMode mode : {DissipationMode::ReconstructedLoad, DissipationMode::ImplicitLoad}) {
    for (bool bDynamic : {false, true}) {
      Case c;
      c.A = Build(ball, true);
      c.B = Build(ball, bDynamic);
      c.bDynamic = bDynamic;
      c.a.p = Eigen::Vector3d(0.02, -0.01, 0.0985);  // 1.5 mm into B's reach
      c.a.p *= 0.0975 / c.a.p.norm();
      c.a.R = ExpSo3(Eigen::Vector3d(0.2, -0.3, 0.1));
      c.setup = CaseSetup(mode);
      RigidPose last = c.a;
      last.p += 0.04 * Eigen::Vector3d(0.0985, 0.0, -0.02).normalized();  // across the normal
      last.R = ExpSo3(Eigen::Vector3d(0.0, 0.1, -0.1)) * c.a.R;
      c.a0 = StartOf(last);
      c.b0 = StartOf(c.b);
      Case flat = c;
      SampleNode all = c.A.sampleTree.front();
      all.left = all.right = -1;
      flat.A.sampleTree = SharedArray<SampleNode>({all});
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(bDynamic ? 12 : 6);
      const RigidPairDissipation culled = Eval(c, zero, 2), every = Eval(flat, zero, 2);
      DYNAMIC_SECTION(ToString(mode) << (bDynamic ? " dynamic B" : " static B")) {
        REQUIRE(every.activeSamples > 0);
        CHECK(culled.activeSamples == every.activeSamples);
        CHECK(culled.value == every.value);
        CHECK(culled.residual == every.residual);
        CHECK(culled.jacobian == every.jacobian);
      }
    }
  }
}
