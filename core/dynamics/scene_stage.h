// One implicit stage over the scene's rigid and soft actors and the generic layer's kinds, as a
// StageProblem for the optim/ solvers:
//   Φ_i(q) = 1/(2Δt_i²) Σ_b E_inertia,b(q)  +  Σ_b U_gravity,b(q)  +  Σ_s Φ_soft,s(q)
//            + Π_contact(q) + Δt_i Σ w R(V_rel,i)  −  Σ_b F_b(t_i)·p_b                 [J]
// (Φ_soft: core/model/soft_terms.h). Dofs: 6 per dynamic rigid body [δp, δθ], then 3 per free soft node.
// The dissipation term is an exact potential only with ExplicitNormals; in the other dissipation
// modes the stage is the residual r = ∇(Φ without R) + Σ w J_Yᵀ ∂R/∂V
// (core/contact/rigid_dissipation.h). An applied torque τ_b(t_i) adds −τ_b to the residual's
// rotation entries: a constant world torque is not the gradient of any function of the rotation,
// so a stage with one is not a potential either (IsPotential); its minimizing solves see the
// torque's work along the iterates they commit (see SceneStageProblem::Commit). A kind's
// generalized load (ActorKind::StageLoad) is treated the same way.
#pragma once

#include <memory>
#include <vector>

#include "core/contact/contact_pipeline.h"
#include "core/model/actor_kind.h"
#include "core/model/soft_terms.h"
#include "core/model/rigid_body.h"
#include "optim/stage_problem.h"
#include "optim/triplet_assembly.h"

namespace superdex {

/// The integrator's data for one stage: step Δt_i [s] and inertial targets x̂ in material-point
/// form (p̂ [m], R̂ — an affine combination of rotations, not necessarily a rotation).
struct StageTargets {
  double dt = 0.0;
  std::vector<Eigen::Vector3d> pHat;
  std::vector<Eigen::Matrix3d> RHat;
  std::vector<RigidStageStart> start;  ///< x⁰ and x_n per body (dissipation, alignment test);
                                       ///< may be empty without dissipation
  /// Applied loads per body at the stage's time, world frame: force at the centre of mass [N]
  /// and torque [N·m]; each empty when no body has one.
  std::vector<Eigen::Vector3d> force, torque;
};

/// Dissipation settings of a stage; `enabled` false gives the conservative stage.
struct StageDissipation {
  bool enabled = false;
  DissipationMode mode = DissipationMode::ReconstructedLoad;
  bool fadeFriction = true;
  StageSlips* slips = nullptr;  ///< DissipationContext::slips (sensitivities)
  bool recordSlips = false;
};

/// The generic layer's actors of a stage (core/model/actor_kind.h): the kinds, and per actor the
/// stage offsets of its local dofs (−1 for a prescribed dof), its stage data and copies of its x⁰
/// and x_n (contact view).
struct KindStage {
  const std::vector<const ActorKind*>* kinds = nullptr;
  std::vector<std::vector<int>> stageDof;
  std::vector<KindStageData> data;
  std::vector<Eigen::VectorXd> q0, qLast;
  size_t Size() const { return data.size(); }
};

/// The vector-state actors of a stage: the soft actors (models, their first dof, and per actor the
/// stage data), then the generic layer's actors. The stage's vector iterate (softX) holds the soft
/// actors' positions, then the kinds' configurations.
struct SoftStage {
  const std::vector<SoftBodyModel>* models = nullptr;
  std::vector<int> dofOffset;
  std::vector<SoftStageTarget> targets;
  std::vector<Eigen::VectorXd> x0, xLast;  ///< copies of the targets' x⁰ and x_n (contact view)
  KindStage kinds;
  bool Empty() const { return targets.empty() && kinds.Size() == 0; }
};

/// The kinds' part of a contact evaluation at the vector iterate x (soft actors' positions, then
/// the kinds' configurations); empty (q null) without kinds.
KindView KindViewOf(const SoftStage& soft, const std::vector<Eigen::VectorXd>& x);

/// The pipeline's dissipation data for a stage of step dt [s] (ContactPipeline::Evaluate).
DissipationContext ContextOf(const StageDissipation& dissipation, double dt);

/// Buffers that one stage hands to the next (no allocation after the first stage of a scene).
/// Problems that share it must be used one after the other (a solve ends before the next
/// problem's begins), as the stage solves are.
struct StageWorkspace {
  std::vector<RigidPose> trial;            ///< the configuration s ⊕ d under evaluation
  std::vector<Eigen::VectorXd> softTrial;  ///< its soft positions
  std::vector<double> limits;              ///< LimitStep's fractions per body
  std::vector<double> kindLimits;          ///< and per kind of the generic layer
  std::vector<double> bodyValue;           ///< the last evaluation's inertia + gravity per body
  std::vector<double> kindValue;           ///< and each kind's stage energy
  std::vector<double> splitValue;          ///< LastSplit's per-body shares
  Eigen::VectorXd scratch;                 ///< the dissipative residual's part
  Eigen::VectorXd pendingStep;             ///< the step of the last EvaluateAtStep-like call
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<DenseBlock6> blocks;         ///< rigid pairs' 6 × 6 blocks (ContactPipeline)
  size_t blockPosition = 0;                ///< where in `triplets` the blocks stand
  std::vector<SoftTermScratch> soft;
  Eigen::VectorXd kindGradient;                    ///< a kind's local gradient
  Eigen::VectorXd kindDelta;                       ///< a kind's local step (or residual)
  std::vector<Eigen::Triplet<double>> kindHessian; ///< a kind's local Hessian entries
  TripletAssembly hessianAssembly;   ///< Evaluate's Hessians (pattern kept between iterations)
  TripletAssembly jacobianAssembly;  ///< EvaluateResidual's Jacobians
};


class SceneStageProblem : public StageProblem {
 public:
  /// `poses` is the iterate, updated in place by Commit; dynamic bodies own 6 dofs each
  /// [δp, δθ] at dofOffset[i] (−1 for static bodies). `soft` and `softX` (node positions, the
  /// soft part of the iterate; prescribed nodes already at their stage values) may be null.
  SceneStageProblem(const std::vector<RigidBodyModel>& models, const std::vector<int>& dofOffset,
                    int numDofs, const StageTargets& targets, const Eigen::Vector3d& gravity,
                    ContactPipeline* contact, std::vector<RigidPose>* poses,
                    const StageDissipation& dissipation = StageDissipation(),
                    const SoftStage* soft = nullptr, std::vector<Eigen::VectorXd>* softX = nullptr,
                    StageWorkspace* workspace = nullptr);

  int NumDofs() const override { return numDofs_; }
  double Value(const Eigen::VectorXd& d) override;
  double Evaluate(Eigen::VectorXd* gradient, Eigen::SparseMatrix<double>* hessian,
                  PsdProjection projection) override;
  void Commit(const Eigen::VectorXd& d) override;
  /// Whether the stage is a potential: its dissipation is one (or off) and no body has an applied
  /// torque.
  bool IsPotential() const override;
  /// Units are the dynamic rigid bodies (unit = dofOffset / 6), then the kinds (one each);
  /// shares their inertia and gravity terms (a kind's stage energy) plus the contact pairs'
  /// values (ContactPipeline::SplitLastEvaluation). False with soft actors.
  bool LastSplit(StageSplit* split) override;
  void Residual(const Eigen::VectorXd& d, Eigen::VectorXd* r) override;
  /// J = ∂r/∂δ: the (unprojected) Hessian of the potential terms with the rotation blocks'
  /// trivialization term −½[τ]× (τ: that body's potential torque), plus the dissipation Jacobian.
  void EvaluateResidual(Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J) override;
  /// The contact statistics of the evaluation become LastContactStats when Commit(d) follows.
  bool EvaluateResidualAtStep(const Eigen::VectorXd& d, Eigen::VectorXd* r,
                              Eigen::SparseMatrix<double>* J) override;
  /// As EvaluateResidualAtStep, for the potential.
  bool EvaluateAtStep(const Eigen::VectorXd& d, double* value, Eigen::VectorXd* gradient,
                      Eigen::SparseMatrix<double>* hessian, PsdProjection projection) override;
  bool SupportsChart() const override { return true; }
  void SetChartOrigin() override;
  /// p = p₀ + δp, R = exp([δθ]×) R₀.
  void MoveInChart(const Eigen::VectorXd& d) override;
  /// Block diagonal: I for δp, the left Jacobian J_l(δθ) of SO(3) for δθ.
  Eigen::MatrixXd ChartTangentMap(const Eigen::VectorXd& d) const override;

  /// Contact statistics of the last evaluation at the current iterate (Evaluate or
  /// EvaluateResidual), including the dissipative samples and the largest ‖T_C‖/(μ λ̂_n).
  const ContactStats& LastContactStats() const { return lastStats_; }
  /// Smallest det F over the soft tets at the last Evaluate / EvaluateResidual (+∞ without).
  double LastMinDetF() const { return lastMinDetF_; }
  /// Scales each dynamic rigid body's [δp, δθ], and each kind's stage dofs, by its
  /// ContactPipeline::StepLimits fraction (the move's sample depths may at most double, or reach
  /// ε/2; core/contact/rigid_contact.h). Soft dofs are left as they are.
  bool LimitStep(Eigen::VectorXd* d) override;
  /// Scales each dynamic rigid body's [δp, δθ] so that no point within the body's radius ρ moves
  /// more than kCorrectionTrust ρ: ‖δp‖ + ‖δθ‖ ρ <= kCorrectionTrust ρ, ρ = max(samples' radius,
  /// RMS radius √(tr J / m)) [m]. Soft dofs are left as they are.
  bool TrustStep(Eigen::VectorXd* d) override;
  /// max over bodies of ‖δp‖∞ and ‖δθ‖ times the body's RMS radius √(tr J / m), and over soft
  /// nodes of ‖δx‖∞ [m].
  double StepNorm(const Eigen::VectorXd& d) const override;
  /// In dof order: blocks of six for the dynamic rigid bodies (whose dofs lead), blocks of three
  /// for the free soft nodes, each kind's free dofs in blocks of its DofBlockSize.
  void BlockLayout(DofBlockLayout* layout) const override;

 private:
  /// Whether the dissipation terms are a potential (off, or ExplicitNormals).
  bool DissipationIsPotential() const;
  /// Body i's applied loads at `pose` [J]: −F·p, and −(W_i + τ·log(R R_cᵀ)) for a torque, with
  /// R_c the current iterate's rotation and W_i the torque's work along the committed iterates
  /// (so that a trial's value equals the one evaluated after committing it, bit for bit).
  /// order >= 1: −F into gPot's δp entries and −τ into rDiss's δθ entries (a residual term).
  double AppliedLoads(size_t i, const RigidPose& pose, int order, Eigen::VectorXd* gPot,
                      Eigen::VectorXd* rDiss) const;
  /// The kinds' stage energies at their configurations in softX (after the soft actors'); order
  /// >= 1 adds their gradients into *gPot, order 2 their Hessians into triplets_. A kind's
  /// StageLoad f adds −(W + f·TangentBetween(q_c, q)) to the value (q_c the current iterate, W
  /// its work so far: a trial's value equals the one evaluated after committing it) and −f into
  /// *rDiss (a residual term).
  double EvaluateKindTerms(const std::vector<Eigen::VectorXd>& softX, int order,
                           PsdProjection projection, Eigen::VectorXd* gPot,
                           Eigen::VectorXd* rDiss);
  /// Kind k's part of a stage vector d (its tangent dofs; 0 at prescribed ones), in a scratch
  /// vector of the workspace (valid until the next call).
  const Eigen::VectorXd& KindLocal(size_t k, const Eigen::VectorXd& d) const;
  /// The kinds' trivialization terms of the residual Jacobian (ActorKind::
  /// AddResidualJacobianCorrection) from the potential residual (r, plus scratch_ when the
  /// dissipation is a potential) at their configurations in softX, into triplets_.
  void AddKindJacobianCorrections(const Eigen::VectorXd& r, bool dissipationIsPotential,
                                  const std::vector<Eigen::VectorXd>& softX);
  /// Moves trial_ to s ⊕ d and marks d as the step whose statistics a Commit(d) adopts.
  void BeginTrial(const Eigen::VectorXd& d);
  /// Evaluate's work at the given configuration.
  double ValueAndDerivatives(const std::vector<RigidPose>& poses,
                             const std::vector<Eigen::VectorXd>& softX, Eigen::VectorXd* gradient,
                             Eigen::SparseMatrix<double>* hessian, PsdProjection projection,
                             ContactStats* stats, double* minDetF);
  /// EvaluateResidual's work at the given configuration.
  void ResidualAndJacobian(const std::vector<RigidPose>& poses,
                           const std::vector<Eigen::VectorXd>& softX, Eigen::VectorXd* r,
                           Eigen::SparseMatrix<double>* J, ContactStats* stats, double* minDetF);
  /// The rigid poses (and, if softOut is not null, the soft positions) at s ⊕ d.
  void Retract(const Eigen::VectorXd& d, std::vector<RigidPose>* out,
               std::vector<Eigen::VectorXd>* softOut) const;
  /// All terms at `poses` and soft positions `softX`: value; order >= 1: potential gradient into
  /// *gPot and dissipative residual into *rDiss (may alias); order 2: triplets_.
  double EvaluateAt(const std::vector<RigidPose>& poses,
                    const std::vector<Eigen::VectorXd>& softX, int order,
                    PsdProjection projection, Eigen::VectorXd* gPot, Eigen::VectorXd* rDiss,
                    ContactStats* stats = nullptr, double* minDetF = nullptr);

  const std::vector<RigidBodyModel>& models_;
  const std::vector<int>& dofOffset_;
  int numDofs_;
  const StageTargets& targets_;
  bool hasTorque_ = false;          ///< some body has a nonzero applied torque, or some kind a
                                    ///< StageLoad
  std::vector<double> torqueWork_;  ///< W_i of AppliedLoads, per body (with hasTorque_)
  /// Per kind: its StageLoad f (empty: none) and f's work W along the committed iterates [J]
  /// (both empty when no kind has one).
  std::vector<Eigen::VectorXd> kindLoad_;
  std::vector<double> kindLoadWork_;
  Eigen::Vector3d gravity_;
  ContactPipeline* contact_;
  std::vector<RigidPose>* poses_;
  std::unique_ptr<StageWorkspace> ownWorkspace_;  // only without the caller's
  StageWorkspace* ws_;  // the caller's, or *ownWorkspace_
  std::vector<RigidPose>& trial_;
  std::vector<Eigen::VectorXd>& softTrial_;
  std::vector<double>& limits_;
  Eigen::VectorXd& scratch_;
  Eigen::VectorXd& pendingStep_;  // EvaluateResidualAtStep's or EvaluateAtStep's step
  std::vector<Eigen::Triplet<double>>& triplets_;
  StageDissipation dissipation_;
  DissipationContext context_;
  ContactStats lastStats_;
  // Whether pendingStep_ and these statistics are this problem's (EvaluateResidualAtStep's or
  // EvaluateAtStep's), adopted by a Commit of that step.
  bool hasPending_ = false;
  ContactStats pendingStats_;
  double pendingMinDetF_ = INFINITY;
  std::vector<RigidPose> origin_;
  const std::vector<Eigen::VectorXd>& SoftPositions() const { return softX_ ? *softX_ : noSoft_; }
  const SoftStage* soft_ = nullptr;
  std::vector<Eigen::VectorXd>* softX_ = nullptr;
  std::vector<Eigen::VectorXd> softOrigin_, noSoft_;
  double lastMinDetF_ = INFINITY;
  int softBegin_ = 0, softEnd_ = 0;  // the soft nodes' dofs [softBegin_, softEnd_)
};

/// The data of one stage, from which its problem can be built at any configuration (the stage
/// driver's solves, and recording policies: core/dynamics/stage_recorder.h).
struct StageInputs {
  const std::vector<RigidBodyModel>* models = nullptr;
  const std::vector<int>* dofOffset = nullptr;
  int numDofs = 0;
  const StageTargets* targets = nullptr;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  ContactPipeline* pipeline = nullptr;
  const SoftStage* soft = nullptr;
  StageWorkspace* workspace = nullptr;
  /// The stage's problem at *poses (and *softX, may be null) in the dissipation setting d; its
  /// Commit moves them.
  SceneStageProblem Problem(std::vector<RigidPose>* poses, const StageDissipation& d,
                            std::vector<Eigen::VectorXd>* softX) const {
    return SceneStageProblem(*models, *dofOffset, numDofs, *targets, gravity, pipeline, poses, d,
                             soft, softX, workspace);
  }
};

}  // namespace superdex
