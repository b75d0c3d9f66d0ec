#include "core/contact/soft_samples.h"

#include <algorithm>
#include <cmath>

namespace superdex {
namespace {

Eigen::Vector3d Node(const Eigen::VectorXd& x, int i) { return x.segment<3>(3 * i); }

Eigen::Vector3d UnitFaceNormal(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double len = n.norm();
  return len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

// The centroid of a triangle and its largest distance to a corner [m].
double Ball(const Eigen::Vector3d xs[3], Eigen::Vector3d* c) {
  *c = (xs[0] + xs[1] + xs[2]) / 3.0;
  return std::max({(xs[0] - *c).norm(), (xs[1] - *c).norm(), (xs[2] - *c).norm()});
}

}  // namespace

void GatherSoftSamples(const SoftPairInput& in, const FrameSide& side, double delta,
                       const DissipationSetup* diss, SampleSink* sink) {
  const SoftBodyModel& A = *in.model;
  const Eigen::VectorXd& x = *in.x;
  const Eigen::VectorXd& xn = in.xLast ? *in.xLast : x;
  const bool withDissipation = diss && diss->coefficients.Any() && side.hasStart && in.x0;
  const BallCulling near(side, delta, withDissipation ? diss : nullptr, withDissipation, 2.0);
  PairSample s;
  s.hasNormal = true;
  s.faceNormal = true;
  s.blocks = 3;
  for (size_t f = 0; f < A.faces.size(); ++f) {
    const Eigen::Vector3i& F = A.faces[f];
    const Eigen::Vector3d xs[3] = {Node(x, F[0]), Node(x, F[1]), Node(x, F[2])};
    const Eigen::Vector3d xns[3] = {Node(xn, F[0]), Node(xn, F[1]), Node(xn, F[2])};
    Eigen::Vector3d c, cn;
    const double r = std::max(Ball(xs, &c), Ball(xns, &cn));
    if (!near(c, cn, r)) continue;
    s.n = UnitFaceNormal(xs[0], xs[1], xs[2]);
    s.nLast = UnitFaceNormal(xns[0], xns[1], xns[2]);
    s.face = static_cast<int>(f);
    for (int a = 0; a < 3; ++a) {
      s.faceNodes[a] = xs[a];
      const int free = A.freeIndex[F[a]];
      s.offs[a] = free < 0 ? -1 : in.dofOffset + 3 * free;
    }
    for (int q = A.faceSampleBegin[f]; q < A.faceSampleBegin[f + 1]; ++q) {
      const Eigen::Vector3d& w3 = A.samples[q].bary;
      s.map = SamplePointMap::Face(w3);
      s.y = w3[0] * xs[0] + w3[1] * xs[1] + w3[2] * xs[2];
      s.yLast = w3[0] * xns[0] + w3[1] * xns[1] + w3[2] * xns[2];
      s.y0 = withDissipation ? Eigen::Vector3d(w3[0] * Node(*in.x0, F[0]) +
                                               w3[1] * Node(*in.x0, F[1]) +
                                               w3[2] * Node(*in.x0, F[2]))
                             : s.y;
      s.weight = A.samples[q].weight;
      s.key = q;
      sink->Add(s);
    }
  }
}

}  // namespace superdex
