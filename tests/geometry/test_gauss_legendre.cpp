// Every Gauss–Legendre rule integrates every monomial up to degree 2n − 1 exactly on [−1, 1]
// (∫ x^k = 2/(k + 1) for even k, 0 for odd), and not degree 2n (the rule's error there is
// nonzero, so the test could fail for a rule of lower degree).
#include <catch2/catch.hpp>
#include <cmath>

#include "geometry/gauss_legendre.h"

using namespace superdex;

namespace {

double Moment(int k) { return k % 2 ? 0.0 : 2.0 / (k + 1); }

double Apply(const GaussLegendreRule& rule, int k) {
  double sum = 0.0;
  for (size_t i = 0; i < rule.nodes.size(); ++i) sum += rule.weights[i] * std::pow(rule.nodes[i], k);
  return sum;
}

}  // namespace

TEST_CASE("gauss-legendre: n points integrate degree 2n - 1 exactly, not 2n", "[quadrature]") {
  for (int n = 1; n <= kMaxGaussLegendrePoints; ++n) {
    const GaussLegendreRule& rule = GaussLegendre(n);
    REQUIRE(static_cast<int>(rule.nodes.size()) == n);
    for (int i = 0; i < n; ++i) {
      CHECK(rule.weights[i] > 0.0);
      CHECK(std::abs(rule.nodes[i]) < 1.0);
      if (i > 0) CHECK(rule.nodes[i] > rule.nodes[i - 1]);
      CHECK(rule.nodes[i] == Approx(-rule.nodes[n - 1 - i]).margin(1e-15));  // symmetric
    }
    for (int k = 0; k <= 2 * n - 1; ++k) {
      INFO("n = " << n << ", degree " << k);
      CHECK(Apply(rule, k) == Approx(Moment(k)).margin(2e-15));
    }
    INFO("n = " << n << ", degree " << 2 * n);
    CHECK(std::abs(Apply(rule, 2 * n) - Moment(2 * n)) > 1e-12);  // n = 16: 7e-10
  }
}

TEST_CASE("gauss-legendre: n outside 1..max is clamped into the range", "[quadrature]") {
  CHECK(GaussLegendre(0).nodes.size() == 1);
  CHECK(GaussLegendre(kMaxGaussLegendrePoints + 5).nodes.size() == size_t(kMaxGaussLegendrePoints));
}
