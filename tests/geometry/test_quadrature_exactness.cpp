// Every triangle rule integrates every monomial up to its degree exactly on a skewed triangle.
// The exact integrals come from the barycentric formula ∫_T λ1^i λ2^j λ3^k dA = 2A i! j! k!/(i+j+k+2)!
// after expanding x^a y^b z^c in barycentric coordinates (exact rational arithmetic in doubles for
// these small degrees).
#include <Eigen/Geometry>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <set>

#include "geometry/quadrature.h"

using namespace superdex;

namespace {

double Factorial(int n) { return n <= 1 ? 1.0 : n * Factorial(n - 1); }

// Polynomial in barycentric coordinates: map (i, j, k) -> coefficient.
using BaryPoly = std::map<std::array<int, 3>, double>;

BaryPoly Multiply(const BaryPoly& a, const BaryPoly& b) {
  BaryPoly out;
  for (const auto& [ea, ca] : a)
    for (const auto& [eb, cb] : b)
      out[{ea[0] + eb[0], ea[1] + eb[1], ea[2] + eb[2]}] += ca * cb;
  return out;
}

double ExactMonomial(const Eigen::Vector3d v[3], int a, int b, int c, double area) {
  // Coordinate axis d as a linear form in λ: x_d = Σ_m λ_m v_m[d].
  auto linear = [&](int d) {
    return BaryPoly{{{1, 0, 0}, v[0][d]}, {{0, 1, 0}, v[1][d]}, {{0, 0, 1}, v[2][d]}};
  };
  BaryPoly p{{{0, 0, 0}, 1.0}};
  for (int i = 0; i < a; ++i) p = Multiply(p, linear(0));
  for (int i = 0; i < b; ++i) p = Multiply(p, linear(1));
  for (int i = 0; i < c; ++i) p = Multiply(p, linear(2));
  double sum = 0.0;
  for (const auto& [e, coef] : p)
    sum += coef * 2.0 * area * Factorial(e[0]) * Factorial(e[1]) * Factorial(e[2]) /
           Factorial(e[0] + e[1] + e[2] + 2);
  return sum;
}

double RuleMonomial(const TriangleQuadratureRule& r, const Eigen::Vector3d v[3], int a, int b,
                    int c, double area) {
  double sum = 0.0;
  for (size_t q = 0; q < r.weights.size(); ++q) {
    const Eigen::Vector3d& l = r.barycentric[q];
    const Eigen::Vector3d x = l[0] * v[0] + l[1] * v[1] + l[2] * v[2];
    sum += r.weights[q] * std::pow(x[0], a) * std::pow(x[1], b) * std::pow(x[2], c);
  }
  return area * sum;
}

}  // namespace

TEST_CASE("triangle rules: exact to their degree on a skewed triangle", "[geometry][quadrature]") {
  const Eigen::Vector3d v[3] = {{0.1, -0.2, 0.3}, {1.7, 0.4, -0.5}, {0.3, 1.9, 0.8}};
  const double area = 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).norm();
  const std::pair<ActorBoundaryElementType, int> rules[] = {
      {ActorBoundaryElementType::P1Q1, 1},
      {ActorBoundaryElementType::P1Q3, 3},
      {ActorBoundaryElementType::P1Q6, 6},
      {ActorBoundaryElementType::ExperimentalP1Q7, 7},
      {ActorBoundaryElementType::ExperimentalP1Q12, 12},
      {ActorBoundaryElementType::ExperimentalP1Q16, 16}};
  const int expectedDegree[] = {1, 2, 4, 5, 6, 8};
  for (int r = 0; r < 6; ++r) {
    const TriangleQuadratureRule& rule = GetTriangleQuadratureRule(rules[r].first);
    INFO("rule with " << rules[r].second << " points");
    REQUIRE(static_cast<int>(rule.weights.size()) == rules[r].second);
    CHECK(rule.degree == expectedDegree[r]);
    double wsum = 0.0;
    std::set<std::array<long long, 3>> points;
    for (size_t q = 0; q < rule.weights.size(); ++q) {
      CHECK(rule.weights[q] > 0.0);
      wsum += rule.weights[q];
      const Eigen::Vector3d& l = rule.barycentric[q];
      CHECK(l.sum() == Approx(1.0).epsilon(1e-15));
      CHECK(l.minCoeff() > 0.0);
      points.insert({std::llround(l[0] * 1e12), std::llround(l[1] * 1e12), std::llround(l[2] * 1e12)});
    }
    CHECK(wsum == Approx(1.0).epsilon(1e-15));
    // Symmetric: the point set is invariant under permutations of the barycentric coordinates.
    for (const auto& p : points) {
      CHECK(points.count({p[1], p[0], p[2]}) == 1);
      CHECK(points.count({p[0], p[2], p[1]}) == 1);
    }
    double worst = 0.0;
    for (int deg = 0; deg <= rule.degree; ++deg)
      for (int a = 0; a <= deg; ++a)
        for (int b = 0; a + b <= deg; ++b) {
          const int c = deg - a - b;
          const double exact = ExactMonomial(v, a, b, c, area);
          const double got = RuleMonomial(rule, v, a, b, c, area);
          const double err = std::abs(got - exact) / std::max(std::abs(exact), 1e-3);
          worst = std::max(worst, err);
        }
    INFO("worst relative error " << worst);
    CHECK(worst <= 1e-13);
    // Tight: some monomial of degree + 1 is not integrated exactly.
    double worstAbove = 0.0;
    const int deg = rule.degree + 1;
    for (int a = 0; a <= deg; ++a)
      for (int b = 0; a + b <= deg; ++b) {
        const int c = deg - a - b;
        const double exact = ExactMonomial(v, a, b, c, area);
        worstAbove = std::max(worstAbove, std::abs(RuleMonomial(rule, v, a, b, c, area) - exact) /
                                              std::max(std::abs(exact), 1e-3));
      }
    CHECK(worstAbove > 1e-8);
  }
}
