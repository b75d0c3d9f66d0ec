#include "geometry/spatial_hash.h"

#include <algorithm>

namespace superdex {

void SpatialHash::Build(const std::vector<Eigen::Vector3d>& points, double cell,
                        double loadFactor) {
  cell_ = cell;
  const size_t n = points.size();
  size_t table = 1;
  const double want = std::max(1.0, std::ceil(double(n) / loadFactor));
  while (double(table) < want) table *= 2;
  mask_ = table - 1;
  cellOf_.resize(n);
  for (size_t i = 0; i < n; ++i) cellOf_[i] = CellOf(points[i]);
  // Counting sort by bucket, in point order (deterministic, ascending within a bucket).
  start_.assign(table + 1, 0);
  for (size_t i = 0; i < n; ++i) ++start_[Bucket(cellOf_[i]) + 1];
  for (size_t b = 0; b < table; ++b) start_[b + 1] += start_[b];
  items_.resize(n);
  fill_.assign(start_.begin(), start_.end() - 1);
  for (size_t i = 0; i < n; ++i) items_[fill_[Bucket(cellOf_[i])]++] = static_cast<int>(i);
}

}  // namespace superdex
