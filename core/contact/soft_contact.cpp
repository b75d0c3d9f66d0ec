#include "core/contact/soft_contact.h"

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

/// Whether a sample of the face (current nodes xs, last xns) can contribute, by bounding spheres
/// of both faces against B's L-Lipschitz field: the penalty looks at the current face only; with
/// `dissipation`, explicit normals at the last face, the reconstructed load at the current
/// distance shifted by the move (φ + G·(Y_n − Y) >= φ − L|Y_n − Y| for every sample).
bool FaceNeeded(const FrameSide& B, const Eigen::Vector3d xs[3], const Eigen::Vector3d xns[3],
                double delta, const DissipationSetup* dissipation) {
  const RigidCollider& field = *B.field;
  const double L = field.lipschitz;
  const Eigen::Matrix3d RBt = B.pose.R.transpose(), RnBt = B.last.R.transpose();
  const Eigen::Vector3d c = (xs[0] + xs[1] + xs[2]) / 3.0;
  const double rad = std::max({(xs[0] - c).norm(), (xs[1] - c).norm(), (xs[2] - c).norm()});
  const Eigen::Vector3d cn = (xns[0] + xns[1] + xns[2]) / 3.0;
  const double radn =
      std::max({(xns[0] - cn).norm(), (xns[1] - cn).norm(), (xns[2] - cn).norm()});
  const double phiNow = field.Value(RBt * (c - B.pose.p)) - L * rad;
  if (phiNow < delta) return true;
  if (!dissipation) return false;
  if (dissipation->mode == DissipationMode::ExplicitNormals)
    return field.Value(RnBt * (cn - B.last.p)) - L * radn < delta;
  if (dissipation->mode == DissipationMode::ReconstructedLoad) {
    const double shift = (RnBt * (cn - B.last.p) - RBt * (c - B.pose.p)).norm() + rad + radn;
    return phiNow - L * shift < delta;
  }
  return false;
}

}  // namespace

void GatherSoftSamples(const SoftPairInput& in, const FrameSide& side, double delta,
                       const DissipationSetup* diss, SampleSink* sink) {
  const SoftBodyModel& A = *in.model;
  const Eigen::VectorXd& x = *in.x;
  const Eigen::VectorXd& xn = in.xLast ? *in.xLast : x;
  const bool withDissipation = diss && diss->coefficients.Any() && side.hasStart && in.x0;
  PairSample s;
  s.hasNormal = true;
  s.faceNormal = true;
  s.blocks = 3;
  for (size_t f = 0; f < A.faces.size(); ++f) {
    const Eigen::Vector3i& F = A.faces[f];
    const Eigen::Vector3d xs[3] = {Node(x, F[0]), Node(x, F[1]), Node(x, F[2])};
    const Eigen::Vector3d xns[3] = {Node(xn, F[0]), Node(xn, F[1]), Node(xn, F[2])};
    if (!FaceNeeded(side, xs, xns, delta, withDissipation ? diss : nullptr)) continue;
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

void EvaluateSoftRigidPair(const SoftPairInput& in, const RigidBodyModel& B, const RigidPose& b,
                           const RigidStageStart* b0, int bOffset, const PenaltyParams& penalty,
                           double maxAlignment, const DissipationSetup* diss, int order,
                           PairStencils* out, std::vector<ContactSampleRecord>* records) {
  const FrameSide side = RigidFrameSide(B, b, b0, B.dynamic ? bOffset : -1);
  const bool withDissipation = diss && diss->coefficients.Any() && b0 && in.x0;
  FrameEvaluation evaluation(side, penalty, maxAlignment, withDissipation ? diss : nullptr, order,
                             out, records);
  GatherSoftSamples(in, side, penalty.delta, withDissipation ? diss : nullptr, &evaluation);
  evaluation.Finish();
}

}  // namespace superdex
