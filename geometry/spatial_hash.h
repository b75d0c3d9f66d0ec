// A spatial hash over points for fixed-radius neighbour queries (the PointCloud collider's broad
// phase, core/contact/point_cloud.h). Points are binned into cubic cells of side h [m]; a cell
// (i, j, k) = floor(p / h) goes to bucket H(i, j, k) mod T, with the table size T the smallest
// power of two >= n / loadFactor (the spec's spatialHashLoadFactor: points per bucket). Buckets
// are filled by a counting sort in point order, so a query visits its points in a fixed order
// (cells in lexicographic order, points ascending within a cell): the sums over them are
// deterministic. Cells that share a bucket are told apart by the cell each point is stored with.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace superdex {

class SpatialHash {
 public:
  /// Bins `points` (n of them) into cells of side `cell` [m] (> 0) over a table of at least
  /// n / loadFactor buckets (loadFactor > 0). The points are copied where needed (cells only).
  void Build(const std::vector<Eigen::Vector3d>& points, double cell, double loadFactor);

  /// Calls visit(i) once for every point i in the cells that the box [c − r, c + r] overlaps (a
  /// superset of the points within distance r of c), cells in lexicographic order and points
  /// ascending within a cell. A query box of more cells than there are points walks the points
  /// instead (in index order, those inside the box's cells).
  template <typename Visit>
  void ForEachNear(const Eigen::Vector3d& c, double r, Visit&& visit) const {
    if (cellOf_.empty()) return;
    const Cell lo = CellOf(c - Eigen::Vector3d::Constant(r));
    const Cell hi = CellOf(c + Eigen::Vector3d::Constant(r));
    double cells = 1.0;
    for (int a = 0; a < 3; ++a) cells *= double(hi[a] - lo[a] + 1);
    if (cells > double(cellOf_.size())) {
      for (size_t i = 0; i < cellOf_.size(); ++i) {
        const Cell& p = cellOf_[i];
        if (p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] && p[2] >= lo[2] &&
            p[2] <= hi[2])
          visit(static_cast<int>(i));
      }
      return;
    }
    Cell q;
    for (q[0] = lo[0]; q[0] <= hi[0]; ++q[0])
      for (q[1] = lo[1]; q[1] <= hi[1]; ++q[1])
        for (q[2] = lo[2]; q[2] <= hi[2]; ++q[2]) {
          const size_t b = Bucket(q);
          for (int e = start_[b]; e < start_[b + 1]; ++e)
            if (cellOf_[items_[e]] == q) visit(items_[e]);
        }
  }

  size_t NumBuckets() const { return start_.empty() ? 0 : start_.size() - 1; }
  double CellSize() const { return cell_; }

 private:
  using Cell = std::array<int64_t, 3>;
  Cell CellOf(const Eigen::Vector3d& p) const {
    return {static_cast<int64_t>(std::floor(p[0] / cell_)),
            static_cast<int64_t>(std::floor(p[1] / cell_)),
            static_cast<int64_t>(std::floor(p[2] / cell_))};
  }
  size_t Bucket(const Cell& c) const {
    const uint64_t h = static_cast<uint64_t>(c[0]) * 73856093ull ^
                       static_cast<uint64_t>(c[1]) * 19349663ull ^
                       static_cast<uint64_t>(c[2]) * 83492791ull;
    return static_cast<size_t>(h & mask_);
  }
  double cell_ = 1.0;
  uint64_t mask_ = 0;
  std::vector<Cell> cellOf_;   // per point
  std::vector<int> start_;     // per bucket: its first entry in items_ (T + 1 entries)
  std::vector<int> items_;     // point indices, bucket by bucket, ascending within one
  std::vector<int> fill_;      // Build's cursor per bucket (kept: no allocation once sized)
};

}  // namespace superdex
