#include "core/contact/soft_contact.h"

#include <cmath>

#include "core/contact/dissipation_kernels.h"
#include "core/contact/sample_chain.h"
#include "core/model/rigid_math.h"

namespace superdex {
namespace {
using namespace dissipation_kernels;

Eigen::Vector3d Node(const Eigen::VectorXd& x, int i) { return x.segment<3>(3 * i); }

Eigen::Vector3d UnitFaceNormal(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double len = n.norm();
  return len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

/// One sample of a current-geometry mode as a function of the face stencil's step δ: nodes
/// x_a + δx_a, B by the first-order retraction p_B + δp, (1 + [δθ]×) R_B (exact for first
/// derivatives at δ = 0). Output: the world residual [b_a f (3 nodes), −f, −d × f], f = R_B ∂R/∂V.
struct SoftCurrentModeSample {
  Eigen::Vector3d xs[3];   // face nodes
  Eigen::Vector3d bary;
  const RigidPose* b = nullptr;
  Eigen::Vector3d Y, Y0, Yn;
  SdfSample field;
  const DissipationSetup* setup = nullptr;
  bool bDynamic = false;

  /// Adds w ∂residual/∂δ. The kernel g is differentiated in its six arguments (Y, N_A) by
  /// forward-mode AD; the chain to the stencil is analytic (y = Σ b_a x_a, d = y − p_B,
  /// m = (x₁ − x₀) × (x₂ − x₀), n = m/|m|, N_A = R_Bᵀ n):
  ///   dY = R_Bᵀ (dy − δp_B + [d]× δθ_B),   dN_A = R_Bᵀ ((I − n nᵀ)/|m| dm + [n]× δθ_B),
  ///   dm = ([e₂]× − [e₁]×) δx₀ − [e₂]× δx₁ + [e₁]× δx₂   (e_i = x_i − x₀),
  ///   df = R_B (G_Y dY + G_N dN_A) − [f]× δθ_B,   d(−d × f) = [f]× (dy − δp_B) − [d]× df.
  void AddJacobian(double w, StencilMatrix* J) const {
    const Eigen::Matrix3d& RB = b->R;
    const Eigen::Vector3d y = bary[0] * xs[0] + bary[1] * xs[1] + bary[2] * xs[2];
    const Eigen::Vector3d d = y - b->p;
    const Eigen::Vector3d e1 = xs[1] - xs[0], e2 = xs[2] - xs[0];
    const Eigen::Vector3d m = e1.cross(e2);
    const double len = m.norm();
    const Eigen::Vector3d n = m / len;
    const CurrentModeLinearization lin =
        LinearizeCurrentModeGradient(Y, RB.transpose() * n, field, Yn, Y0, *setup);
    const Eigen::Vector3d f = RB * lin.g;
    const Eigen::Matrix3d A = RB * lin.GY * RB.transpose();  // df per world dY-direction
    const Eigen::Matrix3d C = RB * lin.GN * RB.transpose();  // df per world dn-direction
    const Eigen::Matrix3d P = (Eigen::Matrix3d::Identity() - n * n.transpose()) / len;
    const Eigen::Matrix3d S1 = Skew(e1), S2 = Skew(e2), Sf = Skew(f), Sd = Skew(d);
    const Eigen::Matrix3d dm[3] = {S2 - S1, -S2, S1};
    Eigen::Matrix<double, 3, 15> df = Eigen::Matrix<double, 3, 15>::Zero();
    for (int a = 0; a < 3; ++a) df.block<3, 3>(0, 3 * a) = bary[a] * A + C * P * dm[a];
    if (bDynamic) {
      df.block<3, 3>(0, 9) = -A;
      df.block<3, 3>(0, 12) = A * Sd + C * Skew(n) - Sf;
    }
    const int cols = bDynamic ? 15 : 9;
    for (int a = 0; a < 3; ++a) J->block(3 * a, 0, 3, cols) += (w * bary[a]) * df.leftCols(cols);
    if (bDynamic) {
      Eigen::Matrix<double, 3, 15> dd = Eigen::Matrix<double, 3, 15>::Zero();
      for (int a = 0; a < 3; ++a) dd.block<3, 3>(0, 3 * a) = bary[a] * Eigen::Matrix3d::Identity();
      dd.block<3, 3>(0, 9) = -Eigen::Matrix3d::Identity();
      J->block<3, 15>(9, 0) -= w * df;
      J->block<3, 15>(12, 0) += w * (Sf * dd - Sd * df);
    }
  }
};

/// Whether a sample of the face (current nodes xs, last xns) can contribute, by bounding spheres
/// of both faces against B's L-Lipschitz field: the penalty looks at the current face only; with
/// `dissipation`, explicit normals at the last face, the reconstructed load at the current
/// distance shifted by the move (φ + G·(Y_n − Y) >= φ − L|Y_n − Y| for every sample).
bool FaceNeeded(const RigidBodyModel& B, const RigidPose& b, const RigidPose& bn,
                const Eigen::Vector3d xs[3], const Eigen::Vector3d xns[3], double delta,
                const DissipationSetup* dissipation) {
  const double L = B.collider.lipschitz;
  const Eigen::Matrix3d RBt = b.R.transpose(), RnBt = bn.R.transpose();
  const Eigen::Vector3d c = (xs[0] + xs[1] + xs[2]) / 3.0;
  const double rad = std::max({(xs[0] - c).norm(), (xs[1] - c).norm(), (xs[2] - c).norm()});
  const Eigen::Vector3d cn = (xns[0] + xns[1] + xns[2]) / 3.0;
  const double radn =
      std::max({(xns[0] - cn).norm(), (xns[1] - cn).norm(), (xns[2] - cn).norm()});
  const double phiNow = B.collider.Value(RBt * (c - b.p)) - L * rad;
  if (phiNow < delta) return true;
  if (!dissipation) return false;
  if (dissipation->mode == DissipationMode::ExplicitNormals)
    return B.collider.Value(RnBt * (cn - bn.p)) - L * radn < delta;
  if (dissipation->mode == DissipationMode::ReconstructedLoad) {
    const double shift = (RnBt * (cn - bn.p) - RBt * (c - b.p)).norm() + rad + radn;
    return phiNow - L * shift < delta;
  }
  return false;
}

}  // namespace

void EvaluateSoftRigidPair(const SoftPairInput& in, const RigidBodyModel& B, const RigidPose& b,
                           const RigidStageStart* b0, bool bDynamic, const PenaltyParams& penalty,
                           double maxAlignment, const DissipationSetup* diss, int order,
                           PairStencils* out, std::vector<ContactSampleRecord>* records) {
  const SoftBodyModel& A = *in.model;
  const Eigen::VectorXd& x = *in.x;
  const Eigen::VectorXd& xn = in.xLast ? *in.xLast : x;
  const int n = bDynamic ? 15 : 9;
  out->Reset();
  const double delta = penalty.delta;
  const Eigen::Matrix3d RBt = b.R.transpose();
  // Geometry reference (alignment, explicit normals): B at x_n when a stage start is given.
  const RigidPose& bn = b0 ? b0->last : b;
  const Eigen::Matrix3d RnBt = bn.R.transpose();
  const bool alignmentTest = std::isfinite(maxAlignment);
  const bool withDissipation = diss && diss->coefficients.Any() && b0 && in.x0;
  const bool explicitNormals = withDissipation && diss->mode == DissipationMode::ExplicitNormals;
  const double m = maxAlignment;

  PointStencil point;
  for (size_t f = 0; f < A.faces.size(); ++f) {
    const Eigen::Vector3i& F = A.faces[f];
    const Eigen::Vector3d xs[3] = {Node(x, F[0]), Node(x, F[1]), Node(x, F[2])};
    const Eigen::Vector3d xns[3] = {Node(xn, F[0]), Node(xn, F[1]), Node(xn, F[2])};
    if (!FaceNeeded(B, b, bn, xs, xns, delta, withDissipation ? diss : nullptr)) continue;

    ContactStencil& fc = out->Slot(static_cast<int>(f), -1, n, order);
    const Eigen::Vector3d nA = UnitFaceNormal(xs[0], xs[1], xs[2]);
    const Eigen::Vector3d nAn = UnitFaceNormal(xns[0], xns[1], xns[2]);
    Eigen::Vector3d x0s[3] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    if (withDissipation)
      for (int a = 0; a < 3; ++a) x0s[a] = Node(*in.x0, F[a]);

    for (int q = A.faceSampleBegin[f]; q < A.faceSampleBegin[f + 1]; ++q) {
      const SoftSurfaceSample& s = A.samples[q];
      const Eigen::Vector3d& w3 = s.bary;
      const Eigen::Vector3d y = w3[0] * xs[0] + w3[1] * xs[1] + w3[2] * xs[2];
      const Eigen::Vector3d yn = w3[0] * xns[0] + w3[1] * xns[1] + w3[2] * xns[2];
      const Eigen::Vector3d d = y - b.p;
      const Eigen::Vector3d Y = RBt * d;
      const Eigen::Vector3d Yn = RnBt * (yn - bn.p);
      const SdfSample field = B.collider.Evaluate(Y);
      out->minPhi = std::min(out->minPhi, field.value);

      // --- Penalty.
      if (field.value < delta) {
        bool rejected = false;
        if (alignmentTest) {
          const Eigen::Vector3d G = b0 ? B.collider.Evaluate(Yn).gradient : field.gradient;
          const Eigen::Vector3d NA = b0 ? Eigen::Vector3d(RnBt * nAn) : Eigen::Vector3d(RBt * nA);
          rejected = G.dot(NA) > m + kAlignmentRoundoff;
        }
        if (!rejected) {
          ++out->activeSamples;
          fc.penaltyActive = true;
          const PenaltyDensity W = NormalPenaltyDensity(field.value, penalty);
          out->penaltyValue += s.weight * W.W;
          if (records) {
            ContactSampleRecord rec;
            rec.position = y;
            rec.normal = b.R * field.gradient.normalized();
            rec.phi = field.value;
            rec.lambdaN = W.lambdaN;
            rec.traction = W.lambdaN * (b.R * field.gradient);
            rec.weight = s.weight;
            rec.face = static_cast<int>(f);
            records->push_back(rec);
          }
          if (order >= 1) {
            Eigen::Vector3d gY;
            Eigen::Matrix3d HY;
            PenaltyInPullback(W, field, &gY, order >= 2 ? &HY : nullptr);
            RigidPullbackStencil(b.R, d, gY, order >= 2 ? &HY : nullptr, bDynamic, &point);
            ChainToActor(SamplePointMap::Face(w3), point, s.weight, &fc.penaltyGradient,
                         order >= 2 ? &fc.penaltyHessian : nullptr);
          }
        }
      }

      // --- Dissipation.
      if (!withDissipation) continue;
      const DissipationSetup& ds = *diss;
      double lambdaHat = 0.0;
      Eigen::Vector3d N;
      if (explicitNormals) {
        const SdfSample f0 = B.collider.Evaluate(Yn);
        if (f0.value >= delta) continue;
        const Eigen::Vector3d NA0 = RnBt * nAn;
        const double al = f0.gradient.dot(NA0);
        if (al > m + kAlignmentRoundoff) continue;
        lambdaHat = AlignmentFactor(al, ds) * NormalPenaltyDensity(f0.value, ds.penalty).lambdaN;
        N = SplitDirection(f0.gradient, NA0, ds);
      } else {
        const double phiLoad = ds.mode == DissipationMode::ImplicitLoad
                                   ? field.value
                                   : field.value + field.gradient.dot(Yn - Y);
        if (phiLoad >= delta) continue;
        const Eigen::Vector3d NA = RBt * nA;
        const double al = field.gradient.dot(NA);
        if (al > m + kAlignmentRoundoff) continue;
        lambdaHat = AlignmentFactor(al, ds) * NormalPenaltyDensity(phiLoad, ds.penalty).lambdaN;
        N = SplitDirection(field.gradient, NA, ds);
      }
      if (lambdaHat == 0.0) continue;
      const Eigen::Vector3d y0 = w3[0] * x0s[0] + w3[1] * x0s[1] + w3[2] * x0s[2];
      const Eigen::Vector3d Y0 = b0->Rinv * (y0 - b0->p);
      const Eigen::Vector3d V = (Y - Y0) / ds.dt;
      const DissipationDensity D = EvaluateSampleDissipation(
          lambdaHat, N, V, ds.coefficients, ds.HessianKind(explicitNormals && order >= 2),
          ds.slips, q);
      fc.dissipationActive = true;
      out->AddDissipative(s.weight, ds.dt, D, ds.coefficients.mu, lambdaHat);
      if (order == 0) continue;
      const bool hessian = explicitNormals && order >= 2;
      const Eigen::Matrix3d HY = D.hessian / ds.dt;
      RigidPullbackStencil(b.R, d, D.gradient, hessian ? &HY : nullptr, bDynamic, &point);
      ChainToActor(SamplePointMap::Face(w3), point, s.weight, &fc.dissipationResidual,
                   hessian ? &fc.dissipationJacobian : nullptr);
      if (order < 2) continue;
      if (!explicitNormals) {
        SoftCurrentModeSample sample;
        for (int a = 0; a < 3; ++a) sample.xs[a] = xs[a];
        sample.bary = w3;
        sample.b = &b;
        sample.Y = Y;
        sample.Y0 = Y0;
        sample.Yn = Yn;
        sample.field = field;
        sample.setup = &ds;
        sample.bDynamic = bDynamic;
        sample.AddJacobian(s.weight, &fc.dissipationJacobian);
      }
    }
    if (fc.penaltyActive || fc.dissipationActive) out->Keep();
  }
}

}  // namespace superdex
