// Triangle quadrature rules: structure (weights, barycentrics, symmetry) and polynomial exactness.
//
// Exact integrals are computed independently of the implementation: x^a y^b z^c on a skewed
// triangle is expanded in barycentric coordinates (x = Σ_m λ_m v_m) and integrated term by term
// with  ∫_T λ1^i λ2^j λ3^k dA = 2A i! j! k!/(i+j+k+2)!,  in long double.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <string>

#include "geometry/quadrature.h"

using namespace superdex;

namespace {

using Real = long double;

struct RuleCase {
  ActorBoundaryElementType type;
  const char* name;
  int points;
  int degree;
};

const RuleCase kRules[] = {
    {ActorBoundaryElementType::P1Q1, "P1Q1", 1, 1},
    {ActorBoundaryElementType::P1Q3, "P1Q3", 3, 2},
    {ActorBoundaryElementType::P1Q6, "P1Q6", 6, 4},
    {ActorBoundaryElementType::ExperimentalP1Q7, "ExperimentalP1Q7", 7, 5},
    {ActorBoundaryElementType::ExperimentalP1Q12, "ExperimentalP1Q12", 12, 6},
    {ActorBoundaryElementType::ExperimentalP1Q16, "ExperimentalP1Q16", 16, 8},
};

Real Factorial(int n) { return n <= 1 ? Real(1) : n * Factorial(n - 1); }

// Polynomial in barycentric coordinates: exponents (i, j, k) -> coefficient.
using BaryPoly = std::map<std::array<int, 3>, Real>;

BaryPoly Multiply(const BaryPoly& a, const BaryPoly& b) {
  BaryPoly out;
  for (const auto& [ea, ca] : a)
    for (const auto& [eb, cb] : b) out[{ea[0] + eb[0], ea[1] + eb[1], ea[2] + eb[2]}] += ca * cb;
  return out;
}

// The skewed test triangle.
const Eigen::Vector3d kTri[3] = {{0.1, -0.2, 0.3}, {1.7, 0.4, -0.5}, {0.3, 1.9, 0.8}};

Real TriangleArea() {
  const Eigen::Matrix<Real, 3, 1> e1 = (kTri[1] - kTri[0]).cast<Real>();
  const Eigen::Matrix<Real, 3, 1> e2 = (kTri[2] - kTri[0]).cast<Real>();
  return e1.cross(e2).norm() / 2;
}

// ∫_T x^a y^b z^c dA, exactly up to long-double round-off.
Real ExactMonomial(int a, int b, int c) {
  auto linear = [](int d) {  // x_d = Σ_m λ_m v_m[d]
    return BaryPoly{{{1, 0, 0}, Real(kTri[0][d])},
                    {{0, 1, 0}, Real(kTri[1][d])},
                    {{0, 0, 1}, Real(kTri[2][d])}};
  };
  BaryPoly p{{{0, 0, 0}, Real(1)}};
  for (int i = 0; i < a; ++i) p = Multiply(p, linear(0));
  for (int i = 0; i < b; ++i) p = Multiply(p, linear(1));
  for (int i = 0; i < c; ++i) p = Multiply(p, linear(2));
  const Real area = TriangleArea();
  Real sum = 0;
  for (const auto& [e, coef] : p)
    sum += coef * 2 * area * Factorial(e[0]) * Factorial(e[1]) * Factorial(e[2]) /
           Factorial(e[0] + e[1] + e[2] + 2);
  return sum;
}

// area · Σ_q w_q f(x_q) evaluated in precision T: double, as a caller would, or long double, to
// separate the rule's own error from evaluation round-off.
template <typename T>
T RuleMonomial(const TriangleQuadratureRule& r, int a, int b, int c) {
  using V = Eigen::Matrix<T, 3, 1>;
  const T area = static_cast<T>(TriangleArea());
  T sum = 0;
  for (size_t q = 0; q < r.weights.size(); ++q) {
    const V l = r.barycentric[q].cast<T>();
    const V x = l[0] * kTri[0].cast<T>() + l[1] * kTri[1].cast<T>() + l[2] * kTri[2].cast<T>();
    T f = static_cast<T>(r.weights[q]);
    for (int k = 0; k < a; ++k) f *= x[0];
    for (int k = 0; k < b; ++k) f *= x[1];
    for (int k = 0; k < c; ++k) f *= x[2];
    sum += f;
  }
  return area * sum;
}

// Largest relative error over all monomials of total degree exactly `deg`.
template <typename T>
double WorstRelativeError(const TriangleQuadratureRule& r, int deg) {
  double worst = 0.0;
  for (int a = 0; a <= deg; ++a)
    for (int b = 0; a + b <= deg; ++b) {
      const int c = deg - a - b;
      const Real exact = ExactMonomial(a, b, c);
      const Real err = std::abs(Real(RuleMonomial<T>(r, a, b, c)) - exact) / std::abs(exact);
      worst = std::max(worst, static_cast<double>(err));
    }
  return worst;
}

}  // namespace

TEST_CASE("quadrature: exact integrals are well conditioned on the skewed triangle",
          "[geometry][quadrature]") {
  // Relative errors below are meaningful only if no exact monomial integral is nearly zero.
  for (int deg = 0; deg <= 9; ++deg)
    for (int a = 0; a <= deg; ++a)
      for (int b = 0; a + b <= deg; ++b) {
        INFO("x^" << a << " y^" << b << " z^" << deg - a - b);
        CHECK(std::abs(ExactMonomial(a, b, deg - a - b)) > 1e-4);
      }
  // Closed-form spot checks of the exact integrator: area and first moments (A · centroid).
  const double area = static_cast<double>(TriangleArea());
  const Eigen::Vector3d centroid = (kTri[0] + kTri[1] + kTri[2]) / 3.0;
  CHECK(static_cast<double>(ExactMonomial(0, 0, 0)) == Approx(area).epsilon(1e-15));
  CHECK(static_cast<double>(ExactMonomial(1, 0, 0)) == Approx(area * centroid.x()).epsilon(1e-15));
  CHECK(static_cast<double>(ExactMonomial(0, 1, 0)) == Approx(area * centroid.y()).epsilon(1e-15));
  CHECK(static_cast<double>(ExactMonomial(0, 0, 1)) == Approx(area * centroid.z()).epsilon(1e-15));
}

TEST_CASE("quadrature: weights, points and symmetry of every rule", "[geometry][quadrature]") {
  for (const RuleCase& rc : kRules) {
    INFO(rc.name);
    const TriangleQuadratureRule& r = GetTriangleQuadratureRule(rc.type);
    CHECK(&r == &GetTriangleQuadratureRule(rc.type));  // built once
    REQUIRE(r.barycentric.size() == r.weights.size());
    REQUIRE(static_cast<int>(r.weights.size()) == rc.points);
    CHECK(r.degree == rc.degree);
    double wsum = 0.0;
    for (size_t q = 0; q < r.weights.size(); ++q) {
      const Eigen::Vector3d& l = r.barycentric[q];
      CHECK(r.weights[q] > 0.0);
      wsum += r.weights[q];
      CHECK(std::abs(l.sum() - 1.0) <= 1e-15);
      CHECK(l.minCoeff() > 0.0);  // strictly inside the triangle
      CHECK(l.maxCoeff() < 1.0);
    }
    CHECK(std::abs(wsum - 1.0) <= 1e-15);
    // Invariant under all 6 permutations of the barycentric coordinates, weights included.
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (size_t q = 0; q < r.weights.size(); ++q)
      for (const auto& p : perms) {
        const Eigen::Vector3d l(r.barycentric[q][p[0]], r.barycentric[q][p[1]],
                                r.barycentric[q][p[2]]);
        int matches = 0;
        for (size_t s = 0; s < r.weights.size(); ++s)
          if ((r.barycentric[s] - l).cwiseAbs().maxCoeff() <= 1e-15 &&
              std::abs(r.weights[s] - r.weights[q]) <= 1e-16)
            ++matches;
        CHECK(matches == 1);
      }
  }
}

TEST_CASE("quadrature: every rule is exact to its degree, and not beyond",
          "[geometry][quadrature]") {
  for (const RuleCase& rc : kRules) {
    const TriangleQuadratureRule& r = GetTriangleQuadratureRule(rc.type);
    double worst = 0.0, worstExtended = 0.0;
    for (int deg = 0; deg <= r.degree; ++deg) {
      worst = std::max(worst, WorstRelativeError<double>(r, deg));
      worstExtended = std::max(worstExtended, WorstRelativeError<Real>(r, deg));
    }
    const double above = WorstRelativeError<double>(r, r.degree + 1);
    INFO(rc.name << ": worst relative error up to degree " << r.degree << " = " << worst
                 << " (evaluated in long double: " << worstExtended << "), at degree "
                 << r.degree + 1 << " = " << above);
    CHECK(worst <= 1e-13);
    CHECK(worstExtended <= 1e-14);  // the rule itself, beyond double evaluation round-off
    CHECK(above > 1e-6);            // the degree claim is tight
  }
}

TEST_CASE("quadrature: an invalid element type yields the default P1Q3 rule",
          "[geometry][quadrature]") {
  const auto bogus = static_cast<ActorBoundaryElementType>(42);
  CHECK(&GetTriangleQuadratureRule(bogus) ==
        &GetTriangleQuadratureRule(ActorBoundaryElementType::P1Q3));
}
