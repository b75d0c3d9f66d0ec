// The one sample chain (core/contact/sample_chain.h): f(Y(y(q_A), q_B)) on the pair stencil, checked
// by finite differences through the real retractions (rigid: p + δp, exp([δθ]×) R; nodes: x + δx),
// for every colliding map (rigid, face, point) and rigid collider (static, dynamic); and equal to
// the rigid pair's fixed-size chain (AddFunctionOfPullback) to rounding.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "core/contact/rigid_contact.h"
#include "core/contact/sample_chain.h"
#include "core/model/rigid_math.h"
#include "derivative_check.h"

using namespace superdex;

namespace {

// A smooth non-quadratic f(Y) with its gradient and Hessian.
struct TestField {
  Eigen::Vector3d u;
  Eigen::Matrix3d M;  // symmetric
  double Value(const Eigen::Vector3d& Y) const { return std::sin(u.dot(Y)) + 0.5 * Y.dot(M * Y); }
  Eigen::Vector3d Gradient(const Eigen::Vector3d& Y) const {
    return std::cos(u.dot(Y)) * u + M * Y;
  }
  Eigen::Matrix3d Hessian(const Eigen::Vector3d& Y) const {
    return -std::sin(u.dot(Y)) * u * u.transpose() + M;
  }
};

}  // namespace

TEST_CASE("the sample chain matches finite differences for every map and rigid collider",
          "[core][contact][gradient]") {
  std::mt19937 rng(5);
  std::normal_distribution<double> n01;
  auto vec = [&]() { return Eigen::Vector3d(n01(rng), n01(rng), n01(rng)); };
  for (int trial = 0; trial < 6; ++trial) {
    TestField field;
    field.u = vec();
    Eigen::Matrix3d A;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) A(i, j) = n01(rng);
    field.M = A + A.transpose();
    const Eigen::Vector3d pA = vec(), X = 0.5 * vec(), pB = vec();
    const Eigen::Matrix3d RA = ExpSo3(vec()), RB = ExpSo3(vec());
    const Eigen::Vector3d nodes[3] = {vec(), vec(), vec()};
    Eigen::Vector3d bary(std::abs(n01(rng)), std::abs(n01(rng)), std::abs(n01(rng)));
    bary /= bary.sum();
    const double w = 0.3;
    for (int kind = 0; kind < 3; ++kind) {  // rigid, face, point
      for (bool bDynamic : {false, true}) {
        SamplePointMap map = kind == 0   ? SamplePointMap::Rigid(RA * X)
                             : kind == 1 ? SamplePointMap::Face(bary)
                                         : SamplePointMap::Point();
        const int nA = map.Dofs(), nB = bDynamic ? 6 : 0, n = nA + nB;
        auto y = [&](const Eigen::VectorXd& q) -> Eigen::Vector3d {
          if (kind == 0) return pA + q.segment<3>(0) + ExpSo3(q.segment<3>(3)) * RA * X;
          Eigen::Vector3d s = Eigen::Vector3d::Zero();
          for (int a = 0; a < map.nodes; ++a)
            s += map.bary[a] * (nodes[a] + q.segment<3>(3 * a));
          return s;
        };
        auto Y = [&](const Eigen::VectorXd& q) -> Eigen::Vector3d {
          if (!bDynamic) return RB.transpose() * (y(q) - pB);
          const Eigen::Matrix3d R = ExpSo3(q.segment<3>(nA + 3)) * RB;
          return R.transpose() * (y(q) - pB - q.segment<3>(nA));
        };
        const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
        const Eigen::Vector3d Y0 = Y(zero);
        const Eigen::Vector3d gY = field.Gradient(Y0);
        const Eigen::Matrix3d HY = field.Hessian(Y0);
        PointStencil point;
        RigidPullbackStencil(RB, y(zero) - pB, gY, &HY, bDynamic, &point);
        StencilVector g = StencilVector::Zero(n);
        StencilMatrix H = StencilMatrix::Zero(n, n);
        ChainToActor(map, point, w, &g, &H);
        // Step 1e-4: central-difference truncation O(h²) and round-off O(ε/h²) both near 1e-8.
        const test::DerivativeCheck c = test::CheckDerivatives(
            [&](const Eigen::VectorXd& q) { return w * field.Value(Y(q)); }, g, H, 1e-4);
        INFO("trial " << trial << ", map " << kind << (bDynamic ? ", dynamic B" : ", static B")
                      << ": gradient error " << c.gradientError << ", Hessian error "
                      << c.hessianError);
        CHECK(c.gradientError < 1e-7);
        CHECK(c.hessianError < 1e-6);
        CHECK((H - H.transpose()).norm() <= 1e-14 * H.norm());
        if (kind != 0) continue;
        // The rigid pair's fixed-size chain adds the same derivatives.
        StencilVector g2 = StencilVector::Zero(n);
        StencilMatrix H2 = StencilMatrix::Zero(n, n);
        AddFunctionOfPullback(map.r, y(zero) - pB, RB, gY, &HY, bDynamic, w, &g2, &H2);
        CHECK((g - g2).norm() <= 1e-13 * g.norm());
        CHECK((H - H2).norm() <= 1e-13 * H.norm());
      }
    }
  }
}
