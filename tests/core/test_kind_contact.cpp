// The one contact assembler on frame colliders (core/contact/kind_contact.h), checked by finite
// differences through the real retractions (nodes x + δx; rigid p + δp, exp([δθ]×) R; a
// translating frame p_B + F_p δq_B): in the potential modes (penalty, explicit-normals
// dissipation) the gradient and Hessian of the pair's value; in the residual modes the Jacobian
// of the residual (world forces and torques), which kind_contact.cpp forms by forward-mode AD.
#include <catch2/catch.hpp>
#include <random>

#include "core/contact/kind_contact.h"
#include "core/model/rigid_math.h"
#include "derivative_check.h"
#include "optim/finite_difference.h"

using namespace superdex;

namespace {

// Colliding sides: a 2-node sample without a normal (a kind's), a rigid sample whose normal turns
// with the body, a soft face's sample whose normal is the moving triangle's.
enum class Side { Nodes, Rigid, Face };
const char* const kSideNames[3] = {"nodes A", "rigid A", "face A"};

struct Setup {
  Side side = Side::Nodes;
  bool rigidA = false;
  bool rigidB = false;  // a rotating rigid frame, else a frame translating with 2 blocks
  Eigen::Vector3d pA, X, nBody, nodes[3], pB;
  Eigen::Matrix3d RA, RB;
  Eigen::Vector3d bary;
  Eigen::Matrix<double, 3, 6> Fp;
  RigidCollider field;
  RigidPose last;
  RigidStageStart start;
  Eigen::Vector3d yLast, y0, nLast;

  int NA() const { return side == Side::Face ? 9 : 6; }
  int NB() const { return 6; }

  // The sample and frame at the stencil step d.
  void At(const Eigen::VectorXd& d, std::vector<PairSample>* samples, FrameSide* B) const {
    PairSample s;
    if (rigidA) {
      const Eigen::Matrix3d R = ExpSo3(d.segment<3>(3)) * RA;
      s.map = SamplePointMap::Rigid(R * X, pA + d.segment<3>(0));
      s.y = pA + d.segment<3>(0) + R * X;
      s.hasNormal = true;
      s.n = R * nBody;
      s.nLast = nLast;
      s.blocks = 2;
      s.offs[0] = 0;
      s.offs[1] = 3;
    } else {
      const int m = side == Side::Face ? 3 : 2;
      s.map.nodes = m;
      s.map.bary.head(m) = bary.head(m);
      s.y.setZero();
      s.blocks = m;
      for (int a = 0; a < m; ++a) {
        s.faceNodes[a] = nodes[a] + d.segment<3>(3 * a);
        s.y += bary[a] * s.faceNodes[a];
        s.offs[a] = 3 * a;
      }
      if (side == Side::Face) {
        s.hasNormal = s.faceNormal = true;
        s.n = (s.faceNodes[1] - s.faceNodes[0]).cross(s.faceNodes[2] - s.faceNodes[0]).normalized();
        s.nLast = nLast;
      }
    }
    s.yLast = yLast;
    s.y0 = y0;
    s.weight = 0.7;
    samples->assign(1, s);
    *B = FrameSide();
    B->field = &field;
    B->last = last;
    B->start = start;
    B->hasStart = true;
    const int o = NA();
    if (rigidB) {
      B->motion = FrameSide::Motion::Rigid;
      B->pose.p = pB + d.segment<3>(o);
      B->pose.R = ExpSo3(d.segment<3>(o + 3)) * RB;
    } else {
      B->motion = FrameSide::Motion::Translation;
      B->blocks = 2;
      B->Fp.leftCols(6) = Fp;
      B->pose.p = pB + Fp * d.segment<6>(o);
      B->pose.R = RB;
    }
    B->offs[0] = o;
    B->offs[1] = o + 3;
  }
};

Setup MakeSetup(std::mt19937& rng, Side side, bool rigidB) {
  std::normal_distribution<double> n01;
  auto vec = [&]() { return Eigen::Vector3d(n01(rng), n01(rng), n01(rng)); };
  Setup s;
  s.side = side;
  s.rigidA = side == Side::Rigid;
  s.rigidB = rigidB;
  s.field.type = ColliderType::Sphere;
  s.field.sphere.radius = 1.0;
  s.field.boundingRadius = 1.0;
  s.RB = ExpSo3(vec());
  s.pB = 0.1 * vec();
  // The sample sits 1 cm inside the unit sphere, its normal facing the centre (s = G·N_A < 0).
  const Eigen::Vector3d u = vec().normalized();
  const Eigen::Vector3d y = s.pB + 0.99 * (s.RB * u);
  s.RA = ExpSo3(vec());
  s.X = 0.3 * vec();
  s.pA = y - s.RA * s.X;
  s.nBody = s.RA.transpose() * (-(s.RB * u) + 0.2 * vec()).normalized();
  // Nodes around y (the face's normal facing the sphere's centre, so that s = G·N_A < 0).
  const Eigen::Vector3d t1 = (s.RB * u).unitOrthogonal(), t2 = (s.RB * u).cross(t1);
  s.nodes[0] = y + 0.1 * t1 + 0.01 * vec();
  s.nodes[1] = y - 0.05 * t1 + 0.1 * t2 + 0.01 * vec();
  s.bary = side == Side::Face ? Eigen::Vector3d(0.2, 0.3, 0.5) : Eigen::Vector3d(0.3, 0.7, 0.0);
  const int m = side == Side::Face ? 3 : 2;
  s.nodes[m - 1] = y;
  for (int a = 0; a + 1 < m; ++a) s.nodes[m - 1] -= s.bary[a] * s.nodes[a];
  s.nodes[m - 1] /= s.bary[m - 1];
  if (side == Side::Face &&
      (s.nodes[1] - s.nodes[0]).cross(s.nodes[2] - s.nodes[0]).dot(s.RB * u) > 0)
    std::swap(s.nodes[0], s.nodes[1]), std::swap(s.bary[0], s.bary[1]);
  for (int c = 0; c < 6; ++c) s.Fp.col(c) = 0.5 * vec();
  // x_n and x⁰ a little away: slip V = (Y − Y⁰)/Δt_i of a few cm/s.
  s.yLast = y + 0.002 * vec();
  s.y0 = y + 0.003 * vec();
  s.nLast = (-(s.RB * u) + 0.1 * vec()).normalized();
  s.last.p = s.pB + 0.001 * vec();
  s.last.R = ExpSo3(0.01 * vec()) * s.RB;
  s.start.p = s.pB + 0.002 * vec();
  s.start.R = ExpSo3(0.01 * vec()) * s.RB;
  s.start.Rinv = s.start.R.transpose();
  s.start.last = s.last;
  return s;
}

DissipationSetup Dissipation(DissipationMode mode) {
  DissipationSetup d;
  d.mode = mode;
  d.dt = 0.05;
  d.penalty.k = 1e4;
  d.penalty.eps = 0.05;
  d.penalty.delta = 0.02;
  d.coefficients.mu = 0.4;
  d.coefficients.ct = 0.3;
  d.coefficients.cn = 0.2;
  d.coefficients.vf = 0.05;
  d.maxAlignment = 0.0;
  return d;
}

}  // namespace

TEST_CASE("the kind contact assembler's potential derivatives match finite differences",
          "[core][kind][contact][gradient]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 4; ++trial)
    for (Side side : {Side::Nodes, Side::Rigid, Side::Face})
      for (bool rigidB : {false, true}) {
        const Setup s = MakeSetup(rng, side, rigidB);
        const DissipationSetup diss = Dissipation(DissipationMode::ExplicitNormals);
        const int n = s.NA() + s.NB();
        std::vector<PairSample> samples;
        FrameSide B;
        PairStencils out;
        auto value = [&](const Eigen::VectorXd& d) {
          s.At(d, &samples, &B);
          EvaluateSamplesOnFrame(samples, B, diss.penalty, diss.maxAlignment, &diss, 0, &out);
          return out.penaltyValue + out.dissipationValue;
        };
        s.At(Eigen::VectorXd::Zero(n), &samples, &B);
        EvaluateSamplesOnFrame(samples, B, diss.penalty, diss.maxAlignment, &diss, 2, &out);
        REQUIRE(out.count == 1);
        const ContactStencil& st = out.stencils[0];
        REQUIRE(st.penaltyActive);
        REQUIRE(st.dissipationActive);
        const Eigen::VectorXd g = st.penaltyGradient + st.dissipationResidual;
        const Eigen::MatrixXd H = st.penaltyHessian + st.dissipationJacobian;
        const test::DerivativeCheck c = test::CheckDerivatives(value, g, H, 2e-6);
        INFO("trial " << trial << ", " << kSideNames[static_cast<int>(side)]
                      << (rigidB ? ", rigid B" : ", translating B") << ": gradient error "
                      << c.gradientError << ", Hessian error " << c.hessianError);
        CHECK(c.gradientError < 1e-6);
        CHECK(c.hessianError < 1e-5);
      }
}

TEST_CASE("the kind contact assembler's residual-mode Jacobian matches finite differences",
          "[core][kind][contact][gradient]") {
  std::mt19937 rng(12);
  for (DissipationMode mode : {DissipationMode::ReconstructedLoad, DissipationMode::ImplicitLoad})
    for (int trial = 0; trial < 3; ++trial)
      for (Side side : {Side::Nodes, Side::Rigid, Side::Face})
        for (bool rigidB : {false, true}) {
          const Setup s = MakeSetup(rng, side, rigidB);
          const DissipationSetup diss = Dissipation(mode);
          const int n = s.NA() + s.NB();
          std::vector<PairSample> samples;
          FrameSide B;
          PairStencils out;
          auto residual = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
            s.At(d, &samples, &B);
            EvaluateSamplesOnFrame(samples, B, diss.penalty, diss.maxAlignment, &diss, 1,
                                   &out);
            return out.stencils[0].dissipationResidual;
          };
          s.At(Eigen::VectorXd::Zero(n), &samples, &B);
          EvaluateSamplesOnFrame(samples, B, diss.penalty, diss.maxAlignment, &diss, 2, &out);
          REQUIRE(out.count == 1);
          REQUIRE(out.stencils[0].dissipationActive);
          const Eigen::MatrixXd J = out.stencils[0].dissipationJacobian;
          const double h = 1e-6;
          Eigen::MatrixXd Jfd(n, n);
          for (int j = 0; j < n; ++j) {
            Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
            d[j] = h;
            const Eigen::VectorXd rp = residual(d);
            d[j] = -h;
            Jfd.col(j) = (rp - residual(d)) / (2 * h);
          }
          const double err = (J - Jfd).norm() / Jfd.norm();
          INFO("mode " << static_cast<int>(mode) << ", trial " << trial << ", "
                       << kSideNames[static_cast<int>(side)]
                       << (rigidB ? ", rigid B" : ", translating B") << ": Jacobian error "
                       << err);
          CHECK(err < 1e-6);
        }
}
