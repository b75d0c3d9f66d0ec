// Gauss–Legendre rules on an interval: n points exact for polynomials of degree 2n − 1.
#pragma once

#include <vector>

namespace superdex {

/// The n-point rule on [−1, 1]: nodes ascending, weights positive and summing to 2, so that
/// ∫_{−1}^{1} f dx ≈ Σ_i w_i f(x_i), exact for degree 2n − 1.
struct GaussLegendreRule {
  std::vector<double> nodes;
  std::vector<double> weights;
};

/// The largest n GaussLegendre serves.
constexpr int kMaxGaussLegendrePoints = 16;

/// The n-point rule, 1 <= n <= kMaxGaussLegendrePoints (clamped into that range); built once,
/// valid for the program's lifetime, thread-safe. Nodes are the roots of P_n found by Newton's
/// method from Tricomi's estimate to round-off, weights 2 / ((1 − x²) P_n'(x)²).
const GaussLegendreRule& GaussLegendre(int n);

}  // namespace superdex
