// Axis-aligned bounding boxes.
#pragma once

#include <Eigen/Core>
#include <limits>

namespace superdex {

struct Aabb {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  bool IsEmpty() const { return (min.array() > max.array()).any(); }
  void Extend(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void Extend(const Aabb& o) {
    min = min.cwiseMin(o.min);
    max = max.cwiseMax(o.max);
  }
  void Inflate(double r) {
    min.array() -= r;
    max.array() += r;
  }
  bool Overlaps(const Aabb& o) const {
    return (min.array() <= o.max.array()).all() && (o.min.array() <= max.array()).all();
  }
  /// Whether the point p lies in the closed box.
  bool Contains(const Eigen::Vector3d& p) const {
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
  }
  /// Whether the ball of centre c and radius r [m] meets the box.
  bool TouchesBall(const Eigen::Vector3d& c, double r) const {
    return (c.cwiseMax(min).cwiseMin(max) - c).squaredNorm() <= r * r;
  }
  static Aabb Everything() {
    Aabb b;
    b.min.setConstant(-std::numeric_limits<double>::infinity());
    b.max.setConstant(std::numeric_limits<double>::infinity());
    return b;
  }
};

}  // namespace superdex
