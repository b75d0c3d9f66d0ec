#include "core/model/actor_kind.h"

#include <cmath>

namespace superdex {

bool ActorKind::HasFreeDof() const {
  for (int i = 0; i < NumTangentDofs(); ++i)
    if (!IsPrescribed(i)) return true;
  return false;
}

void ActorKind::DifferenceGroups(const KindState& s,
                                 std::vector<KindDifferenceGroup>* groups) const {
  const int n = static_cast<int>(s.x.size());
  KindDifferenceGroup g;
  for (int i = 0; i < 2 * n; ++i) {
    g.directions.push_back({{{i, 1.0}}, i >= n, 1.0});
    g.entries.push_back(i);
  }
  for (int i = 0; i < NumTangentDofs(); ++i)
    if (!IsPrescribed(i)) {
      g.tangentDofs.push_back(i);
      g.tangentLength.push_back(1.0);
    }
  groups->assign(1, std::move(g));
}

Eigen::MatrixXd ActorKind::CenterOfMassJacobian(const KindState& s) const {
  const int n = static_cast<int>(s.x.size());
  Eigen::MatrixXd C(3, n);
  KindState moved = s;
  for (int i = 0; i < n; ++i) {
    const double h = 1e-6 * (1.0 + std::abs(s.x[i]));
    moved.x[i] = s.x[i] + h;
    const Eigen::Vector3d plus = CenterOfMass(moved);
    moved.x[i] = s.x[i] - h;
    C.col(i) = (plus - CenterOfMass(moved)) / (2.0 * h);
    moved.x[i] = s.x[i];
  }
  return C;
}

}  // namespace superdex
