#include "core/contact/kind_contact.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "core/contact/dissipation_kernels.h"
#include "core/contact/rigid_dissipation.h"
#include "core/contact/sample_chain.h"
#include "core/contact/sphere_cap.h"
#include "core/model/rigid_math.h"
#include "energies/sphere_penalty.h"

namespace superdex {
namespace {
using namespace dissipation_kernels;

/// R X + t, written out: the per-sample products of a rigid body's samples, inlined (Eigen's
/// 3 × 3 product assignments are called out of line there).
inline Eigen::Vector3d MulAdd(const Eigen::Matrix3d& R, const Eigen::Vector3d& X,
                              const Eigen::Vector3d& t) {
  return Eigen::Vector3d(R(0, 0) * X[0] + R(0, 1) * X[1] + R(0, 2) * X[2] + t[0],
                         R(1, 0) * X[0] + R(1, 1) * X[1] + R(1, 2) * X[2] + t[1],
                         R(2, 0) * X[0] + R(2, 1) * X[1] + R(2, 2) * X[2] + t[2]);
}
inline Eigen::Vector3d Mul(const Eigen::Matrix3d& R, const Eigen::Vector3d& X) {
  return Eigen::Vector3d(R(0, 0) * X[0] + R(0, 1) * X[1] + R(0, 2) * X[2],
                         R(1, 0) * X[0] + R(1, 1) * X[1] + R(1, 2) * X[2],
                         R(2, 0) * X[0] + R(2, 1) * X[1] + R(2, 2) * X[2]);
}

/// The collider's part of a point stencil: on a tet field the tet's (TetPullbackStencil);
/// otherwise RigidPullbackStencil formed on [y, δp_B, δθ_B], kept for a rigid frame, dropped for a
/// static one, and for a translating frame mapped to its dofs by δp_B = F_p δq_B (g_B = F_pᵀ g_p,
/// H_yB = H_yp F_p, H_By = F_pᵀ H_py, H_BB = F_pᵀ H_pp F_p; the rotation part vanishes with a
/// frame that does not rotate).
void ColliderStencil(const FrameSide& B, const SamplePullback& p, const Eigen::Vector3d& gY,
                     const Eigen::Matrix3d* HY, PointStencil* point) {
  if (p.tet) return TetPullbackStencil(*p.tet, gY, HY, point);
  const Eigen::Vector3d& d = p.d;
  RigidPullbackStencil(B.pose.R, d, gY, HY, B.motion != FrameSide::Motion::Static, point);
  if (B.motion != FrameSide::Motion::Translation) return;
  const int m = 3 * B.blocks;
  const auto Fp = B.Fp.leftCols(m);
  const Eigen::Vector3d gp = point->g.segment<3>(3);
  point->colliderDofs = m;
  point->g.segment(3, m) = Fp.transpose() * gp;
  if (!HY) return;
  const Eigen::Matrix3d Hyp = point->H.block<3, 3>(0, 3), Hpy = point->H.block<3, 3>(3, 0);
  const Eigen::Matrix3d Hpp = point->H.block<3, 3>(3, 3);
  point->H.block(0, 3, 3, m) = Hyp * Fp;
  point->H.block(3, 0, m, 3) = Fp.transpose() * Hpy;
  point->H.block(3, 3, m, m) = Fp.transpose() * Hpp * Fp;
}

/// A covector of B's coordinates in the world: R_B v on a frame, F⁻ᵀ v on a tet field (the
/// field's gradient, a traction).
Eigen::Vector3d ToWorld(const FrameSide& B, const SamplePullback& p, const Eigen::Vector3d& v) {
  return p.tet ? Eigen::Vector3d(p.tet->Finv.transpose() * v) : Eigen::Vector3d(B.pose.R * v);
}

template <typename T>
Vec3<T> Cross(const Vec3<T>& a, const Vec3<T>& b) {
  return Vec3<T>(a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(),
                 a.x() * b.y() - a.y() * b.x());
}

/// B's pullback of a sample's moved point y and normal n as jets: Y and N_A in B's coordinates,
/// and the world force f of a B-covector g. On a frame, with the first-order retraction of its
/// rotation ω: Y = R_Bᵀ(d − ω × d), N_A = R_Bᵀ(n − ω × n), f = R_B g + ω × R_B g. On a tet field,
/// through the tet's affine map at the moved nodes: Y = X_0 + Dm Ds⁻¹(y − x_0), N_A the unit
/// Fᵀ n, f = F⁻ᵀ g, and λ the point's barycentric coordinates (B's residual −λ_a f per node).
template <typename Jet>
struct JetPullback {
  Vec3<Jet> pB, om, d;
  Mat3<Jet> RBt, Finv;
  Jet lambda[4];
  bool tet = false;

  JetPullback(const FrameSide& B, const SamplePullback& p, const Jet* delta, int nA,
              const Vec3<Jet>& y) {
    tet = p.tet != nullptr;
    if (tet) {
      FormTet(B, p, delta + nA, y);
      return;
    }
    pB = B.pose.p.cast<Jet>();
    om = Vec3<Jet>::Zero();
    if (B.motion == FrameSide::Motion::Rigid) {
      pB += Vec3<Jet>(delta[nA], delta[nA + 1], delta[nA + 2]);
      om = Vec3<Jet>(delta[nA + 3], delta[nA + 4], delta[nA + 5]);
    } else if (B.motion == FrameSide::Motion::Translation) {
      for (int c = 0; c < B.Dofs(); ++c) pB += B.Fp.col(c).cast<Jet>() * delta[nA + c];
    }
    RBt = B.pose.R.transpose().cast<Jet>();
    d = y - pB;
    Y = RBt * (d - Cross<Jet>(om, d));
  }
  void FormTet(const FrameSide& B, const SamplePullback& p, const Jet* dB, const Vec3<Jet>& y) {
    const SoftBodyModel& m = *B.tet->model;
    const Eigen::Vector4i& T = m.rest.tets[p.tet->tet];
    Vec3<Jet> x[4];
    for (int a = 0; a < 4; ++a)
      x[a] = B.tet->x->segment<3>(3 * T[a]).cast<Jet>() +
             Vec3<Jet>(dB[3 * a], dB[3 * a + 1], dB[3 * a + 2]);
    Mat3<Jet> Ds;
    Ds << x[1] - x[0], x[2] - x[0], x[3] - x[0];
    const Mat3<Jet> Dsinv = Ds.inverse();
    const Vec3<Jet> beta = Dsinv * (y - x[0]);
    lambda[0] = Jet(1.0) - beta.sum();
    for (int a = 0; a < 3; ++a) lambda[a + 1] = beta[a];
    const Eigen::Matrix3d& DmInv = m.elements[p.tet->tet].DmInv;
    const Mat3<Jet> Dm = DmInv.inverse().cast<Jet>();
    Y = m.rest.vertices[T[0]].cast<Jet>() + Dm * beta;
    Finv = Dm * Dsinv;
    F = Ds * DmInv.cast<Jet>();
  }
  Vec3<Jet> Normal(const Vec3<Jet>& n) const {
    if (!tet) return RBt * (n - Cross<Jet>(om, n));
    const Vec3<Jet> N = F.transpose() * n;
    return N / sqrt(N.squaredNorm());
  }
  Vec3<Jet> Force(const FrameSide& B, const Vec3<Jet>& g) const {
    if (tet) return Finv.transpose() * g;
    const Vec3<Jet> fB = B.pose.R.cast<Jet>() * g;
    return fB + Cross<Jet>(om, fB);
  }
  /// B's part of the residual of world force f on A's point.
  void AddResidual(const FrameSide& B, const Vec3<Jet>& f, int nA, Jet* r) const {
    if (tet) {
      for (int a = 0; a < 4; ++a)
        for (int k = 0; k < 3; ++k) r[nA + 3 * a + k] = -lambda[a] * f[k];
    } else if (B.motion == FrameSide::Motion::Rigid) {
      const Vec3<Jet> tau = -Cross<Jet>(d, f);
      for (int k = 0; k < 3; ++k) r[nA + k] = -f[k], r[nA + 3 + k] = tau[k];
    } else if (B.motion == FrameSide::Motion::Translation) {
      for (int c = 0; c < B.Dofs(); ++c) r[nA + c] = -(B.Fp.col(c).cast<Jet>().dot(f));
    }
  }
  Vec3<Jet> Y;
  Mat3<Jet> F;
};

/// Adds w ∂r/∂δ of one sample's current-mode residual on the pair stencil δ = [δq_A, δq_B], r the
/// world residual: A's part Jᵀ f (a rigid A: [f; r_A × f]), B's part [−f; −d × f] (rigid),
/// F_pᵀ(−f) (translating) or −λ_a f per tet node, f B's covector ∂R/∂V in the world
/// (JetPullback). Differentiated by forward-mode AD with the first-order retractions
/// y + δp + δθ × r, R ← (I + [δθ]×) R (exact first derivatives at δ = 0, the stage's world-torque
/// convention).
template <int N>  // jets of N >= n derivatives (the smallest of 9, 12, 15, 24 that holds the stencil)
void AddCurrentModeJacobian(const PairSample& s, const FrameSide& B, const SdfSample& field,
                            const SamplePullback& p, const Eigen::Vector3d& Y0,
                            const DissipationSetup& ds, StencilMatrix* J) {
  const int nA = s.map.Dofs(), nB = B.Dofs(), n = nA + nB;
  using Jet = ceres::Jet<double, N>;
  Jet delta[N];
  for (int i = 0; i < n; ++i) delta[i] = Jet(0.0, i);
  auto vec = [&](int at) { return Vec3<Jet>(delta[at], delta[at + 1], delta[at + 2]); };
  const bool rigidA = s.map.kind == SamplePointMap::Kind::Rigid;
  Vec3<Jet> y = s.y.cast<Jet>(), nw = s.n.cast<Jet>(), rA = s.map.r.cast<Jet>();
  if (rigidA) {
    const Vec3<Jet> th = vec(3);
    rA += Cross<Jet>(th, s.map.r.cast<Jet>());
    y += vec(0) + Cross<Jet>(th, s.map.r.cast<Jet>());
    if (s.hasNormal) nw += Cross<Jet>(th, s.n.cast<Jet>());
  } else {
    for (int a = 0; a < s.map.nodes; ++a) y += s.map.bary[a] * vec(3 * a);
    if (s.faceNormal) {  // n = m/|m|, m = (x₁ − x₀) × (x₂ − x₀) of the moved nodes
      const Vec3<Jet> x0 = s.faceNodes[0].cast<Jet>() + vec(0);
      const Vec3<Jet> m = Cross<Jet>(s.faceNodes[1].cast<Jet>() + vec(3) - x0,
                                     s.faceNodes[2].cast<Jet>() + vec(6) - x0);
      nw = m / sqrt(m.squaredNorm());
    }
  }
  const JetPullback<Jet> pb(B, p, delta, nA, y);
  const Vec3<Jet> NA = s.hasNormal ? pb.Normal(nw) : Vec3<Jet>::Zero();
  const Vec3<Jet> g = CurrentModeDissipationGradient<Jet>(pb.Y, NA, p.Y, field, p.Yn, Y0, ds);
  const Vec3<Jet> f = pb.Force(B, g);
  Jet r[N];
  if (rigidA) {
    const Vec3<Jet> tau = Cross<Jet>(rA, f);
    for (int k = 0; k < 3; ++k) r[k] = f[k], r[3 + k] = tau[k];
  } else {
    for (int a = 0; a < s.map.nodes; ++a)
      for (int k = 0; k < 3; ++k) r[3 * a + k] = s.map.bary[a] * f[k];
  }
  pb.AddResidual(B, f, nA, r);
  for (int i = 0; i < n; ++i) J->row(i) += s.weight * r[i].v.head(n).transpose();
}

void AddCurrentModeJacobianOfSize(const PairSample& s, const FrameSide& B, const SdfSample& field,
                                  const SamplePullback& p, const Eigen::Vector3d& Y0,
                                  const DissipationSetup& ds, StencilMatrix* J) {
  const int n = s.map.Dofs() + B.Dofs();
  if (n <= 9) return AddCurrentModeJacobian<9>(s, B, field, p, Y0, ds, J);
  if (n <= 12) return AddCurrentModeJacobian<12>(s, B, field, p, Y0, ds, J);
  if (n <= 15) return AddCurrentModeJacobian<15>(s, B, field, p, Y0, ds, J);
  AddCurrentModeJacobian<kMaxStencil>(s, B, field, p, Y0, ds, J);
}

SamplePullback PullbackOf(const PairSample& s, const FrameSide& B) {
  SamplePullback p;
  const Eigen::Matrix3d RBt = B.pose.R.transpose(), RnBt = B.last.R.transpose();
  p.d = s.y - B.pose.p;
  p.Y = RBt * p.d;
  p.Yn = RnBt * (s.yLast - B.last.p);
  p.NA = s.hasNormal ? Eigen::Vector3d(RBt * s.n) : Eigen::Vector3d::Zero();
  p.NAn = s.hasNormal ? Eigen::Vector3d(RnBt * s.nLast) : Eigen::Vector3d::Zero();
  return p;
}

/// The penalty of one sample into stencil *st; returns whether it was active. With `record`, an
/// active sample's normal load is written there (its place, weight and φ are the caller's).
bool AddPenalty(const PairSample& s, const FrameSide& B, const SamplePullback& p, const SdfSample& field,
                const PenaltyParams& penalty, double m, int order, PairStencils* out,
                ContactStencil* st, RigidSampleSums* sums, ContactSampleRecord* record) {
  if (!(field.value < penalty.delta)) return false;
  if (s.hasNormal && std::isfinite(m) && p.hasLast) {
    SdfSample atLast;  // the gradient alone
    if (B.hasLast) B.field->EvaluateFirstOrderBelow(p.Yn, INFINITY, &atLast);
    const Eigen::Vector3d& G = B.hasLast ? atLast.gradient : field.gradient;
    const Eigen::Vector3d NA = B.hasLast ? p.NAn : p.NA;
    if (G.dot(NA) > m + kAlignmentRoundoff) return false;
  }
  ++out->activeSamples;
  st->penaltyActive = true;
  const PenaltyDensity W = NormalPenaltyDensity(field.value, penalty);
  out->penaltyValue += s.weight * W.W;
  if (record) {
    const Eigen::Vector3d gradient = ToWorld(B, p, field.gradient);  // ∇_y φ
    record->normal = p.tet ? gradient.normalized()
                           : Eigen::Vector3d(B.pose.R * field.gradient.normalized());
    record->lambdaN = W.lambdaN;
    record->traction = W.lambdaN * gradient;
  }
  if (order < 1) return true;
  Eigen::Vector3d gY;
  Eigen::Matrix3d HY;
  PointStencil point;
  PenaltyInPullback(W, field, &gY, order >= 2 ? &HY : nullptr);
  if (sums->on) {
    AddFunctionOfPullback(s.map.r, p.d, B.pose.R, gY, nullptr, sums->bDynamic, s.weight,
                          &sums->penaltyGradient, nullptr);
    if (order >= 2) sums->penalty.Add(sums->rB, gY, HY, s.weight);
    return true;
  }
  ColliderStencil(B, p, gY, order >= 2 ? &HY : nullptr, &point);
  ChainToActor(s.map, point, s.weight, &st->penaltyGradient,
               order >= 2 ? &st->penaltyHessian : nullptr);
  return true;
}

/// The dissipation of one sample (sample index k, the slip key) into stencil *st. With `record`,
/// its friction and damping tractions are written there.
void AddDissipation(const PairSample& s, int k, const FrameSide& B, const SamplePullback& p,
                    const SdfSample& field, const DissipationSetup& ds, int order,
                    PairStencils* out, ContactStencil* st, RigidSampleSums* sums,
                    ContactSampleRecord* record = nullptr) {
  const bool explicitNormals = ds.mode == DissipationMode::ExplicitNormals;
  const double m = ds.maxAlignment, delta = ds.penalty.delta;
  double lambdaHat = 0.0;
  Eigen::Vector3d N;
  if (explicitNormals) {
    SdfSample f0;
    if (!B.field->EvaluateFirstOrderBelow(p.Yn, delta, &f0)) return;  // its value and gradient
    const double al = f0.gradient.dot(p.NAn);
    if (s.hasNormal && al > m + kAlignmentRoundoff) return;
    lambdaHat = AlignmentFactor(al, ds) * NormalPenaltyDensity(f0.value, ds.penalty).lambdaN;
    N = SplitDirection(f0.gradient, p.NAn, ds);
  } else {
    const double phiLoad = ds.mode == DissipationMode::ImplicitLoad
                               ? field.value
                               : field.value + field.gradient.dot(p.Yn - p.Y);
    if (phiLoad >= delta) return;
    const double al = field.gradient.dot(p.NA);
    if (s.hasNormal && al > m + kAlignmentRoundoff) return;
    lambdaHat = AlignmentFactor(al, ds) * NormalPenaltyDensity(phiLoad, ds.penalty).lambdaN;
    N = SplitDirection(field.gradient, p.NA, ds);
  }
  if (lambdaHat == 0.0) return;
  const Eigen::Vector3d Y0 = p.tet ? p.Y0 : Eigen::Vector3d(B.start.Rinv * (s.y0 - B.start.p));
  const Eigen::Vector3d V = (p.Y - Y0) / ds.dt;
  const bool hessian = explicitNormals && order >= 2;
  const DissipationDensity D = EvaluateSampleDissipation(
      lambdaHat, N, V, ds.coefficients, ds.HessianKind(hessian), ds.slips, k);
  st->dissipationActive = true;
  out->AddDissipative(s.weight, ds.dt, D, ds.coefficients.mu, lambdaHat);
  if (record) {  // the tractions on A, −∂R/∂V split, B's coordinates to the world
    record->friction = ToWorld(B, p, D.coulomb + D.viscousTangential);
    record->damping = ToWorld(B, p, D.viscousNormal);
  }
  if (order == 0) return;
  Eigen::Matrix3d HY;  // ∂²(Δt R)/∂Y², a potential's only
  if (hessian) HY = D.hessian / ds.dt;
  if (sums->on) {
    AddFunctionOfPullback(s.map.r, p.d, B.pose.R, D.gradient, nullptr, sums->bDynamic, s.weight,
                          &sums->dissipationResidual, nullptr);
    if (order < 2) return;
    const Eigen::Vector3d& rB = sums->rB;
    if (explicitNormals) {
      sums->potentialDissipation.Add(rB, D.gradient, HY, s.weight);
    } else {
      const CurrentModeLinearization lin = LinearizeCurrentModeGradient(p.Y, p.NA, field, p.Yn, Y0, ds);
      sums->force.Add(rB, p.NA, lin.g, lin.GY, lin.GN, s.weight);
    }
    return;
  }
  PointStencil point;
  ColliderStencil(B, p, D.gradient, hessian ? &HY : nullptr, &point);
  ChainToActor(s.map, point, s.weight, &st->dissipationResidual,
               hessian ? &st->dissipationJacobian : nullptr);
  if (order >= 2 && !explicitNormals)
    AddCurrentModeJacobianOfSize(s, B, field, p, Y0, ds, &st->dissipationJacobian);
}

/// Fills a stencil's blocks: the sample's, then the frame's (on a tet field, tet t's nodes).
void SetBlocks(const PairSample& s, const FrameSide& B, int t, ContactStencil* st) {
  st->blocks = 0;
  for (int b = 0; b < s.blocks; ++b) st->offs[st->blocks++] = s.offs[b];
  if (B.motion == FrameSide::Motion::Tet) {
    for (int c = 0; c < 4; ++c) st->offs[st->blocks++] = B.tet->NodeOffset(t, c);
  } else if (B.motion == FrameSide::Motion::Rigid) {
    st->offs[st->blocks++] = B.offs[0];
    st->offs[st->blocks++] = B.offs[1];
  } else if (B.motion == FrameSide::Motion::Translation) {
    for (int b = 0; b < B.blocks; ++b) st->offs[st->blocks++] = B.offs[b];
  }
}

}  // namespace

FrameEvaluation::FrameEvaluation(const FrameSide& B, const PenaltyParams& penalty,
                                 double maxAlignment, const DissipationSetup* dissipation,
                                 int order, PairStencils* out,
                                 std::vector<ContactSampleRecord>* records, bool append)
    : B_(B), penalty_(penalty), maxAlignment_(maxAlignment), dissipation_(dissipation),
      order_(order), out_(out), records_(records) {
  if (!append) out->Reset();
  withDissipation_ = dissipation && dissipation->coefficients.Any() && B.hasStart;
  // Samples without a colliding normal: no fading, friction split on the collider's normal.
  if (withDissipation_) {
    noNormal_ = *dissipation;
    noNormal_.fadeFriction = false;
    noNormal_.frictionWithColliderNormal = true;
  }
  explicitNormals_ = withDissipation_ && dissipation->mode == DissipationMode::ExplicitNormals;
  reconstructed_ = withDissipation_ && dissipation->mode == DissipationMode::ReconstructedLoad;
  finiteReach_ = std::isfinite(B.field->boundingRadius);
  reachLast2_ = ReachSquared(penalty.delta);
  penaltyValueOnly_ = order == 0 && !withDissipation_ && !records;
}

void FrameEvaluation::Close() {  // kept when it has a contribution, else its slot is taken again
  if (st_ && (st_->penaltyActive || st_->dissipationActive)) {
    sums_.Flush(B_, order_, st_);
    out_->Keep();
  }
  st_ = nullptr;
}

void FrameEvaluation::Open(const PairSample& s, int t) {
  if (st_ && s.face == st_->aFace && t == openTet_) {
    int k = 0;
    while (k < s.blocks && s.offs[k] == st_->offs[k]) ++k;
    if (k == s.blocks) return;
  }
  Close();
  st_ = &out_->Slot(s.face, t, s.map.Dofs() + B_.Dofs(), order_);
  openTet_ = t;
  SetBlocks(s, B_, t, st_);
  sums_.Begin(s, B_);
}

inline double FrameEvaluation::ReachSquared(double bound) const {
  const double reach = B_.field->boundingRadius + bound;
  return reach * reach;
}

inline bool FrameEvaluation::WithinReach(const Eigen::Vector3d& Y, double reach2) const {
  return !finiteReach_ || !(Y.squaredNorm() >= reach2);
}

inline bool FrameEvaluation::Candidate(const SamplePullback& p, double bound, double reach2,
                                       SdfSample* field, bool* below) {
  *below = false;
  if (WithinReach(p.Y, reach2)) {
    *below = B_.field->EvaluateFirstOrderBelow(p.Y, bound, field);
    out_->minPhi = std::min(out_->minPhi, field->value);
  }
  return *below || (explicitNormals_ && WithinReach(p.Yn, reachLast2_));
}

inline void FrameEvaluation::CompleteCandidate(const Eigen::Vector3d& Y, bool below,
                                               SdfSample* field) const {
  if (below && order_ >= 2) B_.field->CompleteHessian(Y, field);
}

inline bool FrameEvaluation::LoadFree(const SamplePullback& p, const SdfSample& field) const {
  return reconstructed_ && field.value >= penalty_.delta &&
         field.value + field.gradient.dot(p.Yn - p.Y) >= dissipation_->penalty.delta;
}

void FrameEvaluation::AddTerms(const PairSample& s, const SamplePullback& p, const SdfSample& field,
                               bool below) {
  Open(s);  // stencils only for samples that may contribute
  AddOpenTerms(s, p, field, below);
}

void FrameEvaluation::AddOpenTerms(const PairSample& s, const SamplePullback& p,
                                   const SdfSample& field, bool below) {
  ContactSampleRecord* record = BeginRecord();
  // The regrouped sums' arm in B's frame, R_Bᵀ r, for both terms' second derivatives.
  if (sums_.on && order_ >= 2) sums_.rB = B_.pose.R.transpose() * s.map.r;
  const bool penalty = below && !exactPenalty_ &&
                       AddPenalty(s, B_, p, field, penalty_, maxAlignment_, order_, out_, st_,
                                  &sums_, record);
  if (withDissipation_ && (below || explicitNormals_))
    AddDissipation(s, s.key, B_, p, field, s.hasNormal ? *dissipation_ : noNormal_, order_, out_,
                   st_, &sums_, record);
  if (record) EndRecord(s, below ? field.value : NAN, penalty);  // φ not read beyond the bound
}

ContactSampleRecord* FrameEvaluation::BeginRecord() {
  if (!records_) return nullptr;
  rec_ = ContactSampleRecord();
  return &rec_;
}

void FrameEvaluation::EndRecord(const PairSample& s, double phi, bool penalty) {
  // Reported when its penalty is active or its dissipation exerts a traction.
  if (!(penalty || !rec_.friction.isZero(0) || !rec_.damping.isZero(0))) return;
  rec_.position = s.y;
  rec_.phi = phi;
  rec_.weight = s.weight;
  rec_.face = s.face;
  records_->push_back(rec_);
}

void FrameEvaluation::AddOnTet(const PairSample& s) {
  if (!CollidesOnTetField(s)) return;
  const TetFieldSide& T = *B_.tet;
  ContactSampleRecord* record = BeginRecord();
  bool penalty = false;
  SdfSample field;
  field.value = NAN;  // not located now
  TetPullback pb, pbn, pb0;
  Eigen::Vector4d lambda;
  const int t = T.box.Contains(s.y) ? T.locator->Locate(s.y, &lambda) : -1;
  if (t >= 0 && PullbackThrough(*T.model, *T.x, t, s.y, &pb)) {
    field = B_.field->Evaluate(pb.X);
    out_->minPhi = std::min(out_->minPhi, field.value);
    SamplePullback p;
    p.tet = &pb;
    p.Y = pb.X;
    p.NA = ReferenceNormal(pb, s.n);
    p.hasLast = PullbackThrough(*T.model, *T.xLast, t, s.yLast, &pbn);
    if (p.hasLast) {
      p.Yn = pbn.X;
      p.NAn = ReferenceNormal(pbn, s.nLast);
    }
    Open(s, t);
    penalty = AddPenalty(s, B_, p, field, penalty_, maxAlignment_, order_, out_, st_, &sums_,
                         record);
    if (withDissipation_ && !explicitNormals_ && p.hasLast &&
        PullbackThrough(*T.model, *T.x0, t, s.y0, &pb0)) {
      p.Y0 = pb0.X;
      AddDissipation(s, s.key, B_, p, field, *dissipation_, order_, out_, st_, &sums_, record);
    }
  }
  if (explicitNormals_) AddOnTetAtLast(s, record);
  if (record) EndRecord(s, field.value, penalty);  // φ NaN where no tet contains y
}

void FrameEvaluation::AddOnTetAtLast(const PairSample& s, ContactSampleRecord* record) {
  const TetFieldSide& T = *B_.tet;
  if (!T.boxLast.Contains(s.yLast)) return;
  Eigen::Vector4d lambda;
  const int t = T.locatorLast->Locate(s.yLast, &lambda);
  TetPullback pbn, pb, pb0;
  if (t < 0 || !PullbackThrough(*T.model, *T.xLast, t, s.yLast, &pbn) ||
      !PullbackThrough(*T.model, *T.x, t, s.y, &pb) ||
      !PullbackThrough(*T.model, *T.x0, t, s.y0, &pb0))
    return;
  SamplePullback p;
  p.tet = &pb;
  p.Y = pb.X;
  p.Yn = pbn.X;
  p.Y0 = pb0.X;
  p.NA = ReferenceNormal(pb, s.n);
  p.NAn = ReferenceNormal(pbn, s.nLast);
  Open(s, t);
  const SdfSample unused;  // explicit normals read the field at Y_n
  AddDissipation(s, s.key, B_, p, unused, *dissipation_, order_, out_, st_, &sums_, record);
}

void FrameEvaluation::Add(const PairSample& s) {
  if (B_.tet) return AddOnTet(s);
  const SamplePullback p = PullbackOf(s, B_);
  // The field's derivatives only where a term can use them: φ < δ for the penalty and the
  // current load; the reconstructed load φ + G·(Y_n − Y) >= φ − L|Y_n − Y| needs φ below
  // δ + L|Y_n − Y|. Explicit normals read the field at Y_n by themselves.
  double bound = penalty_.delta;
  if (reconstructed_) bound += B_.field->lipschitz * (p.Yn - p.Y).norm();
  SdfSample field;
  bool below;
  if (!Candidate(p, bound, ReachSquared(bound), &field, &below) || LoadFree(p, field)) return;
  CompleteCandidate(p.Y, below, &field);
  AddTerms(s, p, field, below);
}

bool FrameEvaluation::BeginRigidBody(const RigidPose& a, const RigidPose& an,
                                     const RigidStageStart* start, int offP, int offTheta,
                                     int keyOffset, const RigidBodyModel& body,
                                     const BodyInFrame& inFrame) {
  SampleSink::BeginRigidBody(a, an, start, offP, offTheta, keyOffset, body, inFrame);
  rigidOpen_ = false;
  A_ = inFrame;
  dA_ = a.p - B_.pose.p;
  // |Y_n − Y| of any sample, with a margin for round-off.
  motion_ = ((A_.tn - A_.t).norm() + A_.turn * body.samplesRadius) * (1.0 + 1e-12) + 1e-15;
  exactPenalty_ = body.surfaceIntegral == SurfaceIntegral::ExactSphere && AddExactSpherePenalty(body);
  // With the penalty exact, the samples serve the dissipation and the records only; where the
  // dissipation's load is the cap's at x_n, the cap's own quadrature serves it instead.
  if (exactPenalty_ && withDissipation_ && AddCapDissipation(body, keyOffset)) return false;
  return !exactPenalty_ || withDissipation_ || records_;
}

bool FrameEvaluation::AddCapDissipation(const RigidBodyModel& body, int keyOffset) {
  // Explicit normals read the load, the normals and the alignment at x_n; the reconstructed load
  // φ + G·(Y_n − Y) on a plane is φ(Y_n). Both vanish outside the cap at x_n, whose points are
  // fixed in A's body frame for the stage. (The current load, and the reconstructed one on a
  // curved field or a box, whose face region holds at x_n but is not checked at the current
  // samples, reach beyond it: the body's samples carry those.)
  const bool planeCollider = B_.field->type == ColliderType::Plane;
  if (!(explicitNormals_ || (reconstructed_ && planeCollider))) return false;
  const double r = body.shape.radius;
  const double m = dissipation_->maxAlignment;
  const PenaltyParams& p = dissipation_->penalty;
  const AxialField a = AxialFieldAt(*B_.field, A_.tn, r, m, p);  // A's centre at x_n
  if (a.kind == AxialField::Kind::None) return false;
  const SphereCap cap = a.kind == AxialField::Kind::Plane ? PlaneCap(a.x, r, m, p)
                                                          : SphereFieldCap(a.x, r, a.radius, m, p);
  SurfaceSample capSamples[kSphereCapMaxSamples];
  const int n = SphereCapSamples(cap, r, a.axis, A_.Rn.transpose(), capSamples);
  AddRigidSamples(capSamples, 0, n, keyOffset + static_cast<int>(body.samples.size()), motion_);
  return true;
}

ContactSampleRecord FrameEvaluation::ExactSphereRecord(const RigidBodyModel& body,
                                                      const AxialField& a,
                                                      const Eigen::Vector3d& w, double phiDeepest,
                                                      double dE) const {
  // One record for the active cap: at its deepest point, its area (φ < δ: t + 1 <= the cap's
  // height over r, from φ(t) = δ) as the weight and the mean traction −E' w / area on it.
  const double r = body.shape.radius;
  double height;  // t₀ + 1, t₀ the cap's edge
  if (a.kind == AxialField::Kind::Plane) {
    height = (penalty_.delta - phiDeepest) / r;
  } else {
    const double reach = a.radius + penalty_.delta;
    height = (reach * reach - (a.x - r) * (a.x - r)) / (2.0 * a.x * r);
  }
  ContactSampleRecord rec;
  rec.position = a_.p - r * w;
  rec.normal = w;
  rec.phi = phiDeepest;
  rec.weight = 2.0 * M_PI * r * r * std::clamp(height, 0.0, 2.0);
  rec.lambdaN = rec.weight > 0.0 ? -dE / rec.weight : 0.0;
  rec.traction = rec.lambdaN * w;
  return rec;
}

bool FrameEvaluation::AddExactSpherePenalty(const RigidBodyModel& body) {
  if (B_.motion != FrameSide::Motion::Static && B_.motion != FrameSide::Motion::Rigid) return false;
  // A's centre (its body origin) in B's frame, A_.t: E depends on its height over the plane (or
  // box face) or its distance from the sphere's centre alone, so A's rotation and B's do not enter.
  const double r = body.shape.radius;
  const AxialField a = AxialFieldAt(*B_.field, A_.t, r, maxAlignment_, penalty_);
  if (a.kind == AxialField::Kind::None) return false;
  const bool plane = a.kind == AxialField::Kind::Plane;
  const SpherePenalty e = plane ? SpherePlanePenalty(a.x, r, maxAlignment_, penalty_)
                                : SphereSpherePenalty(a.x, r, a.radius, maxAlignment_, penalty_);
  const double phiDeepest = plane ? a.x - r : a.x - r - a.radius;
  out_->minPhi = std::min(out_->minPhi, phiDeepest);
  if (!(phiDeepest < penalty_.delta)) return true;
  ++out_->activeSamples;  // the whole sphere counts as one
  out_->penaltyValue += e.E;
  Open(rigid_);
  rigidOpen_ = true;
  st_->penaltyActive = true;
  // ĝ = ∇_Y x in B's frame; w, its world direction, is where x grows.
  const Eigen::Vector3d& gHat = a.axis;
  const Eigen::Vector3d w = B_.pose.R * gHat;
  if (records_) records_->push_back(ExactSphereRecord(body, a, w, phiDeepest, e.dE));
  if (order_ < 1) return true;
  // E as a function of the centre's pullback Y (a sample at arm r = 0), through the one chain
  // of the samples: g_Y = E' ĝ, H_Y = E'' ĝĝᵀ (+ (E'/d)(I − ĝĝᵀ) for the sphere's distance).
  const Eigen::Vector3d gY = e.dE * gHat;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  AddFunctionOfPullback(zero, dA_, B_.pose.R, gY, nullptr, sums_.bDynamic, 1.0,
                        &sums_.penaltyGradient, nullptr);
  if (order_ < 2) return true;
  Eigen::Matrix3d HY = e.d2E * gHat * gHat.transpose();
  if (!plane) HY += e.dE / a.x * (Eigen::Matrix3d::Identity() - gHat * gHat.transpose());
  sums_.penalty.Add(zero, gY, HY, 1.0);
  return true;
}

void FrameEvaluation::AddRigidSamples(const SurfaceSample* samples, int begin, int end,
                                      int keyOffset, double motion) {
  if (B_.tet) return SampleSink::AddRigidSamples(samples, begin, end, keyOffset, motion);
  // One product per pullback through the body's composed transforms: Y, and Y_n where the
  // explicit normals' load reads it; the rest only for a candidate (AddRigidCandidate). The
  // reconstructed load's bound is the leaf's, δ + L max |Y_n − Y| (Add's per-sample bound is no
  // larger); Y_n is formed only where φ falls below it, and the load test (LoadFree) decides.
  // The loop keeps the body's transforms in locals.
  const Eigen::Matrix3d RA = A_.R, RnA = A_.Rn;
  const Eigen::Vector3d YA = A_.t, YnA = A_.tn;
  const double bound =
      penalty_.delta + (reconstructed_ ? B_.field->lipschitz * std::min(motion, motion_) : 0.0);
  const bool explicitNormals = explicitNormals_;
  const double reach2 = ReachSquared(bound);  // the leaf's, formed once
  SdfSample field;  // its value set per sample, its derivatives where below the bound
  for (int q = begin; q < end; ++q) {
    const SurfaceSample& ss = samples[q];
    SamplePullback p;
    p.Y = MulAdd(RA, ss.X, YA);
    if (explicitNormals) p.Yn = MulAdd(RnA, ss.X, YnA);
    bool below;
    if (!Candidate(p, bound, reach2, &field, &below)) continue;
    if (reconstructed_) {
      p.Yn = MulAdd(RnA, ss.X, YnA);
      if (LoadFree(p, field)) continue;
    }
    CompleteCandidate(p.Y, below, &field);
    AddRigidCandidate(ss, keyOffset + q, explicitNormals || reconstructed_, &p, field, below);
  }
}

void FrameEvaluation::AddRigidCandidate(const SurfaceSample& ss, int key, bool hasYn,
                                        SamplePullback* p, const SdfSample& field, bool below) {
  // Y_n and N_A at x_n: read by the alignment test at x_n (B.hasLast) and by the dissipation.
  const bool atLast = B_.hasLast || withDissipation_;
  if (!hasYn && atLast) p->Yn = MulAdd(A_.Rn, ss.X, A_.tn);
  p->NA = Mul(A_.R, ss.normal);
  if (atLast) p->NAn = Mul(A_.Rn, ss.normal);
  PairSample& s = rigid_;
  s.weight = ss.weight;
  s.key = key;
  if (!rigidOpen_) {  // the body's first candidate: its samples share one stencil
    Open(s);
    rigidOpen_ = true;
  }
  if (penaltyValueOnly_) return AddOpenTerms(s, *p, field, below);  // Y, Y_n, the normals, w
  const Eigen::Vector3d r = Mul(a_.R, ss.X);
  p->d = r + dA_;
  s.y = a_.p + r;
  // y⁰ in world coordinates, as the soft and kind samples form it: the stage start's R⁰ is an
  // affine combination of rotations, and Y⁰ = (R⁰_B)⁻¹(y⁰ − p⁰_B) is formed from it alike.
  if (B_.hasStart) s.y0 = start_ ? Eigen::Vector3d(start_->p + start_->R * ss.X) : s.y;
  s.n = Mul(a_.R, ss.normal);
  s.map.r = r;
  AddOpenTerms(s, *p, field, below);
}

void FrameEvaluation::Finish() { Close(); }

void EvaluateSamplesOnFrame(const std::vector<PairSample>& samples, const FrameSide& B,
                            const PenaltyParams& penalty, double maxAlignment,
                            const DissipationSetup* dissipation, int order, PairStencils* out,
                            std::vector<ContactSampleRecord>* records) {
  FrameEvaluation evaluation(B, penalty, maxAlignment, dissipation, order, out, records);
  for (const PairSample& s : samples) evaluation.Add(s);
  evaluation.Finish();
}

StepLimitSink::StepLimitSink(const FrameSide& B, const PenaltyParams& penalty)
    : B_(B),
      penalty_(penalty),
      RBt1_(B.pose.R.transpose()),
      RBt0_(B.last.R.transpose()),
      reach_(B.field->boundingRadius + penalty.delta - 0.5 * penalty.eps) {}

void StepLimitSink::Limit(const Eigen::Vector3d& Y1, const Eigen::Vector3d& Y0) {
  const RigidCollider& field = *B_.field;
  if (std::isfinite(reach_) && Y1.squaredNorm() >= reach_ * reach_) return;
  const double s1 = penalty_.delta - field.Value(Y1);
  if (s1 <= 0.5 * penalty_.eps) return;
  const double s0 = penalty_.delta - field.Value(Y0);
  const double cap = std::max(2.0 * s0, 0.5 * penalty_.eps);
  if (s1 > cap) alpha_ = std::min(alpha_, (cap - s0) / (s1 - s0));
}

void StepLimitSink::Add(const PairSample& s) {
  Limit(RBt1_ * (s.y - B_.pose.p), RBt0_ * (s.yLast - B_.last.p));
}

bool StepLimitSink::BeginRigidBody(const RigidPose&, const RigidPose& an,
                                   const RigidStageStart*, int, int, int, const RigidBodyModel& body,
                                   const BodyInFrame& inFrame) {
  A_ = inFrame;
  // The current configuration's transforms with B's transpose taken inside the products, as the
  // rigid pairs' limit always formed them: ComposeLastInFrame's stored transpose gives products that
  // differ in the last bit, and the recorded runs' limits (tests/regression) are these.
  A_.Rn = B_.last.R.transpose() * an.R;
  A_.tn = B_.last.R.transpose() * (an.p - B_.last.p);
  // |Y₁ − Y₀| <= |t₁ − t₀| + ‖R₁ − R₀‖ |X| for every sample, and |Δs| <= L |Y₁ − Y₀|.
  const double moved = (inFrame.tn - inFrame.t).norm() + inFrame.turn * body.samplesRadius;
  return B_.field->lipschitz * moved > 0.25 * penalty_.eps;
}

void StepLimitSink::AddRigidSamples(const SurfaceSample* samples, int begin, int end, int,
                                    double) {
  for (int k = begin; k < end; ++k) Limit(A_.t + A_.R * samples[k].X, A_.tn + A_.Rn * samples[k].X);
}

namespace {

// Appends the samples of rigid body A at pose a ([δp] at stage offset offP, [δθ] at offTheta; −1:
// none) that can contribute on B's field, their slip keys counted from keyOffset.
void AppendRigidSamples(const RigidBodyModel& A, const RigidPose& a, const RigidStageStart* start,
                        int offP, int offTheta, int keyOffset, const FrameSide& B, double delta,
                        const DissipationSetup* dissipation, SampleSink* sink) {
  const RigidPose& an = start ? start->last : a;
  // The tree is culled in B's frame as the sink pulls the samples back; the transforms at x_n are
  // formed where a test first reads them.
  BodyInFrame in;
  ComposeNowInFrame(a, B, &in);
  bool composedLast = false;
  auto composeLast = [&] {
    if (!composedLast) ComposeLastInFrame(an, B, &in);
    composedLast = true;
  };
  const BallCulling near(B, delta, dissipation, start != nullptr, &in.turn);
  auto keep = [&](const Eigen::Vector3d& c, double r) {
    return near.InFrame(in.t + in.R * c, [&] {
      composeLast();
      return Eigen::Vector3d(in.tn + in.Rn * c);
    }, r);
  };
  // The root first (ForEachSampleRange tests it again, alike): a body none of whose samples can
  // contribute (in flight) is done before the sink is told of it.
  if (A.sampleTree.empty() || !keep(A.sampleTree[0].center, A.sampleTree[0].radius)) return;
  composeLast();
  if (!sink->BeginRigidBody(a, an, start, offP, offTheta, keyOffset, A, in)) return;
  // A leaf's bound on |Y_n − Y| = |(t_n − t) + (R_n − R) X| over its ball |X − c| <= r:
  // |(t_n − t) + (R_n − R) c| + turn r, with the body bound's round-off margin.
  const Eigen::Vector3d dt = in.tn - in.t;
  const Eigen::Matrix3d dR = in.Rn - in.R;
  auto visit = [&](int begin, int end, const SampleNode& leaf) {
    const double motion =
        ((dt + dR * leaf.center).norm() + in.turn * leaf.radius) * (1.0 + 1e-12) + 1e-15;
    sink->AddRigidSamples(A.samples.data(), begin, end, keyOffset, motion);
  };
  ForEachSampleRange(A, keep, visit);
}

}  // namespace

bool SampleSink::BeginRigidBody(const RigidPose& a, const RigidPose& an,
                                const RigidStageStart* start, int offP, int offTheta, int,
                                const RigidBodyModel&, const BodyInFrame&) {
  a_ = a;
  an_ = an;
  start_ = start;
  rigid_.map.origin = a.p;  // the rest of the sample is each one's (FormRigidSample)
  rigid_.offs[0] = offP;
  rigid_.offs[1] = offTheta;
  return true;
}

const PairSample& SampleSink::FormRigidSample(const SurfaceSample& ss, int key) {
  PairSample& s = rigid_;
  const Eigen::Vector3d r = a_.R * ss.X;
  s.y = a_.p + r;
  s.yLast = an_.p + an_.R * ss.X;
  s.y0 = start_ ? Eigen::Vector3d(start_->p + start_->R * ss.X) : s.y;
  s.n = a_.R * ss.normal;
  s.nLast = an_.R * ss.normal;
  s.weight = ss.weight;
  s.map.r = r;
  s.key = key;
  return s;
}

void SampleSink::AddRigidSamples(const SurfaceSample* samples, int begin, int end,
                                 int keyOffset, double) {
  for (int q = begin; q < end; ++q) Add(FormRigidSample(samples[q], keyOffset + q));
}

void ComposeNowInFrame(const RigidPose& a, const FrameSide& B, BodyInFrame* f) {
  const Eigen::Matrix3d RBt = B.pose.R.transpose();
  f->R = RBt * a.R;
  f->t = RBt * (a.p - B.pose.p);
}

void ComposeLastInFrame(const RigidPose& an, const FrameSide& B, BodyInFrame* f) {
  const Eigen::Matrix3d RnBt = B.last.R.transpose();
  f->Rn = RnBt * an.R;
  f->tn = RnBt * (an.p - B.last.p);
  f->turn = (f->Rn - f->R).norm();
}

void SampleBodyPoses::Form(const ActorKind& A, const Eigen::VectorXd& q,
                           const Eigen::VectorXd* qLast, const Eigen::VectorXd* q0) {
  const int n = A.NumSampleBodies();
  pose.resize(n);
  start.resize(n);
  hasStart = false;
  for (int b = 0; b < n; ++b) hasStart = SampleBodyAt(A, b, q, qLast, q0, &pose[b], &start[b]);
}

void GatherKindSamples(const ActorKind& A, const Eigen::VectorXd& q, const Eigen::VectorXd* qLast,
                       const Eigen::VectorXd* q0, const std::vector<int>& stageDof,
                       const FrameSide& B, double delta, const DissipationSetup* dissipation,
                       SampleSink* sink, const SampleBodyPoses* bodies) {
  if (A.NumSampleBodies() > 0) {  // rigid bodies' samples: the rigid gather per body
    int keyOffset = 0;
    for (int b = 0; b < A.NumSampleBodies(); ++b) {
      const RigidBodyModel& body = *A.SampleBody(b);
      int dof[2];
      A.SampleBodyDofs(b, dof);
      RigidPose pose;
      RigidStageStart start;
      const bool hasStart = bodies ? bodies->hasStart : SampleBodyAt(A, b, q, qLast, q0, &pose, &start);
      const RigidPose& p = bodies ? bodies->pose[b] : pose;
      const RigidStageStart& s = bodies ? bodies->start[b] : start;
      AppendRigidSamples(body, p, hasStart ? &s : nullptr, stageDof[dof[0]], stageDof[dof[1]],
                         keyOffset, B, delta, dissipation, sink);
      keyOffset += static_cast<int>(body.samples.size()) + kSphereCapMaxSamples;
    }
    return;
  }
  // A kind's ball may turn by anything between x_n and now: |ΔY| of a sample within 2 r of its
  // centre's.
  const double spread = 2.0;
  const BallCulling near(B, delta, dissipation, q0 != nullptr, &spread);
  A.ForEachSampleNear(q, qLast ? *qLast : q, near, [&](int begin, int end) {
    GatherKindSampleRange(A, q, qLast, q0, stageDof, begin, end, sink);
  });
}

bool SampleBodyAt(const ActorKind& A, int b, const Eigen::VectorXd& q,
                  const Eigen::VectorXd* qLast, const Eigen::VectorXd* q0, RigidPose* pose,
                  RigidStageStart* start) {
  *pose = A.SampleBodyPose(b, q);
  start->last = qLast ? A.SampleBodyPose(b, *qLast) : *pose;
  const RigidPose p0 = q0 ? A.SampleBodyPose(b, *q0) : *pose;  // without x⁰: y⁰ = y
  start->p = p0.p;  // a colliding body's y⁰ = p⁰ + R⁰ X needs no inverse
  start->R = p0.R;
  return qLast || q0;
}


void GatherKindSampleRange(const ActorKind& A, const Eigen::VectorXd& q,
                           const Eigen::VectorXd* qLast, const Eigen::VectorXd* q0,
                           const std::vector<int>& stageDof, int begin, int end,
                           SampleSink* sink) {
  PairSample s;
  for (int k = begin; k < end; ++k) {
    const KindSample ks = A.Sample(k, q);
    s.y = ks.y;
    s.hasNormal = ks.hasNormal;
    s.n = ks.n;
    s.nLast = ks.n;
    if (qLast) {
      const KindSample last = A.Sample(k, *qLast);
      s.yLast = last.y;
      s.nLast = last.n;
    } else {
      s.yLast = ks.y;
    }
    s.y0 = q0 ? A.Sample(k, *q0).y : ks.y;
    s.faceNormal = ks.faceNormal;
    s.face = ks.face;
    if (ks.faceNormal)
      for (int c = 0; c < 3; ++c) s.faceNodes[c] = ks.faceNodes[c];
    s.weight = ks.weight;
    s.map = ks.map;
    s.key = k;
    s.blocks = ks.Blocks();
    for (int b = 0; b < s.blocks; ++b) s.offs[b] = stageDof[ks.dof[b]];
    sink->Add(s);
  }
}

FrameSide KindFrameSide(const ActorKind& B, const Eigen::VectorXd& q, const Eigen::VectorXd* qLast,
                        const Eigen::VectorXd* q0, const std::vector<int>& stageDof) {
  FrameSide side;
  FormKindFrameSide(B, q, qLast, q0, stageDof, &side);
  return side;
}

void FormKindFrameSide(const ActorKind& B, const Eigen::VectorXd& q, const Eigen::VectorXd* qLast,
                       const Eigen::VectorXd* q0, const std::vector<int>& stageDof,
                       FrameSide* side) {
  const KindFrame f = B.ColliderFrame(q);
  side->field = B.Collider();
  side->tet = nullptr;
  side->pose = f.pose;
  side->last = qLast ? B.ColliderFrame(*qLast).pose : f.pose;
  side->hasLast = qLast != nullptr;
  side->hasStart = q0 != nullptr;
  if (q0) {
    const RigidPose p0 = B.ColliderFrame(*q0).pose;
    side->start.p = p0.p;
    side->start.R = p0.R;
    side->start.Rinv = p0.R.inverse();  // R⁰ an affine combination, not always a rotation
    side->start.last = side->last;
  }
  side->blocks = 0;
  std::fill(side->offs, side->offs + 4, -1);  // the side is kept from evaluation to evaluation
  if (f.rigid) {
    side->motion = FrameSide::Motion::Rigid;
    side->offs[0] = stageDof[f.dof[0]];
    side->offs[1] = stageDof[f.dof[1]];
    if (side->offs[0] < 0) side->motion = FrameSide::Motion::Static;  // a prescribed pose
    return;
  }
  side->motion = f.blocks > 0 ? FrameSide::Motion::Translation : FrameSide::Motion::Static;
  side->blocks = f.blocks;
  side->Fp.leftCols(3 * f.blocks) = f.F.topRows<3>();
  for (int b = 0; b < f.blocks; ++b) side->offs[b] = stageDof[f.dof[b]];
}

}  // namespace superdex
