#include "optim/finite_difference.h"

namespace superdex {

Eigen::VectorXd FiniteDifferenceGradient(const ScalarFunction& f, const Eigen::VectorXd& x,
                                         double h) {
  Eigen::VectorXd g(x.size());
  Eigen::VectorXd xp = x;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    xp[i] = x[i] + h;
    const double fp = f(xp);
    xp[i] = x[i] - h;
    const double fm = f(xp);
    xp[i] = x[i];
    g[i] = (fp - fm) / (2.0 * h);
  }
  return g;
}

Eigen::MatrixXd FiniteDifferenceJacobian(const VectorFunction& F, const Eigen::VectorXd& x,
                                         double h) {
  Eigen::VectorXd xp = x;
  Eigen::MatrixXd J;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    xp[i] = x[i] + h;
    const Eigen::VectorXd fp = F(xp);
    xp[i] = x[i] - h;
    const Eigen::VectorXd fm = F(xp);
    xp[i] = x[i];
    if (i == 0) J.resize(fp.size(), x.size());
    J.col(i) = (fp - fm) / (2.0 * h);
  }
  return J;
}

}  // namespace superdex
