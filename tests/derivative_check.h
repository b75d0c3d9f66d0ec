// One derivative checker for every energy term (STYLE.md habit 5): compares an analytic gradient
// and Hessian at a state with central differences of the value along tangent steps d.
#pragma once

#include <Eigen/Core>
#include <algorithm>

#include "optim/finite_difference.h"

namespace superdex::test {

struct DerivativeCheck {
  double gradientError = 0.0;  ///< ‖g − g_fd‖ / ‖g_fd‖
  double hessianError = 0.0;   ///< ‖H − H_fd‖ / ‖H_fd‖
};

/// f(d) is the value at the state retracted by the tangent step d. g and H are the analytic
/// derivatives at d = 0. Gradient: central differences with step h. Hessian: the four-point
/// second difference [f(hi+hj) − f(hi−hj) − f(−hi+hj) + f(−hi−hj)] / 4h² (diagonal: the
/// three-point formula with step 2h), which avoids the noise of differencing differences.
inline DerivativeCheck CheckDerivatives(const ScalarFunction& f, const Eigen::VectorXd& g,
                                        const Eigen::MatrixXd& H, double h) {
  const Eigen::Index n = g.size();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd gfd = FiniteDifferenceGradient(f, zero, h);
  Eigen::MatrixXd Hfd(n, n);
  const double f0 = f(zero);
  Eigen::VectorXd d = zero;
  for (Eigen::Index i = 0; i < n; ++i) {
    d.setZero();
    d[i] = 2 * h;
    const double fp = f(d);
    d[i] = -2 * h;
    const double fm = f(d);
    Hfd(i, i) = (fp - 2 * f0 + fm) / (4 * h * h);
    for (Eigen::Index j = 0; j < i; ++j) {
      double s = 0.0;
      for (int a = -1; a <= 1; a += 2)
        for (int b = -1; b <= 1; b += 2) {
          d.setZero();
          d[i] = a * h;
          d[j] = b * h;
          s += a * b * f(d);
        }
      Hfd(i, j) = Hfd(j, i) = s / (4 * h * h);
    }
  }
  DerivativeCheck c;
  c.gradientError = (g - gfd).norm() / std::max(gfd.norm(), 1e-300);
  c.hessianError = (H - Hfd).norm() / std::max(Hfd.norm(), 1e-300);
  return c;
}

}  // namespace superdex::test
