// The contact assembler of the generic actor layer: colliding samples of any actor (a kind's
// samples, or a rigid body's) on a collider field carried by a frame (a rigid body's pose, or a
// kind's collider frame, core/model/actor_kind.h) or by a kind's tets (core/contact/tet_field.h:
// the pullback Y is the located tet's, and its stencil side the tet's four nodes).
//
// Per sample, with the pullback Y = R_Bᵀ(y − p_B) [m] into the frame:
//   penalty      w W(Φ_B(Y))                                              [J]
//   dissipation  Δt_i w R(V_rel),  V_rel = (Y − Y⁰)/Δt_i,  Y⁰ = (R⁰_B)⁻¹(y⁰ − p⁰_B)  [J]
// chained once into the pair stencil [q_A, q_B] (core/contact/sample_chain.h): the frame's side by
// RigidPullbackStencil (then, for a kind's frame, through its Jacobian F), the colliding side by
// the sample's SamplePointMap, times the weight w [m²] applied once. In the current-geometry
// dissipation modes the residual w Jᵀ ∂R/∂V is not a gradient; its Jacobian (with the dependence
// of the load, the split direction and the colliding normal on the dofs, in the stage's world-
// torque convention for rigid rotations) is differentiated by forward-mode automatic
// differentiation of the same residual (kind_contact.cpp). Samples without a colliding normal
// (a kind's, as a shell's or a particle's) have no alignment rejection and no fading, and split
// friction on the collider's normal (spec: "Normal/Tangential Split").
//
// Alignment rejection (spec: "Normal/Tangential Split"): a sample whose alignment
// s = G_B·N_A (N_A the colliding normal in B's coordinates, raw vectors) exceeds the collider's m
// is rejected entirely; +∞ disables the test. The test is evaluated at the last actual
// configuration x_n (when the frame has a stage start), so that within one stage the set of
// rejected samples is fixed and the stage energy stays smooth: evaluated at the current iterate,
// the samples of a face perpendicular to the collider (s = 0 = m by default, e.g. the side faces
// of a box pressed into a plane deeper than their first sample row) would be rejected and
// accepted at random from one Newton iterate to the next, and the stage would not converge.
#pragma once

#include <vector>

#include "core/contact/contact_stencil.h"
#include "core/contact/dissipation_setup.h"
#include "core/contact/rigid_contact.h"
#include "core/contact/rigid_dissipation.h"
#include "core/contact/sphere_cap.h"
#include "core/contact/tet_field.h"
#include "core/model/actor_kind.h"
#include "core/model/rigid_body.h"

namespace superdex {

/// One colliding sample of a pair, world frame, with its stencil blocks (3-dof blocks at stage
/// offsets; −1 for a block without unknowns).
struct PairSample {
  Eigen::Vector3d y = Eigen::Vector3d::Zero();      ///< current point [m]
  Eigen::Vector3d yLast = Eigen::Vector3d::Zero();  ///< at the last actual configuration x_n
  Eigen::Vector3d y0 = Eigen::Vector3d::Zero();     ///< at the stage start x⁰ (dissipation)
  bool hasNormal = false;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();      ///< unit colliding normal at y (world)
  Eigen::Vector3d nLast = Eigen::Vector3d::Zero();  ///< at x_n
  /// The normal is that of the triangle of the map's three nodes, at these current positions
  /// (a soft face's sample): it moves with the nodes. Otherwise a rigid map's normal turns with
  /// the body, and a Nodes map has none.
  bool faceNormal = false;
  Eigen::Vector3d faceNodes[3];
  int key = 0;    ///< the sample's index in its actor (the slip tape's key)
  int face = -1;  ///< a soft actor's boundary face (records)
  double weight = 0.0;                              ///< w [m²]
  SamplePointMap map;
  int blocks = 0;
  int offs[4] = {-1, -1, -1, -1};
};

/// The collider side: a field in a frame at the current pose, at x_n and at the stage start; or a
/// kind's tet field (Motion::Tet, core/contact/tet_field.h), whose pullback is the located tet's
/// and whose frame is the world's.
struct FrameSide {
  enum class Motion { Static, Rigid, Translation, Tet };
  const RigidCollider* field = nullptr;
  RigidPose pose;                          ///< current
  RigidPose last;                          ///< x_n (the geometry reference)
  RigidStageStart start;                   ///< x⁰ (dissipation; valid when hasStart)
  bool hasStart = false;
  /// x_n given (`last` is the step start's pose, not a copy of the current one): the penalty's
  /// alignment test reads the normals at x_n then, so that a stage's contact set does not change
  /// with the iterate (a face perpendicular to the collider flips s's sign at round-off).
  bool hasLast = false;
  /// Static: no dofs. Rigid: [δp_B, δθ_B] at offs[0], offs[1]. Translation: δp_B = F_p δq_B over
  /// `blocks` 3-dof blocks. Tet: the four nodes of a sample's tet (`field` the reference grid,
  /// `tet` the field; the poses the identity, hasLast set).
  Motion motion = Motion::Static;
  Eigen::Matrix<double, 3, kMaxFrameDofs> Fp;  ///< Translation: its first 3·blocks columns
  int blocks = 0;
  int offs[4] = {-1, -1, -1, -1};
  const TetFieldSide* tet = nullptr;
  int Dofs() const {
    switch (motion) {
      case Motion::Static: return 0;
      case Motion::Rigid: return 6;
      case Motion::Tet: return 12;
      default: return 3 * blocks;
    }
  }
};

/// Rigid body A's composed transforms into frame B's coordinates: a sample's Y = R X + t now and
/// Y_n = Rn X + tn at x_n, and turn = ‖Rn − R‖_F, so that |Y_n − Y| <= |tn − t| + turn |X|.
struct BodyInFrame {
  Eigen::Matrix3d R, Rn;
  Eigen::Vector3d t, tn;
  double turn = 0.0;
};
/// A at pose a now in B's frame (B.pose): R and t; and at x_n (an, B.last): Rn, tn and then turn
/// (after the part now).
void ComposeNowInFrame(const RigidPose& a, const FrameSide& B, BodyInFrame* f);
void ComposeLastInFrame(const RigidPose& an, const FrameSide& B, BodyInFrame* f);

/// Receives a gather's samples one at a time (a sample is valid only during the call).
class SampleSink {
 public:
  virtual void Add(const PairSample& s) = 0;
  /// A rigid body's samples, announced by body (pose a now, an at x_n, the stage start `start`
  /// or null; [δp] at stage dof offP, [δθ] at offTheta, −1: none; its slip keys from keyOffset:
  /// its samples' and then kSphereCapMaxSamples more for a sink's own samples of the body
  /// (core/contact/sphere_cap.h); `body` its model, whose
  /// samplesRadius bounds every sample's |X| [m]; `inFrame`: a and an composed into the
  /// collider's frame, ComposeNowInFrame and
  /// ComposeLastInFrame), then a leaf of its sample tree at a time in the body frame; a body whose
  /// tree's root is culled is not announced. Returns whether the sink takes the body's samples
  /// (false: the gather skips them; a sink that can tell from the body's motion alone that none
  /// of them matters).
  virtual bool BeginRigidBody(const RigidPose& a, const RigidPose& an,
                              const RigidStageStart* start, int offP, int offTheta, int keyOffset,
                              const RigidBodyModel& body, const BodyInFrame& inFrame);
  /// The samples begin .. end−1 of a body's array, keys from keyOffset + begin; `motion` [m]
  /// bounds their |Y_n − Y| in the collider's frame (a leaf's bound, or infinity). The default
  /// forms each as a PairSample (a Rigid map, its normal turning with the body) and passes it to
  /// Add; a sink may form only what it needs.
  virtual void AddRigidSamples(const SurfaceSample* samples, int begin, int end, int keyOffset,
                               double motion);

 protected:
  SampleSink() {
    rigid_.hasNormal = true;
    rigid_.map = SamplePointMap::Rigid(Eigen::Vector3d::Zero());
    rigid_.blocks = 2;
  }
  ~SampleSink() = default;
  /// The body's sample at `ss` as a PairSample, in rigid_ (its per-body fields set by
  /// BeginRigidBody).
  const PairSample& FormRigidSample(const SurfaceSample& ss, int key);
  PairSample rigid_;
  RigidPose a_, an_;
  const RigidStageStart* start_ = nullptr;
};

/// A sink that appends the samples to a list.
class SampleList final : public SampleSink {
 public:
  explicit SampleList(std::vector<PairSample>* list) : list_(list) {}
  void Add(const PairSample& s) override { list_->push_back(s); }

 private:
  std::vector<PairSample>* list_;
};

/// The regrouped chain of one rigid body's samples on a rigid or static frame (one stencil
/// [δp_A, δθ_A (, δp_B, δθ_B)]): gradients and residuals per sample by AddFunctionOfPullback into
/// fixed-size vectors, second derivatives as moments in B's frame, mapped at Flush.
struct RigidSampleSums {
  bool on = false;
  bool bDynamic = false;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();  ///< p_A − p_B [m]
  Eigen::Vector3d rB;                            ///< the sample's arm R_Bᵀ r_A [m]
  PairVector penaltyGradient, dissipationResidual;
  PairHessianSums penalty, potentialDissipation;
  PairForceJacobianSums force{true};

  /// Starts a stencil: on when its samples are a Rigid map's and B does not deform.
  void Begin(const PairSample& s, const FrameSide& B) {
    on = s.map.kind == SamplePointMap::Kind::Rigid && s.hasNormal &&
         (B.motion == FrameSide::Motion::Static || B.motion == FrameSide::Motion::Rigid);
    if (!on) return;
    bDynamic = B.motion == FrameSide::Motion::Rigid;
    c = s.map.origin - B.pose.p;
    penaltyGradient.setZero();
    dissipationResidual.setZero();
    penalty.Clear();
    potentialDissipation.Clear();
    force.Clear(bDynamic);
  }
  /// Writes the sums into the stencil (its parts zero on n dofs).
  void Flush(const FrameSide& B, int order, ContactStencil* st) const {
    if (!on || order < 1) return;
    const int n = bDynamic ? 12 : 6;
    if (st->penaltyActive) st->penaltyGradient = penaltyGradient.head(n);
    if (st->dissipationActive) st->dissipationResidual = dissipationResidual.head(n);
    if (order < 2) return;
    PairMatrix M;
    if (st->penaltyActive) {
      M.setZero();
      penalty.AddTo(B.pose.R, c, bDynamic, &M);
      st->penaltyHessian = M.topLeftCorner(n, n);
    }
    if (st->dissipationActive) {
      M.setZero();
      potentialDissipation.AddTo(B.pose.R, c, bDynamic, &M);
      force.AddTo(B.pose.R, c, &M);
      st->dissipationJacobian = M.topLeftCorner(n, n);
    }
  }
};

/// A sample's pullbacks into B's frame: d = y − p_B (world) [m], Y now and Y_n at x_n [m], and
/// the colliding normal N_A in B's coordinates at both (zero without one). On a tet field: `tet`
/// the pullback Y is taken through (its map to the stencil), Y⁰ at the stage start through the
/// same tet, and `hasLast` whether that tet has a pullback at x_n (else no alignment rejection).
struct SamplePullback {
  Eigen::Vector3d d, Y, Yn, NA, NAn;
  const TetPullback* tet = nullptr;
  Eigen::Vector3d Y0;
  bool hasLast = true;
};

/// EvaluateSamplesOnFrame one sample at a time, as a sink: a gather feeds it directly, so that a
/// pair's samples are evaluated where they are formed and never stored (a sampled sphere of a
/// pile keeps hundreds per pair). B must outlive it; Finish closes the last stencil.
class FrameEvaluation final : public SampleSink {
 public:
  /// `append`: keep what *out holds (its stencils and counts) and add after it (the point-cloud
  /// pairs evaluate one sphere after another into one list); else *out starts empty.
  FrameEvaluation(const FrameSide& B, const PenaltyParams& penalty, double maxAlignment,
                  const DissipationSetup* dissipation, int order, PairStencils* out,
                  std::vector<ContactSampleRecord>* records = nullptr, bool append = false);
  void Add(const PairSample& s) override;
  /// A rigid body's samples: each one's pullback Y, and Y_n where the bound needs it, first; the
  /// rest only when the field says it can contribute (most samples a pile's culling keeps do not).
  /// A sphere with SurfaceIntegral::ExactSphere on a plane's, a box face's or a sphere's field
  /// has its penalty integrated exactly here (AddExactSpherePenalty), and its dissipation on its
  /// cap's quadrature where the mode allows (AddCapDissipation); else its samples carry the
  /// dissipation and the records.
  bool BeginRigidBody(const RigidPose& a, const RigidPose& an, const RigidStageStart* start,
                      int offP, int offTheta, int keyOffset, const RigidBodyModel& body,
                      const BodyInFrame& inFrame) override;
  void AddRigidSamples(const SurfaceSample* samples, int begin, int end, int keyOffset,
                       double motion) override;
  void Finish();

 private:
  void Close();
  // (radius + bound)² for B's bounding radius: beyond it the field is at least `bound` (no field
  // evaluation needed to say so).
  double ReachSquared(double bound) const;
  // Whether Y lies within the reach of squared radius reach2 (always, for an unbounded field).
  bool WithinReach(const Eigen::Vector3d& Y, double reach2) const;
  // Whether a sample with pullbacks p may contribute: its field at Y below `bound` (reach2 =
  // ReachSquared(bound); *field, value and gradient, and *below, evaluated only within reach), or
  // explicit normals' load at a Y_n within δ's reach. CompleteCandidate adds the Hessian.
  bool Candidate(const SamplePullback& p, double bound, double reach2, SdfSample* field,
                 bool* below);
  // The field's Hessian at Y for a candidate below the bound, where the order reads it (2).
  void CompleteCandidate(const Eigen::Vector3d& Y, bool below, SdfSample* field) const;
  // Whether a sample with φ >= δ carries no reconstructed load either: φ + G·(Y_n − Y) >= δ
  // (between δ and the bound, the load decides; AddPenalty, AddDissipation).
  bool LoadFree(const SamplePullback& p, const SdfSample& field) const;
  // Opens the stencil of sample s (on a tet field: with tet t's nodes) when it does not share
  // the open one's blocks.
  void Open(const PairSample& s, int t = -1);
  // A sample on a tet field: its penalty and current-mode dissipation through the tet that
  // contains it, its explicit normals' dissipation through the tet that contained it at x_n.
  void AddOnTet(const PairSample& s);
  // The explicit normals' dissipation of sample s on a tet field (AddOnTet).
  void AddOnTetAtLast(const PairSample& s, ContactSampleRecord* record);
  // A sample's report (rec_), when records_ asks for one: started empty (null without
  // records_), then appended with the sample's place, φ and weight if its penalty is active or
  // its dissipation exerts a traction.
  ContactSampleRecord* BeginRecord();
  void EndRecord(const PairSample& s, double phi, bool penalty);
  // The terms of a candidate sample s with pullback p at field value `field` (`below`: within
  // the bound; else the field is not read).
  void AddTerms(const PairSample& s, const SamplePullback& p, const SdfSample& field, bool below);
  // AddTerms into the open stencil.
  void AddOpenTerms(const PairSample& s, const SamplePullback& p, const SdfSample& field,
                    bool below);
  // The exact penalty of sphere `body` (SurfaceIntegral::ExactSphere) on B's field where it is a
  // plane's, a box face's or a sphere's about the body (AxialFieldAt), into the body's stencil;
  // whether it is (else the samples carry it).
  bool AddExactSpherePenalty(const RigidBodyModel& body);
  // The dissipation of sphere `body` with an exact penalty on the cap's quadrature at x_n
  // (core/contact/sphere_cap.h), where the mode's load vanishes outside that cap (explicit
  // normals; the reconstructed load on a plane), its slip keys after the body's samples'
  // (keyOffset their first); whether it applies (else the body's samples carry it).
  bool AddCapDissipation(const RigidBodyModel& body, int keyOffset);
  // The penalty's record: the active cap at its deepest point (a: B's field about the body; w,
  // its axis in world coordinates; dE = E'(x)).
  ContactSampleRecord ExactSphereRecord(const RigidBodyModel& body, const AxialField& a,
                                        const Eigen::Vector3d& w, double phiDeepest,
                                        double dE) const;
  // A rigid body's candidate sample ss (its pullback p with Y, and Y_n when hasYn) formed and
  // its terms added.
  void AddRigidCandidate(const SurfaceSample& ss, int key, bool hasYn, SamplePullback* p,
                         const SdfSample& field, bool below);
  // The rigid body in B's frame (its samples' Y and Y_n); y − p_B = R_A X + dA_ (world).
  BodyInFrame A_;
  Eigen::Vector3d dA_;
  double motion_ = 0.0;  // a bound on |Y_n − Y| over the body's samples [m]
  const FrameSide& B_;
  PenaltyParams penalty_;
  double maxAlignment_;
  const DissipationSetup* dissipation_;
  DissipationSetup noNormal_;
  int order_;
  PairStencils* out_;
  std::vector<ContactSampleRecord>* records_;
  bool withDissipation_ = false, explicitNormals_ = false, reconstructed_ = false;
  bool finiteReach_ = true;  // B's field has a finite bounding radius (not a plane)
  double reachLast2_ = 0.0;  // ReachSquared(δ): explicit normals' reach at Y_n
  bool penaltyValueOnly_ = false;  // order 0 without dissipation or records
  ContactStencil* st_ = nullptr;
  int openTet_ = -1;        // the open stencil's tet on a tet field
  bool rigidOpen_ = false;  // the rigid body's stencil is open (its samples share their blocks)
  bool exactPenalty_ = false;  // the open rigid body's penalty is integrated exactly
  RigidSampleSums sums_;
  ContactSampleRecord rec_;  // the sample's report under way (with records_)
};

/// Evaluates every sample on the frame's field into stencils: consecutive samples with the same
/// blocks share one (a rigid body's samples, a soft face's). order 0: value;
/// 1: gradient and residual; 2: Hessian and Jacobian (unprojected). The samples of a Rigid map on
/// a rigid or static frame (one rigid body on another's field) are chained to the stencil as
/// regrouped moments (PairHessianSums, PairForceJacobianSums of core/contact/rigid_contact.h and
/// rigid_dissipation.h): per sample a few 3 × 3 products instead of a 12 × 12 stencil, mapped once
/// per stencil, and the current modes' Jacobian from the closed-form linearization of the kernel
/// instead of automatic differentiation; the same derivatives up to rounding. `dissipation` null: penalty
/// only. `records` (order 0 only) collects the active penalty samples.
void EvaluateSamplesOnFrame(const std::vector<PairSample>& samples, const FrameSide& B,
                            const PenaltyParams& penalty, double maxAlignment,
                            const DissipationSetup* dissipation, int order, PairStencils* out,
                            std::vector<ContactSampleRecord>* records = nullptr);

/// Whether a ball of colliding samples (radius r [m], centred at c now and at cLast at x_n, world)
/// may hold a sample that contributes on B's field: its penalty now, or with dissipation the load
/// geometry of the mode. B's field has Lipschitz constant L, so every sample of the ball has
/// φ >= φ(centre) − L r. Explicit normals read the load at x_n; so does the reconstructed load on
/// an affine field (a plane), where φ + G·(Y_n − Y) is Φ(Y_n) exactly; otherwise the reconstructed
/// load is bounded below over the ball by the field (RigidCollider::FirstOrderLowerBound, with the
/// centre's Y_n − Y), and a sample's Y_n − Y differs from its ball centre's by at most *spread r
/// (a rigid body: ‖R_n,BᵀR_n,A − R_BᵀR_A‖_F; read only after the centre at x_n is asked for, so
/// that it may be formed with it).
class BallCulling {
 public:
  BallCulling(const FrameSide& B, double delta, const DissipationSetup* dissipation,
              bool hasStart, const double* spread)
      : field_(*B.field),
        B_(B),
        RBt_(B.pose.R.transpose()),
        RnBt_(B.last.R.transpose()),
        delta_(delta),
        spread_(spread) {
    const bool diss = dissipation && dissipation->coefficients.Any() && hasStart && B.hasStart;
    mode_ = diss ? dissipation->mode : DissipationMode::ImplicitLoad;
    loadAtLast_ = mode_ == DissipationMode::ExplicitNormals ||
                  (mode_ == DissipationMode::ReconstructedLoad && field_.type == ColliderType::Plane);
  }
  bool operator()(const Eigen::Vector3d& c, const Eigen::Vector3d& cLast, double r) const {
    return InFrame(RBt_ * (c - B_.pose.p), [&] { return RnBt_ * (cLast - B_.last.p); }, r);
  }
  /// The same test on the centre in B's frame: Y now, and lastY() at x_n (formed only where the
  /// load geometry needs it). On a tet field (the world's frame): the ball touches the field's box
  /// now, or with explicit normals at x_n (samples outside both meet no tet).
  template <typename LastCentre>
  bool InFrame(const Eigen::Vector3d& Y, LastCentre&& lastY, double r) const {
    if (B_.tet)
      return B_.tet->box.TouchesBall(Y, r) ||
             (mode_ == DissipationMode::ExplicitNormals && B_.tet->boxLast.TouchesBall(lastY(), r));
    const double L = field_.lipschitz;
    const double phiNow = field_.Value(Y) - L * r;
    if (phiNow < delta_) return true;
    if (mode_ == DissipationMode::ImplicitLoad) return false;
    const Eigen::Vector3d Yn = lastY();
    if (loadAtLast_) return field_.Value(Yn) - L * r < delta_;
    return field_.FirstOrderLowerBound(Y, r, Yn - Y) - L * *spread_ * r < delta_;
  }

 private:
  const RigidCollider& field_;
  const FrameSide& B_;
  Eigen::Matrix3d RBt_, RnBt_;
  double delta_;
  const double* spread_;
  DissipationMode mode_;
  bool loadAtLast_ = false;
};

/// Step limit of Newton's global phase (SceneStageProblem::LimitStep) on a frame's field, for
/// every pair on one: the largest fraction α ∈ (0, 1] of a move, interpolated linearly per sample,
/// that keeps every sample's penetration depth s = δ − φ (the ramp's argument, spec: "Normal
/// penalty") within
///     s₁ <= max(2 s₀, ε/2)                                                          [m]
/// (s₁ at the trial configuration, s₀ at the current one). The contact force of a sample grows
/// like s⁵ on the ramp (h h' ≈ 3 s⁵/(16 ε⁴) for s ≪ ε), so a Newton step taken from where a sample
/// barely touches predicts its load from a stiffness that is orders of magnitude too small and
/// overshoots deep into the collider; Newton then returns only at the rate 4/5 per iteration.
/// Letting the depth at most double per iteration reaches the equilibrium depth in log₂ steps
/// instead. Samples whose alignment is rejected are not excluded (the limit is only more
/// cautious).
///
/// A sink for a gather at the trial configuration with the current one as its x_n: the samples'
/// y at the trial and yLast now, B.pose the frame's trial pose and B.last its current one; gather
/// to the bound δ − ε/2 (samples with φ₁ >= δ − ε/2 have s₁ <= ε/2 and cannot break the limit). A
/// sample cannot break it either unless its depth grows by more than ε/4 (cap − s₀ =
/// max(s₀, ε/2 − s₀) for s₀ >= 0, > ε/2 for s₀ < 0): a rigid body whose samples all move by at
/// most ε/(4L) relative to B is skipped whole.
class StepLimitSink final : public SampleSink {
 public:
  StepLimitSink(const FrameSide& B, const PenaltyParams& penalty);
  void Add(const PairSample& s) override;
  bool BeginRigidBody(const RigidPose& a, const RigidPose& an, const RigidStageStart* start,
                      int offP, int offTheta, int keyOffset, const RigidBodyModel& body,
                      const BodyInFrame& inFrame) override;
  void AddRigidSamples(const SurfaceSample* samples, int begin, int end, int keyOffset,
                       double motion) override;
  /// α of the samples so far (1 without any).
  double Alpha() const { return alpha_; }

 private:
  // The rule for one sample at Y1 (trial) and Y0 (current), in B's frame.
  void Limit(const Eigen::Vector3d& Y1, const Eigen::Vector3d& Y0);
  const FrameSide& B_;
  PenaltyParams penalty_;
  Eigen::Matrix3d RBt1_, RBt0_;
  double reach_ = 0.0;
  double alpha_ = 1.0;
  BodyInFrame A_;
};

/// A kind's sample bodies at one configuration (SampleBodyAt for each), formed once for all the
/// pairs it takes part in.
struct SampleBodyPoses {
  std::vector<RigidPose> pose;
  std::vector<RigidStageStart> start;
  bool hasStart = false;
  /// Forms them for A at q, x_n (qLast) and x⁰ (q0), as SampleBodyAt does (no allocation once
  /// sized for A's bodies).
  void Form(const ActorKind& A, const Eigen::VectorXd& q, const Eigen::VectorXd* qLast,
            const Eigen::VectorXd* q0);
};

/// The samples of a kind's actor at q (x_n: qLast, x⁰: q0, either may be null), with the stage
/// offsets of its local dofs (`stageDof`, −1 for prescribed ones), that can contribute on B's
/// field: a sample body's tree (a rigid body's) culled by B's Lipschitz bound at the current pose
/// and, with dissipation, at x_n (the modes' load geometry); the kind's own samples by their
/// bounding balls (ActorKind::ForEachSampleNear) the same way. `bodies` (may be null): A's sample bodies formed at the same
/// configurations (SampleBodyPoses::Form), read instead of forming them again.
void GatherKindSamples(const ActorKind& A, const Eigen::VectorXd& q, const Eigen::VectorXd* qLast,
                       const Eigen::VectorXd* q0, const std::vector<int>& stageDof,
                       const FrameSide& B, double delta, const DissipationSetup* dissipation,
                       SampleSink* sink, const SampleBodyPoses* bodies = nullptr);
/// Sample body b of kind A at q: its pose, and as its stage start its pose at x_n (qLast) and at
/// x⁰ (q0) (each the pose at q where null; R⁰ an affine combination of rotations, its inverse not
/// formed: a colliding body's y⁰ = p⁰ + R⁰ X needs none). Returns whether it has a start (qLast
/// or q0 given).
bool SampleBodyAt(const ActorKind& A, int b, const Eigen::VectorXd& q,
                  const Eigen::VectorXd* qLast, const Eigen::VectorXd* q0, RigidPose* pose,
                  RigidStageStart* start);
/// The kind's samples begin .. end−1 (no culling).
void GatherKindSampleRange(const ActorKind& A, const Eigen::VectorXd& q,
                           const Eigen::VectorXd* qLast, const Eigen::VectorXd* q0,
                           const std::vector<int>& stageDof, int begin, int end,
                           SampleSink* sink);

/// A kind's collider frame as a FrameSide (its F moves the frame by translation only), at q, x_n
/// (qLast; null: q) and x⁰ (q0; null: no stage start).
FrameSide KindFrameSide(const ActorKind& B, const Eigen::VectorXd& q, const Eigen::VectorXd* qLast,
                        const Eigen::VectorXd* q0, const std::vector<int>& stageDof);
/// KindFrameSide into *side (kept from evaluation to evaluation: no copy of the side).
void FormKindFrameSide(const ActorKind& B, const Eigen::VectorXd& q, const Eigen::VectorXd* qLast,
                       const Eigen::VectorXd* q0, const std::vector<int>& stageDof,
                       FrameSide* side);

}  // namespace superdex
