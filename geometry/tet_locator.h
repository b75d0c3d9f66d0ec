// Point location in a tetrahedral mesh at its current (deformed) node positions: which tet
// contains a point, and the point's barycentric coordinates in it.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace superdex {

/// A uniform grid over the tets' bounding boxes, rebuilt in O(#tets) per configuration.
class TetLocator {
 public:
  /// x: node positions stacked [x_0; x_1; …] (3n) [m]; tets: node indices. The cell size is the
  /// mean tet bounding-box diagonal. The locator keeps references to neither.
  void Build(const Eigen::VectorXd& x, const std::vector<Eigen::Vector4i>& tets);

  /// The lowest-numbered tet whose closed domain contains p (barycentric coordinates >= −1e-12;
  /// degenerate or inverted tets are skipped), with λ (Σ λ = 1), or −1 when p lies in no tet.
  int Locate(const Eigen::Vector3d& p, Eigen::Vector4d* lambda) const;

  /// Barycentric coordinates of p with respect to tet t (the tet's affine map extended to all of
  /// space); false when the tet is degenerate.
  bool Barycentric(int t, const Eigen::Vector3d& p, Eigen::Vector4d* lambda) const;

 private:
  Eigen::Vector3i Cell(const Eigen::Vector3d& p) const;

  std::vector<Eigen::Matrix3d> inverse_;  // per tet: Ds⁻¹
  std::vector<Eigen::Vector3d> origin_;   // per tet: x_0
  std::vector<char> valid_;
  Eigen::Vector3d lo_ = Eigen::Vector3d::Zero();
  double cell_ = 1.0;
  Eigen::Vector3i dims_ = Eigen::Vector3i::Ones();
  std::vector<int> start_, items_;  // CSR: cell → tets overlapping it
};

}  // namespace superdex
