// Broad phase: which actor bounding boxes overlap (spec: "Contact Pipeline", step 1).
#pragma once

#include <utility>
#include <vector>

#include "geometry/aabb.h"

namespace superdex {

/// Unordered pairs (i < j) of overlapping boxes, by sweep and prune along the axis of largest
/// spread: O(n log n + k) for n finite boxes and k overlaps. Boxes with an infinite extent
/// (planes' half-spaces) are tested against every other box. Empty boxes overlap nothing. Output
/// is sorted, so the result does not depend on the input's internal ordering choices. Up to 8
/// boxes every pair is tested directly.
void FindOverlappingPairs(const std::vector<Aabb>& boxes, std::vector<std::pair<int, int>>* pairs);

/// FindOverlappingPairs over boxes that move a little between calls (the evaluations of a
/// stage). The sweep runs over fat boxes — each box grown by kFatFraction of its largest side —
/// and its candidate pairs are kept; while every box stays inside its fat box, a call only keeps
/// the candidates whose boxes overlap, which is exactly the set (and the order) FindOverlappingPairs
/// gives. A box that leaves its fat box makes the next call sweep again. Up to 8 boxes every call
/// tests every pair directly, as FindOverlappingPairs does.
class OverlapCache {
 public:
  static constexpr double kFatFraction = 0.25;
  void Find(const std::vector<Aabb>& boxes, std::vector<std::pair<int, int>>* pairs);
  /// Calls that swept, for tests and benchmarks.
  long sweeps() const { return sweeps_; }

 private:
  std::vector<Aabb> fat_;
  std::vector<std::pair<int, int>> candidates_;
  long sweeps_ = 0;
};

}  // namespace superdex
