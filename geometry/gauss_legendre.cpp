#include "geometry/gauss_legendre.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace superdex {

namespace {

// P_n(x) and P_n'(x) by the three-term recurrence.
void Legendre(int n, double x, double* p, double* dp) {
  double p0 = 1.0, p1 = x;
  for (int k = 2; k <= n; ++k) {
    const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  *p = n == 0 ? 1.0 : p1;
  *dp = n * (x * *p - p0) / (x * x - 1.0);
}

GaussLegendreRule Build(int n) {
  GaussLegendreRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  for (int i = 0; i < n; ++i) {
    // Tricomi's estimate of the i-th largest root, then Newton to round-off.
    double x = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double p = 0.0, dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      Legendre(n, x, &p, &dp);
      const double dx = p / dp;
      x -= dx;
      if (std::abs(dx) <= 1e-16) break;
    }
    Legendre(n, x, &p, &dp);
    rule.nodes[n - 1 - i] = x;
    rule.weights[n - 1 - i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return rule;
}

}  // namespace

const GaussLegendreRule& GaussLegendre(int n) {
  static const std::array<GaussLegendreRule, kMaxGaussLegendrePoints> rules = [] {
    std::array<GaussLegendreRule, kMaxGaussLegendrePoints> r;
    for (int k = 1; k <= kMaxGaussLegendrePoints; ++k) r[k - 1] = Build(k);
    return r;
  }();
  return rules[std::clamp(n, 1, kMaxGaussLegendrePoints) - 1];
}

}  // namespace superdex
