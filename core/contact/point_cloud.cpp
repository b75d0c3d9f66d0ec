#include "core/contact/point_cloud.h"

#include <algorithm>
#include <cmath>

namespace superdex {

void CloudSamples::Form(const ActorKind& A, const Eigen::VectorXd& q, const Eigen::VectorXd* qLast,
                        const Eigen::VectorXd* q0, const std::vector<int>& stageDof, double cell,
                        double loadFactor, bool withReference) {
  samples.clear();
  SampleList list(&samples);
  GatherKindSampleRange(A, q, qLast, q0, stageDof, 0, A.NumSamples(), &list);
  places.resize(samples.size());
  motion = 0.0;
  for (size_t i = 0; i < samples.size(); ++i) {
    places[i] = samples[i].y;
    motion = std::max(motion, (samples[i].yLast - samples[i].y).norm());
  }
  hash.Build(places, cell, loadFactor);
  reference.clear();
  if (!withReference) return;
  const Eigen::VectorXd& X = *A.ReferenceConfiguration();
  for (int i = 0; i < A.NumSamples(); ++i) reference.push_back(A.Sample(i, X).y);
}

void CloudPoints::Form(const ActorKind& B, const Eigen::VectorXd& q, const Eigen::VectorXd* qLast,
                       const Eigen::VectorXd* q0, bool withReference) {
  const PointCloudColliderParams& p = *B.PointCloud();
  radius = p.radius;
  weightScale = std::pow(p.radius, -B.CloudDimension());
  sphere.type = ColliderType::Sphere;
  sphere.sphere.radius = p.radius;
  sphere.lipschitz = 1.0;
  sphere.boundingRadius = p.radius;
  const int n = B.NumCloudPoints();
  now.resize(n);
  last.resize(n);
  start.resize(n);
  hasLast = qLast != nullptr;
  hasStart = q0 != nullptr;
  for (int j = 0; j < n; ++j) {
    now[j] = B.CloudPoint(j, q);
    last[j] = qLast ? B.CloudPoint(j, *qLast).y : now[j].y;
    start[j] = q0 ? B.CloudPoint(j, *q0).y : now[j].y;
  }
  reference.clear();
  if (!withReference) return;
  const Eigen::VectorXd& X = *B.ReferenceConfiguration();
  for (int j = 0; j < n; ++j) reference.push_back(B.CloudPoint(j, X).y);
}

void CloudPoints::Side(int j, const std::vector<int>& stageDof, FrameSide* side) const {
  const KindSample& s = now[j];
  side->field = &sphere;
  side->tet = nullptr;
  side->pose.p = s.y;
  side->pose.R.setIdentity();
  side->last.p = last[j];
  side->last.R.setIdentity();
  side->hasLast = hasLast;
  side->hasStart = hasStart;
  side->start.p = start[j];
  side->start.R.setIdentity();
  side->start.Rinv.setIdentity();
  side->start.last = side->last;
  side->motion = FrameSide::Motion::Translation;
  side->blocks = s.Blocks();
  std::fill(side->offs, side->offs + 4, -1);
  for (int b = 0; b < side->blocks; ++b) {
    side->offs[b] = stageDof[s.dof[b]];
    side->Fp.block<3, 3>(0, 3 * b) = s.map.bary[b] * Eigen::Matrix3d::Identity();
  }
}

void EvaluateCloudPoints(const CloudSamples& A, const CloudPoints& B,
                         const std::vector<int>& stageDofB, bool self, double exclusionRatio,
                         int begin, int end, const PenaltyParams& penalty,
                         const DissipationSetup* dissipation, int order, PairStencils* out,
                         std::vector<ContactSampleRecord>* records) {
  // The geometry at x_n matters where the mode reads it (explicit normals' contacts, the
  // reconstructed load): the query grows by the motions since x_n.
  const bool readsLast = dissipation && dissipation->coefficients.Any() && B.hasStart &&
                         dissipation->mode != DissipationMode::ImplicitLoad;
  const double reach = B.radius + penalty.delta;
  const double excluded2 = std::pow(exclusionRatio * B.radius, 2);
  FrameSide side;
  PairSample s;
  static thread_local std::vector<int> near;
  for (int j = begin; j < end; ++j) {
    const Eigen::Vector3d& x = B.now[j].y;
    const double r = reach + (readsLast ? A.motion + (B.last[j] - x).norm() : 0.0);
    near.clear();
    A.hash.ForEachNear(x, r, [&](int i) {
      if ((A.places[i] - x).squaredNorm() > r * r) return;
      if (self && (A.reference[i] - B.reference[j]).squaredNorm() < excluded2) return;
      near.push_back(i);
    });
    if (near.empty()) continue;
    std::sort(near.begin(), near.end());  // a face's samples together: one stencil
    B.Side(j, stageDofB, &side);
    const double scale = B.now[j].weight * B.weightScale;
    FrameEvaluation evaluation(side, penalty, INFINITY, dissipation, order, out, records, true);
    for (int i : near) {
      s = A.samples[i];
      s.weight *= scale;
      evaluation.Add(s);
    }
    evaluation.Finish();
  }
}

}  // namespace superdex
