// Joint limit and drive potentials (energies/joint_energies.h).
//
// Expectations: the derivatives equal central differences of the value away from the kinks
// (relative 1e-7 first, 1e-6 second), the values follow the closed forms (the limit's ½ k s², the
// drive's quadratic and its linear continuation past the force limit, continuous there), and the
// drive's force −∂U/∂x never exceeds its limit.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "energies/joint_energies.h"

using namespace superdex;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

template <typename F>
void CheckDerivatives(F f, double x) {
  const double h = 1e-6;
  const JointEnergy e = f(x);
  const double d1 = (f(x + h).value - f(x - h).value) / (2 * h);
  const double d2 = (f(x + h).d1 - f(x - h).d1) / (2 * h);
  CHECK(e.d1 == Approx(d1).epsilon(1e-7).margin(1e-9));
  CHECK(e.d2 == Approx(d2).epsilon(1e-6).margin(1e-6));
}

}  // namespace

TEST_CASE("joint limits: a one-sided quadratic penalty outside [lower, upper]",
          "[energies][joint]") {
  const double k = 250.0;
  const auto f = [&](double x) { return JointLimitEnergy(x, -0.5, 0.75, k); };
  CHECK(f(0.1).value == 0.0);
  CHECK(f(0.1).d1 == 0.0);
  CHECK(f(1.0).value == Approx(0.5 * k * 0.25 * 0.25).epsilon(1e-14));
  CHECK(f(-0.7).d1 == Approx(k * -0.2).epsilon(1e-14));
  for (double x : {-0.9, -0.2, 0.3, 0.9, 2.0}) CheckDerivatives(f, x);
  // No limit on an infinite side.
  CHECK(JointLimitEnergy(1e6, -kInf, kInf, k).value == 0.0);
}

TEST_CASE("a PD drive's potential: quadratic, linear past its force limit, convex",
          "[energies][joint]") {
  const double a = 40.0, xEq = 0.3;
  SECTION("no force limit") {
    const auto f = [&](double x) { return DriveEnergy(x, xEq, a, kInf); };
    CHECK(f(1.3).value == Approx(0.5 * a).epsilon(1e-14));
    for (double x : {-1.0, 0.2, 0.3, 5.0}) CheckDerivatives(f, x);
  }
  SECTION("a force limit") {
    const double fmax = 8.0;  // reached at |x − x_eq| = 0.2
    const auto f = [&](double x) { return DriveEnergy(x, xEq, a, fmax); };
    CHECK(f(0.4).value == Approx(0.5 * a * 0.01).epsilon(1e-14));
    CHECK(f(1.3).value == Approx(fmax * (1.0 - 0.1)).epsilon(1e-14));
    CHECK(f(0.5 + 1e-12).value == Approx(f(0.5 - 1e-12).value).epsilon(1e-10));
    for (double x : {-2.0, 0.0, 0.25, 0.45, 0.6, 3.0}) {
      CheckDerivatives(f, x);
      CHECK(std::abs(f(x).d1) <= fmax);
      CHECK(f(x).d2 >= 0.0);
    }
  }
}
