#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "energies/penalty_ramp.h"

using namespace superdex;

namespace {
constexpr double kEps = 0.005, kDelta = 0.001;
// φ at the ramp joins: z = −φ − (ε − δ) = ±ε.
constexpr double kPhiStart = kDelta;             // z = −ε
constexpr double kPhiLinear = kDelta - 2 * kEps; // z = +ε
}  // namespace

TEST_CASE("ramp: s-form equals the spec's z-polynomial", "[energies][ramp]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(kDelta - 3 * kEps, kDelta + kEps);
  for (int i = 0; i < 2000; ++i) {
    const double phi = u(rng);
    const double a = PenaltyRamp(phi, kEps, kDelta).h;
    const double b = PenaltyRampSpecForm(phi, kEps, kDelta);
    REQUIRE(a == Approx(b).margin(1e-17).epsilon(1e-12));
  }
}

TEST_CASE("ramp: regimes below, in and above the smoothing band", "[energies][ramp]") {
  SECTION("zero for phi >= delta") {
    for (double phi : {kDelta, kDelta + 1e-9, 0.01, 1.0}) {
      const RampValue r = PenaltyRamp(phi, kEps, kDelta);
      CHECK(r.h == 0.0);
      CHECK(r.dh == 0.0);
      CHECK(r.d2h == 0.0);
    }
  }
  SECTION("linear in penetration below the band") {
    for (double phi : {kPhiLinear, kPhiLinear - 1e-6, -0.1}) {
      const RampValue r = PenaltyRamp(phi, kEps, kDelta);
      CHECK(r.h == Approx(-phi - (kEps - kDelta)).epsilon(1e-14));
      CHECK(r.dh == 1.0);
      CHECK(r.d2h == 0.0);
    }
  }
  SECTION("inside the band: positive, increasing, convex") {
    for (double t = 0.01; t < 1.0; t += 0.01) {
      const double phi = kDelta - t * 2 * kEps;
      const RampValue r = PenaltyRamp(phi, kEps, kDelta);
      CHECK(r.h > 0.0);
      CHECK(r.dh > 0.0);
      CHECK(r.dh < 1.0);
      CHECK(r.d2h > 0.0);
    }
  }
}

TEST_CASE("ramp: C2 continuity at both joins z = ±eps", "[energies][ramp]") {
  for (double phi0 : {kPhiStart, kPhiLinear}) {
    const double t = 1e-9;
    const RampValue a = PenaltyRamp(phi0 + t, kEps, kDelta);
    const RampValue b = PenaltyRamp(phi0 - t, kEps, kDelta);
    CHECK(std::abs(a.h - b.h) < 1e-8);
    CHECK(std::abs(a.dh - b.dh) < 1e-6);
    CHECK(std::abs(a.d2h - b.d2h) < 1e-4);  // d2h scale 3/(4ε) = 150 [1/m]
  }
  // Exact one-sided values at the joins.
  const RampValue start = PenaltyRamp(kPhiStart - 1e-15, kEps, kDelta);
  CHECK(start.h == Approx(0.0).margin(1e-30));
  const RampValue lin = PenaltyRamp(kPhiLinear + 1e-13, kEps, kDelta);
  CHECK(lin.h == Approx(kEps).epsilon(1e-10));
  CHECK(lin.dh == Approx(1.0).epsilon(1e-10));
  CHECK(lin.d2h == Approx(0.0).margin(1e-8));
}

TEST_CASE("ramp: derivatives match finite differences across the band", "[energies][ramp]") {
  const double h = 1e-7;
  for (double phi = kDelta - 2.5 * kEps; phi < kDelta + 0.5 * kEps; phi += kEps / 37.0) {
    const RampValue r = PenaltyRamp(phi, kEps, kDelta);
    // dh/dψ with ψ = −φ.
    const double dfd =
        -(PenaltyRamp(phi + h, kEps, kDelta).h - PenaltyRamp(phi - h, kEps, kDelta).h) / (2 * h);
    const double d2fd =
        (PenaltyRamp(phi + h, kEps, kDelta).dh - PenaltyRamp(phi - h, kEps, kDelta).dh) /
        (-2 * h);
    CHECK(r.dh == Approx(dfd).margin(1e-7));
    CHECK(r.d2h == Approx(d2fd).margin(1e-4));
  }
}
