#include "geometry/grid_sdf.h"

#include <algorithm>
#include <cmath>

namespace superdex {

GridSdf GridSdf::Build(const std::function<double(const Eigen::Vector3d&)>& phi,
                       const Eigen::Vector3d& origin, double h, const Eigen::Vector3i& nodes) {
  GridSdf g;
  g.origin_ = origin;
  g.h_ = h;
  g.n_ = nodes.cwiseMax(2);
  g.values_.resize(size_t(g.n_.x()) * g.n_.y() * g.n_.z());
  size_t idx = 0;
  for (int k = 0; k < g.n_.z(); ++k)
    for (int j = 0; j < g.n_.y(); ++j)
      for (int i = 0; i < g.n_.x(); ++i)
        g.values_[idx++] = phi(origin + h * Eigen::Vector3d(i, j, k));
  return g;
}

SdfSample GridSdf::Evaluate(const Eigen::Vector3d& X) const {
  const Eigen::Vector3d hi = origin_ + h_ * (n_ - Eigen::Vector3i::Ones()).cast<double>();
  const Eigen::Vector3d p = X.cwiseMax(origin_).cwiseMin(hi);
  // Cell and local coordinates of p.
  int c[3];
  double u[3];
  for (int a = 0; a < 3; ++a) {
    const double t = (p[a] - origin_[a]) / h_;
    c[a] = std::min(std::max(static_cast<int>(std::floor(t)), 0), n_[a] - 2);
    u[a] = t - c[a];
  }
  double v[2][2][2];
  for (int dk = 0; dk < 2; ++dk)
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di) v[di][dj][dk] = At(c[0] + di, c[1] + dj, c[2] + dk);
  // f(u) = Σ v_ijk Π_a (i_a ? u_a : 1 − u_a)
  auto w = [&](int bit, int a) { return bit ? u[a] : 1.0 - u[a]; };
  auto dw = [](int bit) { return bit ? 1.0 : -1.0; };
  SdfSample s;
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) {
        const double val = v[i][j][k];
        s.value += val * w(i, 0) * w(j, 1) * w(k, 2);
        g.x() += val * dw(i) * w(j, 1) * w(k, 2);
        g.y() += val * w(i, 0) * dw(j) * w(k, 2);
        g.z() += val * w(i, 0) * w(j, 1) * dw(k);
        H(0, 1) += val * dw(i) * dw(j) * w(k, 2);
        H(0, 2) += val * dw(i) * w(j, 1) * dw(k);
        H(1, 2) += val * w(i, 0) * dw(j) * dw(k);
      }
  s.gradient = g / h_;
  H(1, 0) = H(0, 1);
  H(2, 0) = H(0, 2);
  H(2, 1) = H(1, 2);
  s.hessian = H / (h_ * h_);
  const Eigen::Vector3d out = X - p;
  const double dist = out.norm();
  if (dist == 0.0) return s;
  // Outside: Φ = Φ_grid(p) + |X − p|.
  const Eigen::Vector3d n = out / dist;
  s.value += dist;
  for (int a = 0; a < 3; ++a) {
    const bool clamped = out[a] != 0.0;
    if (clamped) s.gradient[a] = n[a];
    for (int b = 0; b < 3; ++b) {
      const bool clampedB = out[b] != 0.0;
      if (clamped && clampedB) {
        s.hessian(a, b) = ((a == b ? 1.0 : 0.0) - n[a] * n[b]) / dist;
      } else if (clamped || clampedB) {
        s.hessian(a, b) = 0.0;
      }
    }
  }
  return s;
}

}  // namespace superdex
