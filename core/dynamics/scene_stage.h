// One implicit stage over the scene's actors (the generic layer's kinds: rigid and soft actors
// among them), as a StageProblem for the optim/ solvers:
//   Φ_i(q) = Σ_k Φ_kind,k(q_k)  +  Π_contact(q)  +  Δt_i Σ w R(V_rel,i)   [J]
// (Φ_kind: ActorKind::StageEnergy, inertia, gravity, internal energy and applied forces; a soft
// actor's: core/model/soft_terms.h). Dofs: each kind's free tangent dofs in creation order (6 per
// dynamic rigid actor, [δp, δθ]; 3 per free soft node).
// The dissipation term is an exact potential only with ExplicitNormals; in the other dissipation
// modes the stage is the residual r = ∇(Φ without R) + Σ w J_Yᵀ ∂R/∂V
// (core/contact/rigid_dissipation.h). A kind's generalized load f (ActorKind::StageLoad; a rigid
// actor's applied torque) adds −f to the residual: a constant world torque is not the gradient of
// any function of the rotation, so a stage with one is not a potential either (IsPotential); its
// minimizing solves see the load's work along the iterates they commit (SceneStageProblem::Commit).
#pragma once

#include <memory>
#include <vector>

#include "core/contact/contact_pipeline.h"
#include "core/model/actor_kind.h"
#include "optim/stage_problem.h"
#include "optim/triplet_assembly.h"

namespace superdex {

/// Dissipation settings of a stage; `enabled` false gives the conservative stage.
struct StageDissipation {
  bool enabled = false;
  DissipationMode mode = DissipationMode::ReconstructedLoad;
  bool fadeFriction = true;
  StageSlips* slips = nullptr;  ///< DissipationContext::slips (sensitivities)
  bool recordSlips = false;
};

/// The actors of a stage (core/model/actor_kind.h): the kinds, and per actor the stage offsets of
/// its local dofs (−1 for a prescribed dof), its stage data and copies of its x⁰ and x_n (contact
/// view). The stage's iterate x holds each actor's configuration q, in the same order.
///
/// Attached actors (ActorKind::CarriedParts: a link's collision body, a soft skin's bound nodes)
/// have carried parts whose dofs are no stage unknowns (stageDof −1); their entries in x follow
/// their carriers' (SyncAttached). The contact pipeline and the kinds' own terms see the parts'
/// dofs ([δx] of a point, [δp, δθ] of a pose) at virtual dofs numDofs … numContactDofs − 1
/// (contactDof), and the stage reduces what it assembles there into the carrier's dofs with the
/// chart Jacobian A (ActorKind::CarriedFrameJacobians; a point's rows are its δp's) and, in the
/// exact Hessian, the chart's curvature (ActorKind::AddCarriedFrameCurvature):
///   g = g_real + Aᵀ g_part,   H = Pᵀ H_ext P + Σ_parts curvature(g_part),   P = [I; A].
struct KindStage {
  const std::vector<const ActorKind*>* kinds = nullptr;
  std::vector<std::vector<int>> stageDof;
  std::vector<KindStageData> data;
  std::vector<Eigen::VectorXd> q0, qLast;
  /// An attached actor and its carrier (indices into the kinds; a carrier comes first).
  struct Attached {
    int actor = -1, carrier = -1;
  };
  std::vector<Attached> attached;
  std::vector<std::vector<int>> contactDof;  ///< with attached actors only: the contact's numbering
  int numContactDofs = 0;                    ///< with attached actors only
  size_t Size() const { return data.size(); }
};

/// The contact view of a stage at the iterate x; empty (q null) without actors.
KindView KindViewOf(const KindStage& stage, const std::vector<Eigen::VectorXd>& x);

/// Writes each attached actor's configuration in *x from its carrier's (AttachedConfiguration).
void SyncAttached(const KindStage& stage, std::vector<Eigen::VectorXd>* x);

/// The pipeline's dissipation data for a stage of step dt [s] (ContactPipeline::Evaluate).
DissipationContext ContextOf(const StageDissipation& dissipation, double dt);

/// A carried part of an attached actor in a stage (SceneStageProblem::ReduceAttached): the actor,
/// its carrier, the part and its first dof at the contact's numbering (−1: the carrier has no
/// unknowns).
struct StagePart {
  int actor = -1, carrier = -1;
  const CarriedPart* part = nullptr;
  int first = -1;
};

/// Buffers that one stage hands to the next (no allocation after the first stage of a scene).
/// Problems that share it must be used one after the other (a solve ends before the next
/// problem's begins), as the stage solves are.
struct StageWorkspace {
  std::vector<Eigen::VectorXd> trial;      ///< the configuration s ⊕ d under evaluation
  std::vector<double> kindLimits;          ///< LimitStep's fractions per kind
  std::vector<double> kindValue;           ///< the last evaluation's stage energy per kind
  std::vector<double> splitValue;          ///< LastSplit's per-kind shares
  Eigen::VectorXd scratch;                 ///< the dissipative residual's part
  Eigen::VectorXd pendingStep;             ///< the step of the last EvaluateAtStep-like call
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<DenseBlock6> blocks;         ///< rigid pairs' 6 × 6 blocks (ContactPipeline)
  size_t blockPosition = 0;                ///< where in `triplets` the blocks stand
  Eigen::VectorXd kindGradient;                    ///< a kind's local gradient
  Eigen::VectorXd kindDelta;                       ///< a kind's local step (or residual)
  std::vector<Eigen::Triplet<double>> kindHessian; ///< a kind's local Jacobian corrections
  TripletAssembly hessianAssembly;   ///< Evaluate's Hessians (pattern kept between iterations)
  TripletAssembly jacobianAssembly;  ///< EvaluateResidual's Jacobians
  // Attached actors' reduction (ReduceAttached).
  TripletAssembly extendedAssembly;           ///< the contact's extended Hessian
  Eigen::SparseMatrix<double> extended;       ///< H_ext
  Eigen::SparseMatrix<double> reduction;      ///< P
  std::vector<StagePart> parts;
  std::vector<Eigen::MatrixXd> frameJacobians;
  std::vector<FramePoint> framePoints;
  std::vector<Eigen::Matrix<double, 6, 1>> frameLoads;
};


class SceneStageProblem : public StageProblem {
 public:
  /// A stage of step dt [s] over the actors of `stage` (their stage dofs numbered below numDofs)
  /// at the iterate *x (each actor's configuration; prescribed entries already at their stage
  /// values), updated in place by Commit.
  SceneStageProblem(int numDofs, double dt, ContactPipeline* contact, const KindStage& stage,
                    std::vector<Eigen::VectorXd>* x,
                    const StageDissipation& dissipation = StageDissipation(),
                    StageWorkspace* workspace = nullptr);

  int NumDofs() const override { return numDofs_; }
  double Value(const Eigen::VectorXd& d) override;
  double Evaluate(Eigen::VectorXd* gradient, Eigen::SparseMatrix<double>* hessian,
                  PsdProjection projection) override;
  void Commit(const Eigen::VectorXd& d) override;
  /// Whether the stage is a potential: its dissipation is one (or off) and no kind has a
  /// StageLoad (a rigid actor's applied torque).
  bool IsPotential() const override;
  /// Units are the kinds (one each); shares their stage energies plus the contact pairs' values
  /// (ContactPipeline::SplitLastEvaluation). False where a kind refuses it (ActorKind::Shortcuts).
  bool LastSplit(StageSplit* split) override;
  void Residual(const Eigen::VectorXd& d, Eigen::VectorXd* r) override;
  /// J = ∂r/∂δ: the (unprojected) Hessian of the potential terms with the kinds' trivialization
  /// terms (ActorKind::AddResidualJacobianCorrection; a rigid actor's −½[τ]×, τ its potential
  /// torque), plus the dissipation Jacobian.
  void EvaluateResidual(Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J) override;
  /// The contact statistics of the evaluation become LastContactStats when Commit(d) follows.
  bool EvaluateResidualAtStep(const Eigen::VectorXd& d, Eigen::VectorXd* r,
                              Eigen::SparseMatrix<double>* J) override;
  /// As EvaluateResidualAtStep, for the potential.
  bool EvaluateAtStep(const Eigen::VectorXd& d, double* value, Eigen::VectorXd* gradient,
                      Eigen::SparseMatrix<double>* hessian, PsdProjection projection) override;
  bool SupportsChart() const override { return true; }
  void SetChartOrigin() override;
  /// Each kind's Retract from the chart's origin (a rigid actor: p = p₀ + δp, R = exp([δθ]×) R₀).
  void MoveInChart(const Eigen::VectorXd& d) override;
  /// Block diagonal: each kind's ActorKind::ChartTangentMap (a rigid actor: I for δp, the left
  /// Jacobian J_l(δθ) of SO(3) for δθ; I for a vector kind).
  Eigen::MatrixXd ChartTangentMap(const Eigen::VectorXd& d) const override;

  /// Contact statistics of the last evaluation at the current iterate (Evaluate or
  /// EvaluateResidual), including the dissipative samples and the largest ‖T_C‖/(μ λ̂_n).
  const ContactStats& LastContactStats() const { return lastStats_; }
  /// Scales each kind's stage dofs by its ContactPipeline::StepLimits fraction (the move's sample
  /// depths may at most double, or reach ε/2; core/contact/rigid_contact.h).
  bool LimitStep(Eigen::VectorXd* d) override;
  /// Scales each kind's stage dofs by its ActorKind::TrustFraction (a rigid actor: no point within
  /// its radius ρ moves more than kCorrectionTrust ρ; a vector kind: 1).
  bool TrustStep(Eigen::VectorXd* d) override;
  /// max over kinds of ActorKind::StepLength (a rigid actor: ‖δp‖∞ and ‖δθ‖ times its RMS
  /// radius √(tr J / m); soft nodes: ‖δx‖∞) [m].
  double StepNorm(const Eigen::VectorXd& d) const override;
  /// In dof order: each kind's free dofs in blocks of its DofBlockSize.
  void BlockLayout(DofBlockLayout* layout) const override;

 private:
  /// Whether the dissipation terms are a potential (off, or ExplicitNormals).
  bool DissipationIsPotential() const;
  /// The kinds' stage energies at their configurations in x; order
  /// >= 1 adds their gradients into *gPot, order 2 their Hessians into triplets_. A kind's
  /// StageLoad f adds −(W + f·TangentBetween(q_c, q)) to the value (q_c the current iterate, W
  /// its work so far: a trial's value equals the one evaluated after committing it) and −f into
  /// *rDiss (a residual term).
  double EvaluateKindTerms(const std::vector<Eigen::VectorXd>& x, int order,
                           PsdProjection projection, Eigen::VectorXd* gPot,
                           Eigen::VectorXd* rDiss);
  /// Kind k's part of a stage vector d (its tangent dofs; 0 at prescribed ones), in a scratch
  /// vector of the workspace (valid until the next call).
  const Eigen::VectorXd& KindLocal(size_t k, const Eigen::VectorXd& d) const;
  /// The kinds' trivialization terms of the residual Jacobian (ActorKind::
  /// AddResidualJacobianCorrection) from the potential residual (r, plus scratch_ when the
  /// dissipation is a potential) at their configurations in x, into triplets_.
  void AddKindJacobianCorrections(const Eigen::VectorXd& r, bool dissipationIsPotential,
                                  const std::vector<Eigen::VectorXd>& x);
  /// Moves trial_ to s ⊕ d and marks d as the step whose statistics a Commit(d) adopts.
  void BeginTrial(const Eigen::VectorXd& d);
  /// Evaluate's work at the given configuration.
  double ValueAndDerivatives(const std::vector<Eigen::VectorXd>& x, Eigen::VectorXd* gradient,
                             Eigen::SparseMatrix<double>* hessian, PsdProjection projection,
                             ContactStats* stats);
  /// EvaluateResidual's work at the given configuration.
  void ResidualAndJacobian(const std::vector<Eigen::VectorXd>& x, Eigen::VectorXd* r,
                           Eigen::SparseMatrix<double>* J, ContactStats* stats);
  /// The vector states at s ⊕ d into *out (attached actors' from their carriers').
  void Retract(const Eigen::VectorXd& d, std::vector<Eigen::VectorXd>* out) const;
  /// Attached actors: EvaluateAt's extended gradient *gPot, residual *rDiss (may alias) and
  /// triplets (order 2) at the contact's numbering, reduced to the stage dofs (KindStage). The
  /// exact Hessian (projection None) takes the carriers' chart curvature of the bodies' total
  /// chart loads; the projected model leaves it out (the carrier's Gauss–Newton rule). In the
  /// residual modes the dissipative load is no gradient: its curvature is the symmetric form plus
  /// ½ Aᵀ[τ_d]×A on the rotation rows (the trivialization the symmetric form takes out), so that
  /// J is the exact ∂(Aᵀ r)/∂δ there too.
  void ReduceAttached(const std::vector<Eigen::VectorXd>& x, int order, PsdProjection projection,
                      Eigen::VectorXd* gPot, Eigen::VectorXd* rDiss);
  /// All terms at the vector states x: value; order >= 1: potential gradient into *gPot and
  /// dissipative residual into *rDiss (may alias); order 2: triplets_.
  double EvaluateAt(const std::vector<Eigen::VectorXd>& x, int order,
                    PsdProjection projection, Eigen::VectorXd* gPot, Eigen::VectorXd* rDiss,
                    ContactStats* stats = nullptr);

  int numDofs_;
  double dt_;
  bool hasLoad_ = false;  ///< some kind has a StageLoad
  /// Per kind: its StageLoad f (empty: none) and f's work W along the committed iterates [J]
  /// (both empty when no kind has one).
  std::vector<Eigen::VectorXd> kindLoad_;
  std::vector<double> kindLoadWork_;
  ContactPipeline* contact_;
  std::unique_ptr<StageWorkspace> ownWorkspace_;  // only without the caller's
  StageWorkspace* ws_;  // the caller's, or *ownWorkspace_
  std::vector<Eigen::VectorXd>& trial_;
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
  const std::vector<Eigen::VectorXd>& Positions() const { return x_ ? *x_ : none_; }
  const KindStage* stage_ = nullptr;  // null for a stage without actors
  std::vector<Eigen::VectorXd>* x_ = nullptr;
  std::vector<Eigen::VectorXd> origin_, none_;
};

/// The data of one stage, from which its problem can be built at any configuration (the stage
/// driver's solves, and recording policies: core/dynamics/stage_recorder.h).
struct StageInputs {
  int numDofs = 0;
  double dt = 0.0;  ///< Δt_i [s]
  ContactPipeline* pipeline = nullptr;
  const KindStage* stage = nullptr;
  StageWorkspace* workspace = nullptr;
  /// The stage's problem at *x in the dissipation setting d; its Commit moves *x.
  SceneStageProblem Problem(const StageDissipation& d, std::vector<Eigen::VectorXd>* x) const {
    return SceneStageProblem(numDofs, dt, pipeline, *stage, x, d, workspace);
  }
};

}  // namespace superdex
