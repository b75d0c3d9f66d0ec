#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <random>

#include "derivative_check.h"
#include "energies/normal_penalty.h"
#include "energies/psd_projection.h"

using namespace superdex;

TEST_CASE("normal penalty density: W, dW, d2W against finite differences", "[energies][gradient]") {
  PenaltyParams p;
  p.k = 1e9;
  const double h = 1e-8;
  // Sweep below, across both joins, and above the band.
  for (double phi = p.delta - 2.6 * p.eps; phi < p.delta + 0.3 * p.eps; phi += p.eps / 29.0) {
    const PenaltyDensity d = NormalPenaltyDensity(phi, p);
    const double dfd =
        (NormalPenaltyDensity(phi + h, p).W - NormalPenaltyDensity(phi - h, p).W) / (2 * h);
    const double d2fd =
        (NormalPenaltyDensity(phi + h, p).dW - NormalPenaltyDensity(phi - h, p).dW) / (2 * h);
    CHECK(d.dW == Approx(dfd).epsilon(1e-6).margin(1e-3));
    CHECK(d.d2W == Approx(d2fd).epsilon(1e-6).margin(1e-1));
    CHECK(d.lambdaN == Approx(-d.dW));
    CHECK(d.d2W >= 0.0);
  }
}

TEST_CASE("normal penalty on a stencil: chain rule against finite differences",
          "[energies][gradient]") {
  // φ(q) = c + aᵀq + ½ qᵀ B q on a 9-dof stencil; q0 chosen in each ramp regime.
  std::mt19937 rng(3);
  std::normal_distribution<double> n01;
  const int n = 9;
  PenaltyParams p;
  p.k = 1e6;
  Eigen::VectorXd a(n);
  Eigen::MatrixXd B(n, n);
  for (int i = 0; i < n; ++i) a[i] = n01(rng);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) B(i, j) = n01(rng);
  B = (0.5 * (B + B.transpose())).eval();  // eval: no aliasing
  for (double phi0 : {p.delta - 3 * p.eps, p.delta - 1.5 * p.eps, p.delta - 0.3 * p.eps}) {
    auto phi = [&](const Eigen::VectorXd& q) { return phi0 + a.dot(q) + 0.5 * q.dot(B * q); };
    auto W = [&](const Eigen::VectorXd& q) {
      double v = 0;
      StencilVector g = StencilVector::Zero(n);
      AddNormalPenalty(NormalPenaltyDensity(phi(q), p), 0.7, a + B * q, B, &v, &g, nullptr);
      return v;
    };
    double v = 0;
    StencilVector g = StencilVector::Zero(n);
    StencilMatrix H = StencilMatrix::Zero(n, n);
    AddNormalPenalty(NormalPenaltyDensity(phi0, p), 0.7, a, B, &v, &g, &H);
    const auto c = test::CheckDerivatives(W, g, H, 3e-7);
    INFO("phi0 " << phi0 << ": gradient error " << c.gradientError << ", Hessian error " << c.hessianError);
    CHECK(c.gradientError < 1e-6);
    CHECK(c.hessianError < 1e-5);
  }
}

TEST_CASE("PSD projection keeps eigenvectors and clamps or flips negative eigenvalues",
          "[energies]") {
  StencilMatrix H(3, 3);
  H << 2, 1, 0, 1, -3, 0, 0, 0, 0;
  StencilMatrix C = H, A = H;
  ProjectToPsd(&C, false);
  ProjectToPsd(&A, true);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> e{Eigen::MatrixXd(H)};
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ec{Eigen::MatrixXd(C)};
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ea{Eigen::MatrixXd(A)};
  CHECK(ec.eigenvalues().minCoeff() > -1e-12);
  CHECK(ea.eigenvalues().minCoeff() > -1e-12);
  // |λ| spectrum for Abs, zeroed negative part for Clamp.
  CHECK(ea.eigenvalues().sum() == Approx(e.eigenvalues().cwiseAbs().sum()));
  CHECK(ec.eigenvalues().sum() == Approx(e.eigenvalues().cwiseMax(0.0).sum()));
  StencilMatrix P = StencilMatrix::Identity(4, 4);
  ProjectToPsd(&P, false);
  CHECK((P - StencilMatrix::Identity(4, 4)).norm() == 0.0);
}
