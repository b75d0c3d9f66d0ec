#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <random>

#include "derivative_check.h"
#include "energies/contact_dissipation.h"

using namespace superdex;

TEST_CASE("friction ramp: values, C2 join at V_f, slope and curvature", "[energies][dissipation]") {
  const double vf = 0.01;
  // Spec: ρ(V) = V²/V_f − V³/(3V_f²) below V_f, V − V_f/3 above.
  for (double V : {0.0, 0.001, 0.005, 0.0099, 0.01, 0.02, 1.0}) {
    const FrictionRamp r = EvaluateFrictionRamp(V, vf);
    const double expected = V < vf ? V * V / vf - V * V * V / (3 * vf * vf) : V - vf / 3;
    CHECK(r.rho == Approx(expected).margin(1e-18));
    CHECK(r.drho >= 0.0);
    CHECK(r.drho <= 1.0);
    // Derivatives by central differences (away from V = 0, where ρ is one-sided).
    if (V > 1e-4) {
      const double h = 1e-7;
      const auto p = EvaluateFrictionRamp(V + h, vf), m = EvaluateFrictionRamp(V - h, vf);
      CHECK(r.drho == Approx((p.rho - m.rho) / (2 * h)).epsilon(1e-6));
      if (V != vf) CHECK(r.d2rho == Approx((p.drho - m.drho) / (2 * h)).margin(1e-2));
      CHECK(r.slope * V == Approx(r.drho).epsilon(1e-14));
      CHECK(r.curvature == Approx(r.d2rho - r.slope).margin(1e-9));
    }
  }
  // C² at the join: value, slope and curvature agree from both sides.
  const auto below = EvaluateFrictionRamp(vf * (1 - 1e-12), vf);
  const auto above = EvaluateFrictionRamp(vf, vf);
  CHECK(below.rho == Approx(above.rho).epsilon(1e-10));
  CHECK(below.drho == Approx(above.drho).epsilon(1e-10));
  CHECK(below.d2rho == Approx(above.d2rho).margin(1e-8));
  CHECK(EvaluateFrictionRamp(0.0, vf).slope == Approx(2.0 / vf));
}

namespace {
// μ = 0.6, c_t = 0.3 s/m, c_n = 2 s/m, V_f = 1 cm/s.
DissipationCoefficients TestCoefficients() {
  DissipationCoefficients c;
  c.mu = 0.6;
  c.ct = 0.3;
  c.cn = 2.0;
  c.vf = 0.01;
  return c;
}
}  // namespace

TEST_CASE("dissipation potential: gradient, Hessian and tractions against the spec",
          "[energies][dissipation][gradient]") {
  std::mt19937 rng(3);
  std::normal_distribution<double> n01;
  const DissipationCoefficients c = TestCoefficients();
  const double lambda = 1.7e4;
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Vector3d N = Eigen::Vector3d(n01(rng), n01(rng), n01(rng)).normalized();
    // Tangential speeds on both branches of ρ, including near zero and near V_f.
    const double scales[5] = {1e-4, 3e-3, 0.0099, 0.0101, 0.5};
    Eigen::Vector3d V = Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
    V -= V.dot(N) * N;
    V = V.normalized() * scales[trial % 5] + 0.02 * n01(rng) * N;
    const DissipationDensity d = EvaluateDissipation(lambda, N, V, c, DissipationHessian::Exact);
    // T_diss = −∂R/∂V, split as the spec writes it.
    const double Vn = V.dot(N);
    const Eigen::Vector3d Vt = V - Vn * N;
    const FrictionRamp r = EvaluateFrictionRamp(Vt.norm(), c.vf);
    CHECK((d.viscousNormal + c.cn * lambda * Vn * N).norm() < 1e-9);
    CHECK((d.viscousTangential + c.ct * lambda * Vt).norm() < 1e-9);
    CHECK((d.coulomb + c.mu * lambda * r.drho * Vt.normalized()).norm() < 1e-9 * lambda);
    CHECK(d.coulomb.norm() <= c.mu * lambda * (1 + 1e-12));
    const auto check = test::CheckDerivatives(
        [&](const Eigen::VectorXd& dv) {
          return EvaluateDissipation(lambda, N, V + dv, c, DissipationHessian::None).R;
        },
        d.gradient, d.hessian, 1e-4 * std::max(1e-3, Vt.norm()));
    INFO("trial " << trial << " |Vt| " << Vt.norm());
    CHECK(check.gradientError < 1e-6);
    CHECK(check.hessianError < 1e-4);
    // The template used for automatic differentiation gives the same gradient.
    const Eigen::Vector3d g2 = DissipationGradient<double>(
        lambda, N, V, c, [](double x) { return x; });
    CHECK((g2 - d.gradient).norm() < 1e-12 * d.gradient.norm());
    // R is convex in V: the Hessian is positive semi-definite.
    CHECK(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(d.hessian).eigenvalues().minCoeff() >
          -1e-9 * d.hessian.norm());
    // The isotropic model: same value and gradient; its Hessian majorizes the exact one (the
    // difference is μλ(ρ'/V_t − ρ'') t tᵀ, positive semi-definite, zero without slip), and on
    // the slip direction it is μλ ρ'(V_t)/V_t + c_t λ.
    const DissipationDensity iso = EvaluateDissipation(lambda, N, V, c, DissipationHessian::Isotropic);
    CHECK(iso.R == d.R);
    CHECK(iso.gradient == d.gradient);
    const Eigen::Matrix3d excess = iso.hessian - d.hessian;
    CHECK(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(excess).eigenvalues().minCoeff() >
          -1e-9 * d.hessian.norm());
    const Eigen::Vector3d t = Vt.normalized();
    CHECK(t.dot(iso.hessian * t) == Approx(lambda * (c.mu * r.slope + c.ct)).epsilon(1e-12));
    CHECK(t.dot(excess * t) == Approx(-lambda * c.mu * r.curvature).epsilon(1e-9));
  }
  // V_t = 0: no Coulomb traction, finite Hessian 2μλ/V_f on the tangent plane.
  const Eigen::Vector3d N(0, 0, 1);
  const DissipationDensity d0 = EvaluateDissipation(lambda, N, Eigen::Vector3d(0, 0, -0.3), c,
                                                    DissipationHessian::Exact);
  CHECK(d0.coulomb.norm() == 0.0);
  CHECK(d0.hessian(0, 0) == Approx(lambda * (2 * c.mu / c.vf + c.ct)));
  CHECK(d0.hessian(2, 2) == Approx(lambda * c.cn));
}

TEST_CASE("dissipation force about a recorded slip: exact value and Jacobian at the reference, "
          "smooth about it", "[energies][dissipation][gradient]") {
  std::mt19937 rng(5);
  std::normal_distribution<double> n01;
  const DissipationCoefficients c = TestCoefficients();
  const double lambda = 1.7e4;
  // Central differences of the force with step e = 1e-4 m/s (a hundredth of V_f) about references
  // at tangential speeds from 0 to beyond V_f: the exact force's are O(e/V_f) off near V_t = 0
  // and at V_f (its Jacobian has kinks there); the force about the reference's slip is a
  // quadratic in V_t on the stick branch, so its differences are exact to rounding there, and
  // O(e²/V_t²) on the sliding one (measured 4e-5 at 1.01 V_f; 0 on the stick branch).
  const double e = 1e-4;
  double worstExact = 0.0;
  for (int trial = 0; trial < 24; ++trial) {
    const Eigen::Vector3d N = Eigen::Vector3d(n01(rng), n01(rng), n01(rng)).normalized();
    const double speeds[6] = {0.0, 1e-5, 5e-5, 3e-3, 0.99 * c.vf, 1.01 * c.vf};
    Eigen::Vector3d t = Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
    t = (t - t.dot(N) * N).normalized();
    const Eigen::Vector3d V = speeds[trial % 6] * t + 0.02 * n01(rng) * N;
    const SlipReference slip = SlipAt(N, V, c.vf);
    CHECK(slip.sliding == (speeds[trial % 6] >= c.vf));
    const DissipationDensity exact = EvaluateDissipation(lambda, N, V, c, DissipationHessian::Exact);
    const DissipationDensity about =
        EvaluateDissipation(lambda, N, V, c, DissipationHessian::None, &slip);
    INFO("trial " << trial << ", |V_t| " << speeds[trial % 6]);
    CHECK((about.gradient - exact.gradient).norm() <= 1e-12 * exact.gradient.norm());
    CHECK(about.R == exact.R);
    Eigen::Matrix3d fdAbout, fdExact;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d dv = e * Eigen::Vector3d::Unit(k);
      auto force = [&](const Eigen::Vector3d& at, const SlipReference* s) {
        return EvaluateDissipation(lambda, N, at, c, DissipationHessian::None, s).gradient;
      };
      fdAbout.col(k) = (force(V + dv, &slip) - force(V - dv, &slip)) / (2 * e);
      fdExact.col(k) = (force(V + dv, nullptr) - force(V - dv, nullptr)) / (2 * e);
    }
    const double scale = exact.hessian.norm();
    const double errAbout = (fdAbout - exact.hessian).norm() / scale;
    worstExact = std::max(worstExact, (fdExact - exact.hessian).norm() / scale);
    CHECK(errAbout < (slip.sliding ? 1e-4 : 1e-9));
  }
  CHECK(worstExact > 1e-3);  // what the reference removes (measured: worst 4.8e-3)
}

TEST_CASE("Hunt-Crossley calibration: rational formula and its closed-form inverse",
          "[energies][dissipation]") {
  for (double v : {0.1, 1.0, 4.0}) {
    for (double e : {0.01, 0.1, 0.5, 0.9, 0.999, 1.0}) {
      const double cn = HuntCrossleyDampingFromRestitution(e, v);
      CHECK(cn >= 0.0);
      CHECK(HuntCrossleyRestitutionFromDamping(cn, v) == Approx(e).epsilon(1e-12));
    }
  }
  // The limits the spec names: c_n ≈ 3/2 (1 − e)/v as e → 1, and e v ≈ 1/c_n as e → 0.
  CHECK(HuntCrossleyDampingFromRestitution(0.999, 2.0) == Approx(1.5 * 0.001 / 2.0).epsilon(2e-3));
  CHECK(HuntCrossleyRestitutionFromDamping(1e4, 1.0) * 1.0 == Approx(1.0 / 1e4).epsilon(2e-3));
  CHECK(HuntCrossleyRestitutionFromDamping(0.0, 1.0) == 1.0);
  CHECK(std::isnan(HuntCrossleyDampingFromRestitution(0.0, 1.0)));
  CHECK(std::isnan(HuntCrossleyDampingFromRestitution(0.5, -1.0)));
  CHECK(std::isnan(HuntCrossleyRestitutionFromDamping(-1.0, 1.0)));
}
