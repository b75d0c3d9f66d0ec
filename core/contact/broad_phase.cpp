#include "core/contact/broad_phase.h"

#include <algorithm>
#include <cmath>

namespace superdex {

namespace {
// A few boxes (a body over a plane, a small stack): every pair is tested directly, already in
// the sorted order of the result; the sweep's setup and sorts cost more than that (a sphere over
// a plane: 460 instructions per call, 11 % of a free-flight drop step with the pair setup), and
// so would keeping candidates.
constexpr int kDirectLimit = 8;
}  // namespace

void FindOverlappingPairs(const std::vector<Aabb>& boxes, std::vector<std::pair<int, int>>* pairs) {
  pairs->clear();
  const int n = static_cast<int>(boxes.size());
  if (n <= kDirectLimit) {
    for (int i = 0; i < n; ++i) {
      if (boxes[i].IsEmpty()) continue;
      for (int j = i + 1; j < n; ++j)
        if (!boxes[j].IsEmpty() && boxes[i].Overlaps(boxes[j])) pairs->emplace_back(i, j);
    }
    return;
  }
  // Scratch kept per thread: the broad phase runs at every evaluation of a stage, and for a few
  // actors these two allocations cost more than the sweep.
  thread_local std::vector<int> finite, infinite;
  finite.clear();
  infinite.clear();
  finite.reserve(n);
  for (int i = 0; i < n; ++i) {
    if (boxes[i].IsEmpty()) continue;
    const bool bounded = boxes[i].min.allFinite() && boxes[i].max.allFinite();
    (bounded ? finite : infinite).push_back(i);
  }
  // Axis of largest spread of the box centres.
  int axis = 0;
  if (!finite.empty()) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
    for (int i : finite) {
      const Eigen::Vector3d c = 0.5 * (boxes[i].min + boxes[i].max);
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
    (hi - lo).maxCoeff(&axis);
  }
  std::sort(finite.begin(), finite.end(), [&](int a, int b) {
    return boxes[a].min[axis] < boxes[b].min[axis] ||
           (boxes[a].min[axis] == boxes[b].min[axis] && a < b);
  });
  for (size_t s = 0; s < finite.size(); ++s) {
    const Aabb& a = boxes[finite[s]];
    for (size_t t = s + 1; t < finite.size(); ++t) {
      const Aabb& b = boxes[finite[t]];
      if (b.min[axis] > a.max[axis]) break;
      if (a.Overlaps(b))
        pairs->emplace_back(std::min(finite[s], finite[t]), std::max(finite[s], finite[t]));
    }
  }
  for (int i : infinite)
    for (int j = 0; j < n; ++j)
      if (j != i && !boxes[j].IsEmpty() && boxes[i].Overlaps(boxes[j])) {
        // Two infinite boxes would be listed twice; keep the pair once.
        const bool jInfinite = std::find(infinite.begin(), infinite.end(), j) != infinite.end();
        if (jInfinite && j < i) continue;
        pairs->emplace_back(std::min(i, j), std::max(i, j));
      }
  std::sort(pairs->begin(), pairs->end());
}

namespace {

bool Contains(const Aabb& outer, const Aabb& inner) {
  return (outer.min.array() <= inner.min.array()).all() &&
         (inner.max.array() <= outer.max.array()).all();
}

}  // namespace

void OverlapCache::Find(const std::vector<Aabb>& boxes, std::vector<std::pair<int, int>>* pairs) {
  const size_t n = boxes.size();
  if (n <= static_cast<size_t>(kDirectLimit)) {
    FindOverlappingPairs(boxes, pairs);
    return;
  }
  bool valid = fat_.size() == n;
  // Empty and NaN boxes overlap nothing, wherever they are.
  for (size_t i = 0; valid && i < n; ++i)
    valid = boxes[i].IsEmpty() || boxes[i].min.hasNaN() || boxes[i].max.hasNaN() ||
            (!fat_[i].IsEmpty() && Contains(fat_[i], boxes[i]));
  if (!valid) {
    ++sweeps_;
    fat_ = boxes;
    for (Aabb& b : fat_) {
      if (b.IsEmpty() || !b.min.allFinite() || !b.max.allFinite()) continue;
      b.Inflate(kFatFraction * (b.max - b.min).maxCoeff());
    }
    FindOverlappingPairs(fat_, &candidates_);
  }
  pairs->clear();
  for (const auto& [i, j] : candidates_)
    if (!boxes[i].IsEmpty() && !boxes[j].IsEmpty() && boxes[i].Overlaps(boxes[j]))
      pairs->emplace_back(i, j);
}

}  // namespace superdex
