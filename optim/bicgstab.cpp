#include "optim/bicgstab.h"

#include <cmath>
#include <limits>

namespace superdex {

BiCgStabResult SolveBiCgStab(const RowOperator& A, const BlockJacobi& M, const Eigen::VectorXd& b,
                             double tolerance, int maxIterations, Eigen::VectorXd* xOut,
                             BiCgStabWorkspace* work) {
  BiCgStabResult out;
  const Eigen::Index n = b.size();
  Eigen::VectorXd& x = *xOut;
  x.setZero(n);
  const double bNorm2 = b.squaredNorm();
  if (bNorm2 == 0.0) {
    out.converged = true;
    return out;
  }
  BiCgStabWorkspace& w = *work;
  Eigen::VectorXd &r = w.r, &shadow = w.shadow, &p = w.p, &v = w.v, &y = w.y, &z = w.z,
                  &s = w.s, &t = w.t;
  r = b;  // b − A x at x = 0
  shadow = r;
  p.setZero(n);
  v.setZero(n);
  y.resize(n);
  z.resize(n);
  s.resize(n);
  t.resize(n);
  double shadowNorm2 = shadow.squaredNorm();
  const double tol2 = tolerance * tolerance * bNorm2;
  const double eps = std::numeric_limits<double>::epsilon();
  double rho = 1.0, alpha = 1.0, omega = 1.0;
  int i = 0;
  while (r.squaredNorm() > tol2 && i < maxIterations) {
    const double rhoOld = rho;
    rho = shadow.dot(r);
    if (std::abs(rho) < eps * eps * shadowNorm2) {
      A.Multiply(x.data(), t.data());  // t as scratch: r = b − A x
      r = b - t;
      shadow = r;
      rho = shadowNorm2 = r.squaredNorm();
    }
    const double beta = (rho / rhoOld) * (alpha / omega);
    p = r + beta * (p - omega * v);
    M.Apply(p, &y);
    A.Multiply(y.data(), v.data());
    alpha = rho / shadow.dot(v);
    s = r - alpha * v;
    M.Apply(s, &z);
    A.Multiply(z.data(), t.data());
    const double tt = t.squaredNorm();
    omega = tt > 0.0 ? t.dot(s) / tt : 0.0;
    x += alpha * y + omega * z;
    r = s - omega * t;
    ++i;
  }
  out.iterations = i;
  out.relativeResidual = std::sqrt(r.squaredNorm() / bNorm2);
  out.converged = r.squaredNorm() <= tol2;
  return out;
}

}  // namespace superdex
