#include "geometry/tet_locator.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace superdex {

void TetLocator::Build(const Eigen::VectorXd& x, const std::vector<Eigen::Vector4i>& tets) {
  const int nt = static_cast<int>(tets.size());
  inverse_.resize(nt);
  origin_.resize(nt);
  valid_.assign(nt, 0);
  std::vector<Eigen::Vector3d> bmin(nt), bmax(nt);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  double diag = 0.0;
  for (int t = 0; t < nt; ++t) {
    const Eigen::Vector4i& T = tets[t];
    Eigen::Vector3d p[4];
    for (int a = 0; a < 4; ++a) p[a] = x.segment<3>(3 * T[a]);
    Eigen::Matrix3d Ds;
    Ds << p[1] - p[0], p[2] - p[0], p[3] - p[0];
    const double det = Ds.determinant();
    origin_[t] = p[0];
    bmin[t] = p[0].cwiseMin(p[1]).cwiseMin(p[2]).cwiseMin(p[3]);
    bmax[t] = p[0].cwiseMax(p[1]).cwiseMax(p[2]).cwiseMax(p[3]);
    lo = lo.cwiseMin(bmin[t]);
    hi = hi.cwiseMax(bmax[t]);
    diag += (bmax[t] - bmin[t]).norm();
    if (std::isfinite(det) && det > 0.0) {
      inverse_[t] = Ds.inverse();
      valid_[t] = 1;
    }
  }
  if (nt == 0) {
    start_.assign(2, 0);
    items_.clear();
    dims_.setOnes();
    return;
  }
  cell_ = std::max(diag / nt, 1e-12);
  lo_ = lo;
  for (int k = 0; k < 3; ++k)
    dims_[k] = std::clamp(static_cast<int>((hi[k] - lo[k]) / cell_) + 1, 1, 1 << 10);
  const long cells = long(dims_.x()) * dims_.y() * dims_.z();
  start_.assign(cells + 1, 0);
  auto forEachCell = [&](int t, auto&& f) {
    const Eigen::Vector3i a = Cell(bmin[t]), b = Cell(bmax[t]);
    for (int k = a.z(); k <= b.z(); ++k)
      for (int j = a.y(); j <= b.y(); ++j)
        for (int i = a.x(); i <= b.x(); ++i) f((long(k) * dims_.y() + j) * dims_.x() + i);
  };
  for (int t = 0; t < nt; ++t)
    if (valid_[t]) forEachCell(t, [&](long c) { ++start_[c + 1]; });
  for (long c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  items_.resize(start_[cells]);
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (int t = 0; t < nt; ++t)  // increasing t: each cell's list is sorted
    if (valid_[t]) forEachCell(t, [&](long c) { items_[fill[c]++] = t; });
}

Eigen::Vector3i TetLocator::Cell(const Eigen::Vector3d& p) const {
  Eigen::Vector3i c;
  for (int k = 0; k < 3; ++k)
    c[k] = std::clamp(static_cast<int>(std::floor((p[k] - lo_[k]) / cell_)), 0, dims_[k] - 1);
  return c;
}

bool TetLocator::Barycentric(int t, const Eigen::Vector3d& p, Eigen::Vector4d* lambda) const {
  if (!valid_[t]) return false;
  const Eigen::Vector3d b = inverse_[t] * (p - origin_[t]);
  *lambda << 1.0 - b.sum(), b;
  return true;
}

int TetLocator::Locate(const Eigen::Vector3d& p, Eigen::Vector4d* lambda) const {
  if (items_.empty()) return -1;
  for (int k = 0; k < 3; ++k) {
    const double u = (p[k] - lo_[k]) / cell_;
    if (!(u >= -1e-9 && u <= dims_[k] + 1e-9)) return -1;  // outside every tet's box (or NaN)
  }
  const Eigen::Vector3i c = Cell(p);
  const long cell = (long(c.z()) * dims_.y() + c.y()) * dims_.x() + c.x();
  for (int i = start_[cell]; i < start_[cell + 1]; ++i) {
    const int t = items_[i];
    Barycentric(t, p, lambda);
    if (lambda->minCoeff() >= -1e-12) return t;
  }
  return -1;
}

}  // namespace superdex
