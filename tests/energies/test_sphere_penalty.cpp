// The penalty integrated exactly over a sphere (energies/sphere_penalty.h): its antiderivatives
// against quadrature of W, its derivatives against finite differences, and the whole-sphere
// integral against a quadrature of W over the sphere's surface points in 3D (the field and the
// alignment test evaluated at each point, as a sample's are).
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <vector>

#include "energies/sphere_penalty.h"

using namespace superdex;

namespace {

constexpr double kPi = 3.14159265358979323846;

// ∫_a^b f by 8-point Gauss–Legendre on n equal panels.
double Integrate(const std::function<double(double)>& f, double a, double b, int n) {
  static const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                              0.9602898564975363};
  static const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                              0.1012285362903763};
  double sum = 0.0;
  const double hp = (b - a) / n;
  for (int i = 0; i < n; ++i) {
    const double c = a + (i + 0.5) * hp, half = 0.5 * hp;
    for (int k = 0; k < 4; ++k) sum += half * w[k] * (f(c - half * x[k]) + f(c + half * x[k]));
  }
  return sum;
}

double W(double s, const PenaltyParams& p) { return NormalPenaltyDensity(p.delta - s, p).W; }

// E over the sphere of centre c, radius r: the points y = c + r u on the polar axis `axis`
// (t = u·axis, uniform in the azimuth), φ(y) and its gradient G from `field`, rejected where
// G·u > m; the integrand does not depend on the azimuth about the axis, so 2π r² ∫ dt.
double SurfaceQuadrature(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& axis, double m,
                         const std::function<double(const Eigen::Vector3d&, Eigen::Vector3d*)>& field,
                         const PenaltyParams& p) {
  const Eigen::Vector3d side = axis.unitOrthogonal();
  auto point = [&](double t, Eigen::Vector3d* u, Eigen::Vector3d* G) {
    *u = t * axis + std::sqrt(std::max(0.0, 1.0 - t * t)) * side;
    return field(c + r * *u, G);
  };
  auto accepted = [&](double t) {
    Eigen::Vector3d u, G;
    point(t, &u, &G);
    return G.dot(u) <= m;
  };
  auto integrand = [&](double t) {
    Eigen::Vector3d u, G;
    const double phi = point(t, &u, &G);
    return accepted(t) ? W(p.delta - phi, p) : 0.0;
  };
  // The rejection switches the integrand off at a few t: found by bisection on a grid, and the
  // panels split there.
  std::vector<double> cuts = {-1.0};
  const int grid = 2000;
  for (int i = 0; i < grid; ++i) {
    double a = -1.0 + 2.0 * i / grid, b = -1.0 + 2.0 * (i + 1) / grid;
    if (accepted(a) == accepted(b)) continue;
    const bool left = accepted(a);
    for (int k = 0; k < 80; ++k) {
      const double mid = 0.5 * (a + b);
      (accepted(mid) == left ? a : b) = mid;
    }
    cuts.push_back(0.5 * (a + b));
  }
  cuts.push_back(1.0);
  double sum = 0.0;
  for (size_t i = 0; i + 1 < cuts.size(); ++i)
    sum += Integrate(integrand, cuts[i], cuts[i + 1], 20000);
  return 2.0 * kPi * r * r * sum;
}

// Central differences of E and dE in x.
template <typename F>
void CheckAgainstDifferences(F&& penalty, double x, double step) {
  const SpherePenalty at = penalty(x);
  const SpherePenalty plus = penalty(x + step), minus = penalty(x - step);
  const double dFd = (plus.E - minus.E) / (2 * step), d2Fd = (plus.dE - minus.dE) / (2 * step);
  INFO("x = " << x << ": E " << at.E << ", dE " << at.dE << " (fd " << dFd << "), d2E " << at.d2E
              << " (fd " << d2Fd << ")");
  CHECK(at.dE == Approx(dFd).epsilon(1e-6).margin(1e-9 * (1.0 + std::abs(at.dE))));
  CHECK(at.d2E == Approx(d2Fd).epsilon(1e-6).margin(1e-6 * (1.0 + std::abs(at.d2E))));
}

}  // namespace

TEST_CASE("the penalty's antiderivatives Q0, Q1 integrate W and s W", "[energies][sphere]") {
  const PenaltyParams p;  // k = 1e9 Pa/m, ε = 5 mm, δ = 1 mm
  for (double u : {0.0, 0.3, 1.0, 1.7, 2.0, 2.5, 7.0, 40.0}) {
    const double s = u * p.eps;
    const PenaltyAntiderivatives q = PenaltyIntegrals(s, p);
    const double q0 = Integrate([&](double x) { return W(x, p); }, 0.0, s, 400);
    const double q1 = Integrate([&](double x) { return x * W(x, p); }, 0.0, s, 400);
    INFO("s = " << u << " eps");
    CHECK(q.Q0 == Approx(q0).epsilon(1e-12).margin(1e-300));
    CHECK(q.Q1 == Approx(q1).epsilon(1e-12).margin(1e-300));
  }
  CHECK(PenaltyIntegrals(-1e-3, p).Q0 == 0.0);
  CHECK(PenaltyIntegrals(-1e-3, p).Q1 == 0.0);
}

TEST_CASE("a sphere on a plane: the exact surface integral and its derivatives",
          "[energies][sphere][gradient]") {
  const PenaltyParams p;  // k = 1e9 Pa/m, ε = 5 mm, δ = 1 mm
  const double r = 0.1;
  const Eigen::Vector3d n = Eigen::Vector3d(1, -2, 3).normalized();
  auto plane = [&](const Eigen::Vector3d& y, Eigen::Vector3d* G) {
    *G = n;
    return n.dot(y);
  };
  // The centre's height: beyond the threshold, on the ramp, past it, and sunk below the equator
  // (the cut at t = m inside the active band).
  for (double h : {r + p.delta + 1e-4, r + p.delta - 0.7 * p.eps, r + p.delta - 3.0 * p.eps,
                   0.3 * r, -0.2 * r}) {
    for (double m : {0.0, 0.35, -0.4, 1.0}) {
      DYNAMIC_SECTION("h = " << h << ", m = " << m) {
        const SpherePenalty e = SpherePlanePenalty(h, r, m, p);
        const Eigen::Vector3d c = 0.7 * n.unitOrthogonal() + h * n;  // n·c = h
        const double reference = SurfaceQuadrature(c, r, -n, m, plane, p);
        CHECK(e.E == Approx(reference).epsilon(1e-9).margin(1e-12));
        CheckAgainstDifferences([&](double x) { return SpherePlanePenalty(x, r, m, p); }, h,
                                1e-7);
      }
    }
  }
}

TEST_CASE("a sphere on a sphere's field: the exact surface integral and its derivatives",
          "[energies][sphere][gradient]") {
  const PenaltyParams p;  // k = 1e9 Pa/m, ε = 5 mm, δ = 1 mm
  const double rA = 0.1, rB = 0.07;
  const Eigen::Vector3d cB(0.2, -0.1, 0.3);
  auto sphere = [&](const Eigen::Vector3d& y, Eigen::Vector3d* G) {
    *G = (y - cB).normalized();
    return (y - cB).norm() - rB;
  };
  const Eigen::Vector3d e = Eigen::Vector3d(2, 1, -1).normalized();  // from B's centre to A's
  const double touch = rA + rB + p.delta;
  for (double d : {touch + 1e-4, touch - 0.7 * p.eps, touch - 3.0 * p.eps, 1.1 * rA + 0.3 * rB,
                   1.02 * rA}) {
    for (double m : {0.0, 0.35, -0.4, 1.0}) {
      DYNAMIC_SECTION("d = " << d << ", m = " << m) {
        const SpherePenalty s = SphereSpherePenalty(d, rA, rB, m, p);
        const double reference = SurfaceQuadrature(cB + d * e, rA, -e, m, sphere, p);
        CHECK(s.E == Approx(reference).epsilon(1e-8).margin(1e-12));
        CheckAgainstDifferences([&](double x) { return SphereSpherePenalty(x, rA, rB, m, p); }, d,
                                1e-8);
      }
    }
  }
}
