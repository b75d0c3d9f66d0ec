#include "core/contact/soft_collider.h"

#include <Eigen/LU>
#include <cmath>

#include "core/contact/dissipation_kernels.h"
#include "core/contact/sample_chain.h"
#include "core/model/rigid_math.h"

namespace superdex {
namespace {
using namespace dissipation_kernels;

using Vec15 = Eigen::Matrix<double, 15, 1>;
using Mat15 = Eigen::Matrix<double, 15, 15>;

/// The affine pullback through tet t of B at positions x (extended beyond the tet).
struct Pullback {
  int tet = -1;
  Eigen::Vector4d lambda;
  Eigen::Vector3d X;     // reference point [m]
  Eigen::Matrix3d B;     // Ds⁻¹
  Eigen::Matrix3d Finv;  // Dm Ds⁻¹
  Eigen::Matrix3d F;     // Ds Dm⁻¹
};

bool PullbackThrough(const SoftBodyModel& m, const Eigen::VectorXd& x, int t,
                     const Eigen::Vector3d& y, Pullback* pb) {
  const Eigen::Vector4i& T = m.rest.tets[t];
  const Eigen::Vector3d x0 = x.segment<3>(3 * T[0]);
  Eigen::Matrix3d Ds;
  Ds << x.segment<3>(3 * T[1]) - x0, x.segment<3>(3 * T[2]) - x0, x.segment<3>(3 * T[3]) - x0;
  const double det = Ds.determinant();
  if (!(std::isfinite(det) && det > 0.0)) return false;
  pb->tet = t;
  pb->B = Ds.inverse();
  const Eigen::Vector3d beta = pb->B * (y - x0);
  pb->lambda << 1.0 - beta.sum(), beta;
  const Eigen::Matrix3d& DmInv = m.elements[t].DmInv;
  const Eigen::Matrix3d Dm = DmInv.inverse();
  pb->X = m.rest.vertices[T[0]] + Dm * beta;
  pb->Finv = Dm * pb->B;
  pb->F = Ds * DmInv;
  return true;
}

/// The tet pullback's side of the sample chain (core/contact/sample_chain.h): f(X) on the point
/// stencil z = [y, x_0..x_3] (header formulas), unweighted.
void TetPullbackStencil(const Pullback& pb, const Eigen::Vector3d& gX, const Eigen::Matrix3d* HX,
                        PointStencil* out) {
  out->colliderDofs = 12;
  Eigen::Matrix<double, 3, 15> R;
  R.leftCols<3>().setIdentity();
  for (int a = 0; a < 4; ++a) R.middleCols<3>(3 + 3 * a) = -pb.lambda[a] * Eigen::Matrix3d::Identity();
  const Eigen::Matrix<double, 3, 15> J = pb.Finv * R;
  out->g = J.transpose() * gX;
  if (!HX) return;
  Mat15& Hz = out->H;
  Hz = J.transpose() * (*HX) * J;
  const Eigen::Vector3d c = pb.Finv.transpose() * gX;
  Eigen::Matrix<double, 4, 3> L;
  L.bottomRows<3>() = pb.B;
  L.row(0) = -pb.B.colwise().sum();
  for (int a = 0; a < 4; ++a) {
    const Vec15 u = R.transpose() * L.row(a).transpose();
    // v_a = c at the x_a block: u vᵀ touches only the columns of that block.
    Hz.middleCols<3>(3 + 3 * a) -= u * c.transpose();
    Hz.middleRows<3>(3 + 3 * a) -= c * u.transpose();
  }
}

Eigen::Vector3d Normalized(const Eigen::Vector3d& v) {
  const double n = v.norm();
  return n > 0 ? Eigen::Vector3d(v / n) : Eigen::Vector3d::Zero();
}

/// One sample of a current-geometry dissipation mode as a function of the stencil step δ
/// ([A's dofs, B's tet]); first-order rigid retraction as in core/contact/rigid_dissipation.cpp. Output:
/// the residual [A's part, −λ_a F⁻ᵀ g per tet node].
struct CurrentModeSample {
  SamplePointMap kin;
  // A: a rigid map's origin p_A, arm r = y − p_A and normal (world; R = I + [δθ]× moves r and n
  // alike), or a face's nodes (its map's barycentrics)
  Eigen::Vector3d pA, rA, normalA;
  Eigen::Vector3d xs[3];
  // B: tet nodes, reference data, field at the current pullback
  Eigen::Vector3d xb[4];
  Eigen::Vector3d Xr0;
  Eigen::Matrix3d Dm, DmInv;
  Eigen::Vector3d Xbar, Yn, X0;
  SdfSample field;
  const DissipationSetup* setup = nullptr;

  template <typename T>
  void Residual(const T* delta, T* out) const {
    const DissipationSetup& s = *setup;
    const int nA = kin.Dofs();
    Vec3<T> y, n, r;
    if (kin.kind == SamplePointMap::Kind::Rigid) {
      const Vec3<T> dth(delta[3], delta[4], delta[5]);
      const Mat3<T> R = Mat3<T>::Identity() + SkewT<T>(dth);
      r = R * rA.cast<T>();
      y = pA.cast<T>() + Vec3<T>(delta[0], delta[1], delta[2]) + r;
      n = R * normalA.cast<T>();
    } else {
      Vec3<T> x[3];
      for (int a = 0; a < 3; ++a)
        x[a] = xs[a].cast<T>() + Vec3<T>(delta[3 * a], delta[3 * a + 1], delta[3 * a + 2]);
      y = T(kin.bary[0]) * x[0] + T(kin.bary[1]) * x[1] + T(kin.bary[2]) * x[2];
      n = (x[1] - x[0]).cross(x[2] - x[0]);
    }
    Vec3<T> xbT[4];
    for (int a = 0; a < 4; ++a)
      xbT[a] = xb[a].cast<T>() +
               Vec3<T>(delta[nA + 3 * a], delta[nA + 3 * a + 1], delta[nA + 3 * a + 2]);
    Mat3<T> Ds;
    Ds.col(0) = xbT[1] - xbT[0];
    Ds.col(1) = xbT[2] - xbT[0];
    Ds.col(2) = xbT[3] - xbT[0];
    const Mat3<T> B = Ds.inverse();
    const Vec3<T> beta = B * (y - xbT[0]);
    const T lambda0 = T(1.0) - beta.sum();
    const Vec3<T> X = Xr0.cast<T>() + Dm.cast<T>() * beta;
    const Mat3<T> Finv = Dm.cast<T>() * B;
    const Mat3<T> F = Ds * DmInv.cast<T>();
    using std::sqrt;
    Vec3<T> NA = F.transpose() * n;  // normals map by Fᵀ
    NA = NA / sqrt(NA.squaredNorm());
    const Vec3<T> g = CurrentModeDissipationGradient<T>(X, NA, Xbar, field, Yn, X0, s);
    const Vec3<T> ry = Finv.transpose() * g;
    if (kin.kind == SamplePointMap::Kind::Rigid) {
      const Vec3<T> tau = r.cross(ry);
      for (int k = 0; k < 3; ++k) {
        out[k] = ry[k];
        out[3 + k] = tau[k];
      }
    } else {
      for (int a = 0; a < 3; ++a)
        for (int k = 0; k < 3; ++k) out[3 * a + k] = T(kin.bary[a]) * ry[k];
    }
    const T lam[4] = {lambda0, beta[0], beta[1], beta[2]};
    for (int a = 0; a < 4; ++a)
      for (int k = 0; k < 3; ++k) out[nA + 3 * a + k] = -lam[a] * ry[k];
  }
};

/// Everything about one colliding sample at the three configurations.
struct SamplePoint {
  SamplePointMap kin;
  int face = -1;
  int key = 0;  // the sample's index in A's sample list (core/contact/slip_tape.h)
  double weight = 0.0;
  Eigen::Vector3d y, yn, y0;  // current, last, stage start [m]
  Eigen::Vector3d n, nn;      // A's outward normal now and at x_n (unit)
  // A deforming face's nodes (its normal moves with them), and the stage dof blocks of A.
  Eigen::Vector3d faceNodes[3];
  int blocks = 0;
  int offs[4] = {-1, -1, -1, -1};
};

/// One pair's evaluation on a soft collider: the setup shared by its samples, and per sample the
/// penalty and the dissipation (header formulas).
struct OnSoftCollider {
  OnSoftCollider(const CollidingInput& a, const SoftColliderInput& bin,
                 const PenaltyParams& penaltyParams, double alignment,
                 const DissipationSetup* dissipation, int ord, PairStencils* result,
                 std::vector<ContactSampleRecord>* recs)
      : A(a), Bin(bin), B(*bin.model), xB(*bin.x), xBn(bin.xLast ? *bin.xLast : *bin.x),
        grid(*B.colliderGrid), penalty(penaltyParams), maxAlignment(alignment),
        diss(dissipation), order(ord), out(result), records(recs) {
    delta = penalty.delta;
    alignmentTest = std::isfinite(maxAlignment);
    withDissipation = diss && diss->coefficients.Any() && Bin.x0 &&
                      (A.rigid ? A.start != nullptr : A.x0 != nullptr);
    explicitNormals = withDissipation && diss->mode == DissipationMode::ExplicitNormals;
    n = (A.rigid ? 6 : 9) + 12;  // A's dofs, then B's tet
    box = SoftBounds(xB);
    boxLast = SoftBounds(xBn);
    box.Inflate(1e-9);
    boxLast.Inflate(1e-9);
  }
  static bool inside(const Aabb& b, const Eigen::Vector3d& p) {
    return (p.array() >= b.min.array()).all() && (p.array() <= b.max.array()).all();
  }
  /// A kept stencil for one sample's term (penalty, or dissipation), carrying its blocks: A's,
  /// then the tet's four nodes.
  ContactStencil& newEntry(const SamplePoint& sp, int tet, bool dissipation) {
    ContactStencil& e = out->Slot(sp.face, tet, n, order);
    (dissipation ? e.dissipationActive : e.penaltyActive) = true;
    e.blocks = 0;
    for (int b = 0; b < sp.blocks; ++b) e.offs[e.blocks++] = sp.offs[b];
    for (int c = 0; c < 4; ++c) e.offs[e.blocks++] = (*Bin.nodeDof)[3 * B.rest.tets[tet][c]];
    out->Keep();
    return e;
  }
  /// The sample's penalty (through the tet that contains it now), then its dissipation.
  void Process(const SamplePoint& sp) {
    const double w = sp.weight;
    const bool nowIn = inside(box, sp.y);
    Pullback pb;
    bool located = false;
    SdfSample field;
    if (nowIn) {
      Eigen::Vector4d lam;
      const int t = Bin.locator->Locate(sp.y, &lam);
      located = t >= 0 && PullbackThrough(B, xB, t, sp.y, &pb);
      if (located) {
        field = grid.Evaluate(pb.X);
        out->minPhi = std::min(out->minPhi, field.value);
      }
    }
    // --- Penalty.
    if (located && field.value < delta) {
      bool rejected = false;
      if (alignmentTest) {
        Pullback pbn;
        if (PullbackThrough(B, xBn, pb.tet, sp.yn, &pbn)) {
          const Eigen::Vector3d Gn = grid.Evaluate(pbn.X).gradient;
          rejected = Gn.dot(Normalized(pbn.F.transpose() * sp.nn)) > maxAlignment + kAlignmentRoundoff;
        }
      }
      if (!rejected) {
        ++out->activeSamples;
        const PenaltyDensity W = NormalPenaltyDensity(field.value, penalty);
        out->penaltyValue += w * W.W;
        if (records) {
          ContactSampleRecord rec;
          rec.position = sp.y;
          // The world normal of φ_B: ∇_y φ = F⁻ᵀ ∇Φ.
          const Eigen::Vector3d gradWorld = pb.Finv.transpose() * field.gradient;
          rec.normal = Normalized(gradWorld);
          rec.phi = field.value;
          rec.lambdaN = W.lambdaN;
          rec.traction = W.lambdaN * gradWorld;
          rec.weight = w;
          rec.face = sp.face;
          records->push_back(rec);
        }
        if (order >= 1) {
          Eigen::Vector3d gX;
          Eigen::Matrix3d HX;
          PenaltyInPullback(W, field, &gX, order >= 2 ? &HX : nullptr);
          TetPullbackStencil(pb, gX, order >= 2 ? &HX : nullptr, &point);
          ContactStencil& e = newEntry(sp, pb.tet, false);
          ChainToActor(sp.kin, point, w, &e.penaltyGradient,
                       order >= 2 ? &e.penaltyHessian : nullptr);
        }
      }
    }
    Dissipation(sp, located, pb, field);
  }
  /// The sample's dissipation: explicit normals through the tet that contained it at x_n, the
  /// current-geometry modes through the current tet (pb, when `located`).
  void Dissipation(const SamplePoint& sp, bool located, const Pullback& pb,
                   const SdfSample& field) {
    const double w = sp.weight;
    if (!withDissipation) return;
    const DissipationSetup& ds = *diss;
    const Eigen::VectorXd& xB0 = *Bin.x0;
    if (explicitNormals) {
      if (!inside(boxLast, sp.yn)) return;
      Eigen::Vector4d lam;
      const int tn = Bin.locatorLast->Locate(sp.yn, &lam);
      Pullback pbn, pbc, pb0;
      if (tn < 0 || !PullbackThrough(B, xBn, tn, sp.yn, &pbn)) return;
      const SdfSample f0 = grid.Evaluate(pbn.X);
      if (f0.value >= delta) return;
      const Eigen::Vector3d NA0 = Normalized(pbn.F.transpose() * sp.nn);
      const double al = f0.gradient.dot(NA0);
      if (al > maxAlignment + kAlignmentRoundoff) return;
      const double lambdaHat =
          AlignmentFactor(al, ds) * NormalPenaltyDensity(f0.value, ds.penalty).lambdaN;
      if (lambdaHat == 0.0) return;
      if (!PullbackThrough(B, xB, tn, sp.y, &pbc) || !PullbackThrough(B, xB0, tn, sp.y0, &pb0))
        return;
      const Eigen::Vector3d N = SplitDirection(f0.gradient, NA0, ds);
      const Eigen::Vector3d V = (pbc.X - pb0.X) / ds.dt;
      const DissipationDensity D = EvaluateSampleDissipation(
          lambdaHat, N, V, ds.coefficients, ds.HessianKind(order >= 2), ds.slips, sp.key);
      out->AddDissipative(w, ds.dt, D, ds.coefficients.mu, lambdaHat);
      if (order == 0) return;
      const Eigen::Matrix3d HX = D.hessian / ds.dt;
      TetPullbackStencil(pbc, D.gradient, order >= 2 ? &HX : nullptr, &point);
      ContactStencil& e = newEntry(sp, tn, true);
      ChainToActor(sp.kin, point, w, &e.dissipationResidual,
                   order >= 2 ? &e.dissipationJacobian : nullptr);
      return;
    }
    if (!located) return;
    Pullback pbn, pb0;
    if (!PullbackThrough(B, xBn, pb.tet, sp.yn, &pbn) || !PullbackThrough(B, xB0, pb.tet, sp.y0, &pb0))
      return;
    const double phiLoad = ds.mode == DissipationMode::ImplicitLoad
                               ? field.value
                               : field.value + field.gradient.dot(pbn.X - pb.X);
    if (phiLoad >= delta) return;
    const Eigen::Vector3d NA = Normalized(pb.F.transpose() * sp.n);
    const double al = field.gradient.dot(NA);
    if (al > maxAlignment + kAlignmentRoundoff) return;
    const double lambdaHat =
        AlignmentFactor(al, ds) * NormalPenaltyDensity(phiLoad, ds.penalty).lambdaN;
    if (lambdaHat == 0.0) return;
    const Eigen::Vector3d N = SplitDirection(field.gradient, NA, ds);
    const Eigen::Vector3d V = (pb.X - pb0.X) / ds.dt;
    const DissipationDensity D = EvaluateSampleDissipation(
        lambdaHat, N, V, ds.coefficients, DissipationHessian::None, ds.slips, sp.key);
    out->AddDissipative(w, ds.dt, D, ds.coefficients.mu, lambdaHat);
    if (order == 0) return;
    TetPullbackStencil(pb, D.gradient, nullptr, &point);
    ContactStencil& e = newEntry(sp, pb.tet, true);
    ChainToActor(sp.kin, point, w, &e.dissipationResidual, nullptr);
    if (order < 2) return;
    CurrentModeSample cs;
    cs.kin = sp.kin;
    const Eigen::Vector4i& T = B.rest.tets[pb.tet];
    for (int a = 0; a < 4; ++a) cs.xb[a] = xB.segment<3>(3 * T[a]);
    cs.Xr0 = B.rest.vertices[T[0]];
    cs.DmInv = B.elements[pb.tet].DmInv;
    cs.Dm = cs.DmInv.inverse();
    cs.Xbar = pb.X;
    cs.Yn = pbn.X;
    cs.X0 = pb0.X;
    cs.field = field;
    cs.setup = &ds;
    if (sp.kin.kind == SamplePointMap::Kind::Rigid) {
      cs.pA = sp.kin.origin;
      cs.rA = sp.kin.r;
      cs.normalA = sp.n;
      AddResidualJacobian<18>(cs, w, &e.dissipationJacobian);
    } else {
      for (int a = 0; a < 3; ++a) cs.xs[a] = sp.faceNodes[a];
      AddResidualJacobian<21>(cs, w, &e.dissipationJacobian);
    }
  }

  const CollidingInput& A;
  const SoftColliderInput& Bin;
  const SoftBodyModel& B;
  const Eigen::VectorXd& xB;
  const Eigen::VectorXd& xBn;
  const GridSdf& grid;
  const PenaltyParams& penalty;
  double maxAlignment;
  const DissipationSetup* diss;
  int order;
  PairStencils* out;
  std::vector<ContactSampleRecord>* records;
  double delta = 0.0;
  bool alignmentTest = false, withDissipation = false, explicitNormals = false;
  int n = 0;  // the stencil's size
  Aabb box, boxLast;
  PointStencil point;
};

}  // namespace

void EvaluatePairOnSoftCollider(const CollidingInput& A, const SoftColliderInput& Bin,
                                const PenaltyParams& penalty, double maxAlignment,
                                const DissipationSetup* diss, int order,
                                PairStencils* out,
                                std::vector<ContactSampleRecord>* records) {
  out->Reset();
  OnSoftCollider eval(A, Bin, penalty, maxAlignment, diss, order, out, records);
  const bool explicitNormals = eval.explicitNormals;
  const Aabb& box = eval.box;
  const Aabb& boxLast = eval.boxLast;
  auto inside = OnSoftCollider::inside;
  SamplePoint sp;
  if (A.kind) {
    const ActorKind& K = *A.kind;
    const Eigen::VectorXd& q = *A.x;
    const Eigen::VectorXd& qn = A.xLast ? *A.xLast : q;
    // Culled by A's sample balls against B's boxes, then sample by sample; the box test on the
    // current point comes before x_n's sample is formed.
    auto near = [&](const Eigen::Vector3d& c, const Eigen::Vector3d& cLast, double r) {
      return box.TouchesBall(c, r) || (explicitNormals && boxLast.TouchesBall(cLast, r));
    };
    K.ForEachSampleNear(q, qn, near, [&](int begin, int end) {
      for (int k = begin; k < end; ++k) {
        const KindSample ks = K.Sample(k, q);
        if (!CollidesOnSoftField(ks)) continue;
        const bool nowIn = inside(box, ks.y);
        if (!nowIn && !explicitNormals) continue;
        const KindSample last = A.xLast ? K.Sample(k, qn) : ks;
        if (!nowIn && !inside(boxLast, last.y)) continue;
        sp.key = k;
        sp.kin = ks.map;
        sp.y = ks.y;
        sp.yn = last.y;
        sp.y0 = A.x0 ? K.Sample(k, *A.x0).y : ks.y;
        sp.n = ks.n;
        sp.nn = last.n;
        sp.weight = ks.weight;
        sp.face = ks.face;
        for (int a = 0; a < 3; ++a) sp.faceNodes[a] = ks.faceNodes[a];
        sp.blocks = ks.Blocks();
        for (int b = 0; b < sp.blocks; ++b) sp.offs[b] = (*A.stageDof)[ks.dof[b]];
        eval.n = ks.map.Dofs() + 12;
        eval.Process(sp);
      }
    });
    return;
  }
  // A kind's sample body: the stencil carries the body's [δp, δθ].
  const RigidBodyModel& M = *A.rigid;
  const RigidPose& a = *A.pose;
  const RigidPose& an = A.start ? A.start->last : a;
  sp.blocks = 2;
  sp.offs[0] = A.bodyOffs[0];
  sp.offs[1] = A.bodyOffs[1];
  sp.face = -1;
  for (size_t k = 0; k < M.samples.size(); ++k) {
    const SurfaceSample& s = M.samples[k];
    sp.key = static_cast<int>(k);
    sp.kin = SamplePointMap::Rigid(a.R * s.X, a.p);
    sp.y = a.p + sp.kin.r;
    sp.yn = an.p + an.R * s.X;
    // Cheap rejection: a sample outside both boxes carries nothing.
    if (!inside(box, sp.y) && !(explicitNormals && inside(boxLast, sp.yn))) continue;
    sp.y0 = A.start ? Eigen::Vector3d(A.start->p + A.start->R * s.X) : sp.y;
    sp.n = a.R * s.normal;
    sp.nn = an.R * s.normal;
    sp.weight = s.weight;
    eval.Process(sp);
  }
}

}  // namespace superdex
