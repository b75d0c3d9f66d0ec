// Broad phase: which actor bounding boxes overlap (spec: "Contact Pipeline", step 1).
#pragma once

#include <utility>
#include <vector>

#include "geometry/aabb.h"

namespace superdex {

/// Unordered pairs (i < j) of overlapping boxes, by sweep and prune along the axis of largest
/// spread: O(n log n + k) for n finite boxes and k overlaps. Boxes with an infinite extent
/// (planes) are paired with every other box. Empty boxes overlap nothing. Output is sorted, so the
/// result does not depend on the input's internal ordering choices. Up to 8 boxes every pair is
/// tested directly.
void FindOverlappingPairs(const std::vector<Aabb>& boxes, std::vector<std::pair<int, int>>* pairs);

}  // namespace superdex
