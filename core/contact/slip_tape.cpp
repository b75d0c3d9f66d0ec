#include "core/contact/slip_tape.h"

#include <algorithm>
#include <tuple>

namespace superdex {

const SlipReference* PairSlips::Find(int key) const {
  const auto it = std::lower_bound(
      samples.begin(), samples.end(), key,
      [](const std::pair<int, SlipReference>& s, int k) { return s.first < k; });
  return it != samples.end() && it->first == key ? &it->second : nullptr;
}

void StageSlips::Add(int colliding, int collider, PairSlips slips) {
  std::sort(slips.samples.begin(), slips.samples.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  pairs_.push_back({colliding, collider, std::move(slips)});
}

void StageSlips::Seal() {
  std::sort(pairs_.begin(), pairs_.end(), [](const Entry& a, const Entry& b) {
    return std::tie(a.colliding, a.collider) < std::tie(b.colliding, b.collider);
  });
}

PairSlips* StageSlips::Find(int colliding, int collider) {
  const auto key = std::make_tuple(colliding, collider);
  const auto it = std::lower_bound(pairs_.begin(), pairs_.end(), key, [](const Entry& e, const auto& k) {
    return std::tie(e.colliding, e.collider) < k;
  });
  if (it == pairs_.end() || std::tie(it->colliding, it->collider) != key) return nullptr;
  return &it->slips;
}

size_t StageSlips::Samples() const {
  size_t n = 0;
  for (const Entry& e : pairs_) n += e.slips.samples.size();
  return n;
}

DissipationDensity EvaluateSampleDissipation(double lambdaHat, const Eigen::Vector3d& N,
                                             const Eigen::Vector3d& V,
                                             const DissipationCoefficients& c,
                                             DissipationHessian hessian, const PairSlipUse& use,
                                             int key) {
  if (!use.slips) return EvaluateDissipation(lambdaHat, N, V, c, hessian);
  if (use.record) {
    use.slips->samples.emplace_back(key, SlipAt(N, V, c.vf));
    return EvaluateDissipation(lambdaHat, N, V, c, hessian);
  }
  return EvaluateDissipation(lambdaHat, N, V, c, hessian, use.slips->Find(key));
}

}  // namespace superdex
