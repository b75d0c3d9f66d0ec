// A signed distance field sampled on a regular grid and evaluated by trilinear interpolation.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "geometry/analytic_sdf.h"

namespace superdex {

class GridSdf {
 public:
  /// Samples φ at the nodes origin + h (i, j, k), 0 <= i < nodes.x() (and so on); nodes >= 2.
  static GridSdf Build(const std::function<double(const Eigen::Vector3d&)>& phi,
                       const Eigen::Vector3d& origin, double h, const Eigen::Vector3i& nodes);

  /// Inside the grid box: the trilinear interpolant, its gradient and its Hessian (mixed second
  /// derivatives only: the interpolant is linear along each axis). Outside, the continuous
  /// extension Φ(X) = Φ_grid(p) + |X − p| with p the closest point of the box, differentiated
  /// exactly (grid derivatives along the axes where X is inside the box's slab, the distance to
  /// the box along the others). [m, -, 1/m]
  SdfSample Evaluate(const Eigen::Vector3d& X) const;

  const Eigen::Vector3d& Origin() const { return origin_; }
  double Spacing() const { return h_; }
  const Eigen::Vector3i& Nodes() const { return n_; }
  /// Bytes held by the node values.
  size_t MemoryBytes() const { return values_.size() * sizeof(double); }

 private:
  double At(int i, int j, int k) const { return values_[(size_t(k) * n_.y() + j) * n_.x() + i]; }
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double h_ = 1.0;
  Eigen::Vector3i n_ = Eigen::Vector3i::Constant(2);
  std::vector<double> values_;
};

}  // namespace superdex
