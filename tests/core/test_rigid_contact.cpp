#include <catch2/catch.hpp>
#include <random>

#include "core/contact/rigid_contact.h"
#include "core/model/rigid_math.h"
#include "core/scene.h"
#include "derivative_check.h"
#include "rigid_pair_eval.h"

using namespace superdex;
using test::EvaluateRigidPairDissipation;
using test::EvaluateRigidPairPenalty;
using test::RigidPairStepLimit;
using test::RetractPair;
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

RigidShape Sphere(double r, int res) {
  RigidShape s;
  s.kind = RigidShapeKind::Sphere;
  s.radius = r;
  s.surfaceResolution = res;
  return s;
}
RigidShape Box(Eigen::Vector3d h, int res) {
  RigidShape s;
  s.kind = RigidShapeKind::Box;
  s.halfExtents = h;
  s.surfaceResolution = res;
  return s;
}

struct PairCase {
  RigidBodyModel A, B;
  RigidPose a, b;
  bool bDynamic;
};

// Value of the pair energy after retracting both poses by the stencil step d.
double PairValue(const PairCase& c, const PenaltyParams& p, const Eigen::VectorXd& d) {
  RigidPose a = c.a, b = c.b;
  RetractPair(d, c.bDynamic, &a, &b);
  RigidPairPenalty out;
  EvaluateRigidPairPenalty(c.A, a, c.B, b, c.bDynamic, p, 0, &out);
  return out.value;
}

void CheckPair(const PairCase& c, const PenaltyParams& p, int minActive) {
  RigidPairPenalty out;
  EvaluateRigidPairPenalty(c.A, c.a, c.B, c.b, c.bDynamic, p, 2, &out);
  REQUIRE(out.activeSamples >= minActive);
  RigidPairPenalty v0;
  EvaluateRigidPairPenalty(c.A, c.a, c.B, c.b, c.bDynamic, p, 0, &v0);
  CHECK(v0.value == Approx(out.value).epsilon(1e-14));
  const auto check = test::CheckDerivatives(
      [&](const Eigen::VectorXd& d) { return PairValue(c, p, d); }, Eigen::VectorXd(out.gradient),
      Eigen::MatrixXd(out.hessian), 1e-6);
  INFO("gradient error " << check.gradientError << ", Hessian error " << check.hessianError);
  CHECK(check.gradientError < 1e-5);
  CHECK(check.hessianError < 1e-4);
  if (c.bDynamic) {
    // Balanced: forces sum to zero, torques about the world origin sum to zero.
    const Eigen::Vector3d fA = out.gradient.segment<3>(0), fB = out.gradient.segment<3>(6);
    const Eigen::Vector3d tA = out.gradient.segment<3>(3), tB = out.gradient.segment<3>(9);
    const double scale = fA.norm() + 1e-30;
    CHECK((fA + fB).norm() < 1e-12 * scale);
    CHECK((c.a.p.cross(fA) + tA + c.b.p.cross(fB) + tB).norm() < 1e-11 * scale);
  }
}

}  // namespace

TEST_CASE("rigid pair penalty: derivatives through both retractions", "[core][gradient][contact]") {
  // Smaller k keeps the finite differences well conditioned; the formulas do not depend on k.
  PenaltyParams p;
  p.k = 1e5;
  std::mt19937 rng(5);
  std::normal_distribution<double> n01;
  auto rot = [&]() { return ExpSo3(Eigen::Vector3d(n01(rng), n01(rng), n01(rng))); };

  SECTION("sphere samples against a moving sphere collider") {
    PairCase c{Build(Sphere(0.1, 2), true), Build(Sphere(0.15, 2), true), {}, {}, true};
    c.a.R = rot();
    c.b.R = rot();
    c.a.p = Eigen::Vector3d(0.01, 0.02, 0.0);
    c.b.p = c.a.p + Eigen::Vector3d(0.05, 0.2, 0.1).normalized() * (0.25 - 0.006);
    CheckPair(c, p, 3);
  }
  SECTION("box samples against a moving box collider (face, edge and corner regions)") {
    PairCase c{Build(Box({0.1, 0.07, 0.05}, 3), true), Build(Box({0.2, 0.1, 0.15}, 2), true), {}, {}, true};
    for (int t = 0; t < 3; ++t) {
      c.a.R = rot();
      c.b.R = rot();
      c.b.p = Eigen::Vector3d(0.3, -0.1, 0.2);
      // Put A's centre just outside a face/edge/corner of B so some samples penetrate.
      const Eigen::Vector3d dirs[3] = {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}};
      const Eigen::Vector3d local = Eigen::Vector3d(0.2, 0.1, 0.15).cwiseProduct(dirs[t]) +
                                    dirs[t].normalized() * 0.06;
      c.a.p = c.b.p + c.b.R * local;
      RigidPairPenalty out;
      EvaluateRigidPairPenalty(c.A, c.a, c.B, c.b, true, p, 0, &out);
      if (out.activeSamples == 0) continue;
      CheckPair(c, p, 1);
    }
  }
  SECTION("sphere samples against a static plane") {
    RigidShape plane;
    plane.kind = RigidShapeKind::Plane;
    plane.planeNormal = Eigen::Vector3d(0.1, 0.2, 1.0).normalized();
    PairCase c{Build(Sphere(0.1, 2), true), Build(plane, false), {}, {}, false};
    c.a.R = rot();
    c.b.p = Eigen::Vector3d(0.0, 0.0, -0.05);
    c.a.p = c.b.p + plane.planeNormal * (0.1 - 0.004);
    CheckPair(c, p, 3);
  }
}

TEST_CASE("AddFunctionOfPullback: the block assembly equals the full stencil products bit for bit",
          "[core][contact]") {
  // Reference: w·(J_xᵀ R_B H_Y R_Bᵀ J_x) with the full 3×12 J_x = [I, −[r]×, −I, [d]×] and plain
  // matrix products, plus the same retraction curvature. The block form drops only products with
  // J_x's zeros and ones, so every entry must be equal, not just close.
  std::mt19937 rng(11);
  std::normal_distribution<double> n01;
  auto vec = [&]() { return Eigen::Vector3d(n01(rng), n01(rng), n01(rng)); };
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d r = vec(), d = vec(), gY = vec();
    const Eigen::Matrix3d RB = ExpSo3(vec());
    Eigen::Matrix3d HY;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) HY(i, j) = n01(rng);  // not symmetric: every entry counts
    const double w = std::abs(n01(rng)) + 0.1;
    for (bool bDynamic : {false, true}) {
      const int n = bDynamic ? 12 : 6;
      StencilVector grad = StencilVector::Zero(n);
      StencilMatrix H = StencilMatrix::Zero(n, n);
      AddFunctionOfPullback(r, d, RB, gY, &HY, bDynamic, w, &grad, &H);

      StencilMatrix reference = StencilMatrix::Zero(n, n);
      const Eigen::Matrix3d Hw = w * (RB * HY * RB.transpose());
      Eigen::Matrix<double, 3, 12> Jx;
      Jx << Eigen::Matrix3d::Identity(), -Skew(r), -Eigen::Matrix3d::Identity(), Skew(d);
      const Eigen::Matrix<double, 3, 12> HJ = Hw * Jx;
      const Eigen::Matrix<double, 12, 12> full = Jx.transpose().lazyProduct(HJ);
      reference.topLeftCorner(n, n) = full.topLeftCorner(n, n);
      // The curvature terms alone: the function with a zero H_Y adds exactly them.
      StencilVector g0 = StencilVector::Zero(n);
      StencilMatrix curvature = StencilMatrix::Zero(n, n);
      const Eigen::Matrix3d zero = Eigen::Matrix3d::Zero();
      AddFunctionOfPullback(r, d, RB, gY, &zero, bDynamic, w, &g0, &curvature);
      INFO("trial " << trial << (bDynamic ? ", dynamic B" : ", static B"));
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          INFO("entry (" << i << ", " << j << ")");
          REQUIRE(H(i, j) == reference(i, j) + curvature(i, j));
        }
      CHECK(grad == g0);
      // The fixed-size pair stencil's overload adds the same sums.
      PairVector pairGrad = PairVector::Zero();
      PairMatrix pairH = PairMatrix::Zero();
      AddFunctionOfPullback(r, d, RB, gY, &HY, bDynamic, w, &pairGrad, &pairH);
      CHECK(pairGrad.head(n) == grad);
      CHECK(pairH.topLeftCorner(n, n) == H);
    }
  }
}

TEST_CASE("PairHessianSums: a pair's summed Hessian equals the per-sample pullback Hessians",
          "[core][contact]") {
  // 40 samples of one pair (symmetric H_Y, as the penalty and the explicit-normals dissipation
  // give) against Σ AddFunctionOfPullback: the same sums regrouped, equal to rounding.
  std::mt19937 rng(13);
  std::normal_distribution<double> n01;
  auto vec = [&]() { return Eigen::Vector3d(n01(rng), n01(rng), n01(rng)); };
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Matrix3d RB = ExpSo3(vec());
    const Eigen::Vector3d c = 2.0 * vec();  // p_A − p_B
    for (bool bDynamic : {false, true}) {
      const int n = bDynamic ? 12 : 6;
      PairVector grad = PairVector::Zero();
      PairMatrix reference = PairMatrix::Zero(), summed = PairMatrix::Zero();
      PairHessianSums sums;
      CHECK(sums.Empty());
      for (int k = 0; k < 40; ++k) {
        const Eigen::Vector3d rB = 0.3 * vec(), gY = 1e3 * vec();
        Eigen::Matrix3d M;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) M(i, j) = n01(rng);
        const Eigen::Matrix3d HY = 1e6 * (M + M.transpose());
        const double w = std::abs(n01(rng)) * 1e-3;
        const Eigen::Vector3d r = RB * rB;
        AddFunctionOfPullback(r, c + r, RB, gY, &HY, bDynamic, w, &grad, &reference);
        sums.Add(rB, gY, HY, w);
      }
      sums.AddTo(RB, c, bDynamic, &summed);
      INFO("trial " << trial << (bDynamic ? ", dynamic B" : ", static B"));
      const double scale = reference.topLeftCorner(n, n).norm();
      CHECK((summed - reference).topLeftCorner(n, n).norm() <= 1e-13 * scale);
      if (!bDynamic) CHECK(summed.bottomRows(6).norm() == 0.0);
      // Mutation check: a wrong lever arm (c off by 1 mm) is visible at this tolerance.
      PairMatrix shifted = PairMatrix::Zero();
      sums.AddTo(RB, c + Eigen::Vector3d(1e-3, 0, 0), bDynamic, &shifted);
      if (bDynamic) CHECK((shifted - reference).topLeftCorner(n, n).norm() > 1e-8 * scale);
    }
  }
}

TEST_CASE("Step limit: a sample's penetration depth may at most double (or reach eps/2) per step",
          "[core][contact]") {
  PairCase c{Build(Sphere(0.05, 2), true), Build(Box({1, 1, 0.1}, 2), false), {}, {}, false};
  c.b.p = Eigen::Vector3d(0, 0, -0.1);  // top face at z = 0
  PenaltyParams p;                      // ε = 5 mm, δ = 1 mm
  // The lowest sample's penetration depth s = δ − φ at a centre height z (translation only).
  double lowest = INFINITY;
  for (const SurfaceSample& q : c.A.samples) lowest = std::min(lowest, q.X.z());
  auto depth = [&](double z) { return p.delta - (z + lowest); };
  RigidPose to = c.a;
  // A small move: no limit.
  c.a.p = Eigen::Vector3d(0, 0, -lowest + 0.002);
  to.p = c.a.p - Eigen::Vector3d(0, 0, 0.001);
  CHECK(RigidPairStepLimit(c.A, c.a, to, c.B, c.b, c.b, p) == 1.0);
  // From 2 mm above the surface to 20 mm deep: the depth may reach ε/2 = 2.5 mm. φ is linear in
  // a translation normal to the face, so the fraction is exact: s(α) = ε/2.
  to.p = c.a.p - Eigen::Vector3d(0, 0, 0.022);
  double alpha = RigidPairStepLimit(c.A, c.a, to, c.B, c.b, c.b, p);
  const double z0 = c.a.p.z(), z1 = to.p.z();
  CHECK(depth(z0 + alpha * (z1 - z0)) == Approx(0.5 * p.eps).epsilon(1e-12));
  // From 3 mm deep (lowest sample s₀ = 4 mm) to 20 mm deep: every sample's depth within
  // max(2 s₀, ε/2), and one of them exactly at its cap (the binding sample need not be the
  // lowest: a shallower sample has a tighter cap).
  c.a.p.z() = -lowest - 0.003;
  alpha = RigidPairStepLimit(c.A, c.a, to, c.B, c.b, c.b, p);
  CHECK(alpha < 1.0);
  const double zA = c.a.p.z() + alpha * (to.p.z() - c.a.p.z());
  double worst = -INFINITY;
  for (const SurfaceSample& q : c.A.samples) {
    const double s0 = p.delta - (c.a.p.z() + q.X.z()), s = p.delta - (zA + q.X.z());
    worst = std::max(worst, s - std::max(2 * s0, 0.5 * p.eps));
  }
  CHECK(std::abs(worst) < 1e-12);
  CHECK(depth(zA) > 0.005);  // the lowest sample still went deeper than ε
  // A sideways slide at constant depth is not limited however long.
  to.p = c.a.p + Eigen::Vector3d(0.3, 0, 0);
  CHECK(RigidPairStepLimit(c.A, c.a, to, c.B, c.b, c.b, p) == 1.0);
  // Moving away is not limited.
  to.p = c.a.p + Eigen::Vector3d(0, 0, 0.05);
  CHECK(RigidPairStepLimit(c.A, c.a, to, c.B, c.b, c.b, p) == 1.0);
}

TEST_CASE("sample tree: leaves partition the samples, spheres bound them; culling loses nothing",
          "[core][contact]") {
  const RigidBodyModel A = Build(Box({0.5, 0.3, 0.05}, 24), true);
  REQUIRE(A.samples.size() > 1000);
  REQUIRE(!A.sampleTree.empty());
  std::vector<int> covered(A.samples.size(), 0);
  int leaves = 0;
  for (const SampleNode& node : A.sampleTree) {
    for (int k = node.begin; k < node.end; ++k)
      CHECK((A.samples[k].X - node.center).norm() <= node.radius * (1 + 1e-12));
    if (node.left >= 0) {
      CHECK(A.sampleTree[node.left].begin == node.begin);
      CHECK(A.sampleTree[node.left].end == A.sampleTree[node.right].begin);
      CHECK(A.sampleTree[node.right].end == node.end);
      continue;
    }
    ++leaves;
    CHECK(node.end - node.begin <= kSamplesPerLeaf);
    for (int k = node.begin; k < node.end; ++k) ++covered[k];
  }
  for (int c : covered) CHECK(c == 1);
  // The plate resting on a small sphere: the pair energy over the culled tree equals the sum of
  // W over every sample, and far fewer samples than the plate's are evaluated.
  const RigidBodyModel B = Build(Sphere(0.05, 3), false);
  RigidPose a, b;
  a.p = Eigen::Vector3d(0.1, -0.05, 0.05 + 0.05 - 0.002);  // plate bottom 2 mm into the sphere
  a.R = ExpSo3(Eigen::Vector3d(0.01, -0.02, 0.3));
  PenaltyParams p;
  RigidPairPenalty out;
  EvaluateRigidPairPenalty(A, a, B, b, false, p, 0, &out);
  double brute = 0.0;
  int active = 0;
  for (const SurfaceSample& s : A.samples) {
    const Eigen::Vector3d Y = b.R.transpose() * (a.p + a.R * s.X - b.p);
    const double phi = B.collider.Evaluate(Y).value;
    if (phi >= p.delta) continue;
    ++active;
    brute += s.weight * NormalPenaltyDensity(phi, p).W;
  }
  REQUIRE(active > 0);
  CHECK(out.activeSamples == active);
  CHECK(out.value == Approx(brute).epsilon(1e-14));
  int visited = 0;
  ForEachSampleRange(
      A,
      [&](const Eigen::Vector3d& c, double r) {
        const Eigen::Vector3d Y = b.R.transpose() * (a.p + a.R * c - b.p);
        return B.collider.Evaluate(Y).value - B.collider.lipschitz * r < p.delta;
      },
      [&](int begin, int end) { visited += end - begin; });
  INFO(visited << " of " << A.samples.size() << " samples visited, " << active << " active");
  CHECK(visited < static_cast<int>(A.samples.size()) / 20);
}

TEST_CASE("identical shapes share one sample buffer; others keep their own",
          "[core][contact]") {
  // Two models from one description: equal samples, one buffer once shared.
  RigidBodyModel a = Build(Sphere(0.05, 2), true);
  RigidBodyModel b = Build(Sphere(0.05, 2), true);
  REQUIRE(!a.samples.SharesBufferWith(b.samples));
  CHECK(SamplesHash(a) == SamplesHash(b));
  REQUIRE(ShareSamples(a, &b));
  CHECK(b.samples.SharesBufferWith(a.samples));
  CHECK(b.sampleTree.SharesBufferWith(a.sampleTree));
  // A different radius or resolution: not shared, b's own samples kept.
  for (const RigidShape& other : {Sphere(0.06, 2), Sphere(0.05, 3)}) {
    RigidBodyModel c = Build(other, true);
    const SurfaceSample* own = c.samples.data();
    CHECK(!ShareSamples(a, &c));
    CHECK(c.samples.data() == own);
    CHECK(SamplesHash(a) != SamplesHash(c));
  }

  // In a scene: the spheres of one size share, the box and the other size do not, and the pair
  // energies are those of unshared models.
  Scene scene;
  Error e;
  std::vector<ActorHandle> h;
  for (const RigidShape& s : {Sphere(0.05, 2), Box({0.1, 0.1, 0.1}, 2), Sphere(0.05, 2),
                              Sphere(0.07, 2), Sphere(0.05, 2)}) {
    RigidActorDesc d;
    d.name = "a" + std::to_string(h.size());
    d.shape = s;
    d.position = Eigen::Vector3d(0.3 * h.size(), 0, 1);
    h.push_back(scene.AddRigidActor(d, &e));
    REQUIRE(h.back().index >= 0);
  }
  CHECK(scene.Model(h[2]).samples.SharesBufferWith(scene.Model(h[0]).samples));
  CHECK(scene.Model(h[4]).samples.SharesBufferWith(scene.Model(h[0]).samples));
  CHECK(scene.Model(h[4]).sampleTree.SharesBufferWith(scene.Model(h[0]).sampleTree));
  CHECK(!scene.Model(h[3]).samples.SharesBufferWith(scene.Model(h[0]).samples));
  CHECK(!scene.Model(h[1]).samples.SharesBufferWith(scene.Model(h[0]).samples));
  const RigidBodyModel unshared = Build(Sphere(0.05, 2), true);
  const RigidBodyModel ground = Build(Box({1, 1, 0.1}, 1), false);
  RigidPose pa, pb;
  pa.p = Eigen::Vector3d(0.01, 0.02, 0.05 + 0.05 - 0.003);
  pa.R = ExpSo3(Eigen::Vector3d(0.2, -0.1, 0.4));
  PenaltyParams p;
  RigidPairPenalty fromScene, fromOwn;
  EvaluateRigidPairPenalty(scene.Model(h[4]), pa, ground, pb, false, p, 2, &fromScene);
  EvaluateRigidPairPenalty(unshared, pa, ground, pb, false, p, 2, &fromOwn);
  REQUIRE(fromOwn.activeSamples > 0);
  CHECK(fromScene.value == fromOwn.value);
  CHECK(fromScene.gradient == fromOwn.gradient);
  CHECK(fromScene.hessian == fromOwn.hessian);
}
