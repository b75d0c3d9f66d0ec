// The contact pipeline (spec: "Contact Pipeline") over the generic layer's actors (rigid and soft
// ones among them): broad phase over actor bounding boxes, narrow phase of colliding samples
// against collider fields, response into the stage's gradient and Hessian through the one
// assembler of core/contact/kind_contact.h (on a frame's field or a kind's tet field alike).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "core/contact/broad_phase.h"
#include "core/contact/contact_filter.h"
#include "core/contact/kind_contact.h"
#include "core/contact/point_cloud.h"
#include "core/model/rigid_body.h"
#include "core/contact/rigid_contact.h"
#include "core/contact/rigid_dissipation.h"
#include "optim/stage_problem.h"
#include "optim/triplet_assembly.h"

namespace superdex {

/// What the last evaluation saw.
struct ContactStats {
  int candidatePairs = 0;      ///< ordered pairs after broad phase and role/filter checks
  int activePairs = 0;         ///< pairs with at least one sample below its threshold
  int activeSamples = 0;       ///< samples with φ < δ
  double minSignedDistance = INFINITY;  ///< smallest φ over tested samples [m]
  double energy = 0.0;         ///< Σ Π_{A,B} [J]
  int dissipativeSamples = 0;  ///< samples with a positive dissipative load
  double dissipation = 0.0;    ///< Δt_i Σ w R [J] (0 without a dissipation context)
  double maxCoulombRatio = 0.0;///< max ‖T_C‖/(μ λ̂_n) over samples (<= 1)
};

/// The stage data dissipation needs (spec: "Stage-Discrete Dissipation"); the stage starts x⁰ and
/// last configurations x_n are the view's (KindView).
struct DissipationContext {
  double dt = 0.0;                                      ///< Δt_i [s]
  DissipationMode mode = DissipationMode::ReconstructedLoad;
  bool fadeFriction = true;
  /// Sensitivities (core/contact/slip_tape.h): record every dissipative sample's slip into *slips
  /// (`recordSlips`), or evaluate the force about the slips recorded there; null: neither.
  StageSlips* slips = nullptr;
  bool recordSlips = false;
};

/// The actors of the generic layer for one evaluation (core/model/actor_kind.h): per actor k its
/// q, its x_n (or null), its stage start x⁰ (dissipation; or null) and the stage offsets of its
/// local dofs (−1 for a prescribed dof).
struct KindView {
  const std::vector<Eigen::VectorXd>* q = nullptr;
  const std::vector<Eigen::VectorXd>* qLast = nullptr;
  const std::vector<Eigen::VectorXd>* q0 = nullptr;
  const std::vector<std::vector<int>>* stageDof = nullptr;
};

/// Ordered pair on a collider field of a kind, carried by its frame or its tets (A colliding, B
/// collider: indices into the kinds), evaluated by the one assembler of
/// core/contact/kind_contact.h; or a piece of a point-cloud pair, B's points cloudBegin ..
/// cloudEnd − 1 as spheres on A's samples (core/contact/point_cloud.h; a = b: self-contact).
struct KindPair {
  int a = -1, b = -1;
  PairContactParams params;
  int cloudBegin = -1, cloudEnd = -1;
  bool Cloud() const { return cloudBegin >= 0; }
};

class ContactPipeline {
 public:
  /// Precomputes per-actor data. `filter` (may be null: everything eligible) is read at every
  /// evaluation. `kinds` (may be null) are the actors, seen by the filter as kindActor[k]; they
  /// must outlive the pipeline's use.
  void Configure(const ContactFilter* filter, const std::vector<const ActorKind*>* kinds,
                 std::vector<int> kindActor);

  /// Π = Σ over eligible ordered pairs of the penalty energy at the view's configurations, plus
  /// Δt_i Σ w R when `dissipation` is not null (it then needs the view's x⁰ and x_n). With x_n,
  /// the alignment rejection of the penalty is decided there (core/contact/kind_contact.h);
  /// without, at the current configuration. order 0: value; 1: also adds the penalty gradient
  /// into *gradient and the dissipative residual into *dissipationResidual (may alias
  /// *gradient; at the view's stage dofs); 2: also appends Jacobian entries: each pair's penalty
  /// Hessian plus, in ExplicitNormals mode, its dissipation Hessian, projected per `projection`;
  /// in the residual modes the dissipation Jacobian (not symmetric) is appended unprojected.
  /// Stencils of six-dof groups (rigid actors') append 6 × 6 blocks to *blocks (as if their
  /// triplets stood in *triplets where it ended on entry: TripletAssembly's blockPosition), the
  /// others triplets. Pairs are evaluated in parallel; results are reduced in a fixed order, so
  /// the output does not depend on the number of threads.
  double Evaluate(int order, PsdProjection projection, Eigen::VectorXd* gradient,
                  std::vector<Eigen::Triplet<double>>* triplets,
                  std::vector<DenseBlock6>* blocks, ContactStats* stats,
                  const DissipationContext* dissipation = nullptr,
                  Eigen::VectorXd* dissipationResidual = nullptr,
                  const KindView* kinds = nullptr);

  /// Step limits of Newton's global phase: (*kindAlpha)[k] <= 1 the largest fraction of kind k's
  /// move from `now` to `next` that the pairs it is part of allow (StepLimitSink: no sample's
  /// depth more than doubles, or reaches ε/2), both sides moving by the same fraction (1 for
  /// kinds without such a pair). Pairs with a kind that refuses step limits (ActorKind::
  /// Shortcuts) and pairs on a tet field impose none. Pairs are found at
  /// `next`; evaluated in parallel, reduced by min.
  void StepLimits(const KindView& now, const KindView& next, std::vector<double>* kindAlpha);

  /// Every active contact sample at the view's configurations (serial; for reporting). Records
  /// carry actor indices (see Configure) and, for samples on a face, the face. With a stage's
  /// `dissipation` (and the view's x⁰, x_n), as Evaluate takes them, each record carries its
  /// dissipation traction too.
  void CollectSamples(std::vector<ContactSampleRecord>* records, const KindView* kinds = nullptr,
                      const DissipationContext* dissipation = nullptr);

  /// The last Evaluate's pairs by kind (StageProblem::LastSplit): each pair's penalty and
  /// dissipation values, as Evaluate summed them, added to (*share)[k] of its first dynamic kind
  /// k (some tangent dof not prescribed), and each pair of two dynamic kinds with an active
  /// sample (penalty or dissipation) appended to *joins as (colliding, collider). False, with
  /// nothing added, if that evaluation had pairs on a tet field (not split) or the pairs
  /// changed since (StepLimits).
  bool SplitLastEvaluation(std::vector<double>* share,
                           std::vector<std::pair<int, int>>* joins) const;

 private:
  /// One Evaluate call's arguments, as its pair kinds' evaluations read them.
  struct Request {
    int order = 0;
    PsdProjection projection = PsdProjection::None;
    Eigen::VectorXd* gradient = nullptr;
    std::vector<Eigen::Triplet<double>>* triplets = nullptr;
    std::vector<DenseBlock6>* blocks = nullptr;
    const DissipationContext* dissipation = nullptr;
    Eigen::VectorXd* dissipationResidual = nullptr;
    const KindView* kinds = nullptr;
    bool potential = true;   ///< no dissipation, or ExplicitNormals
    bool isotropic = false;  ///< DissipationSetup::isotropicFrictionHessian
  };
  /// Evaluate's pairs in parallel, then reduced in pair order into *energy and *st and
  /// scattered into the request's outputs.
  void EvaluateKindPairs(const Request& q, double* energy, ContactStats* st);
  void FindPairs(const KindView* kinds);
  // The generic layer's ordered pair (a, b) when the roles, the filter and the motion allow it
  // (a = b: a point cloud's self-contact).
  void ConsiderKindPair(int a, int b);
  // A point-cloud pair's pieces (kCloudPiece points each) with their parameters.
  void AddCloudPieces(int a, int b, const PairContactParams& params);
  // Whether colliding kind a's pairs take the threshold padding (spec: its collider is None or
  // PointCloud, i.e. it has neither a frame field nor a tet field of its own).
  bool PadsThreshold(int a) const { return !kindCollider_[a] && !kindTetCollider_[a]; }
  // The colliding side's samples of a kind pair that can contribute on its collider side B.
  // kindSides_ and kindBodies_ at the request's configurations, for the kinds of kindPairs_.
  void FormKindSides(const Request& q);
  void GatherKindPairSamples(const Request& q, const KindPair& kp, const FrameSide& B,
                             const DissipationSetup* setup, SampleSink* sink) const;
  // The kind pairs' tested samples (the colliding sides' counts): whether a sweep pays for
  // parallel workers.
  size_t KindPairWork() const;
  /// `isotropicFriction`: DissipationSetup::isotropicFrictionHessian.
  DissipationSetup MakeSetup(const PairContactParams& params,
                             const DissipationContext& dissipation,
                             bool isotropicFriction) const;
  /// A stencil pair's reduction: its counts and energies into *st and *energy, and its stencils
  /// scattered into the request's outputs by the blocks they carry (ContactStencil::blocks).
  template <typename Stencils>
  void ReducePair(const Request& q, const Stencils& r, double* energy, ContactStats* st) const;

  const ContactFilter* filter_ = nullptr;
  std::vector<Aabb> boxes_;
  std::vector<std::pair<int, int>> overlaps_;
  OverlapCache overlapCache_;  // the broad phase's candidates, kept while the boxes stay inside
  std::vector<double> kindPairLimits_;
  // Per kind with a tet field in the collider role: its point locators over x and x_n, its side
  // (FormKindSides), and its reference grid as a field (Configure).
  std::vector<TetLocator> kindLocators_, kindLocatorsLast_;
  std::vector<TetFieldSide> kindTetSides_;
  std::vector<RigidCollider> kindTetFields_;
  // Kind k's tet field as a collider side at the view's configurations (with the stage start
  // and, for explicit normals, x_n's locator when there is a `dissipation`).
  FrameSide TetSide(const KindView& kinds, int k, const DissipationContext* dissipation);
  bool evaluatedTetPairs_ = false;  // the last Evaluate had pairs on a tet field
  const std::vector<const ActorKind*>* kinds_ = nullptr;
  std::vector<int> kindActor_;
  std::vector<double> kindInflation_;
  std::vector<char> kindHasDofs_;  // per kind: some tangent dof is not prescribed
  // Per kind: IsColliding(), Collider() != null, IsStatic().
  std::vector<char> kindColliding_, kindCollider_, kindStatic_;
  std::vector<char> kindTetCollider_;  // per kind: a tet field with an Sdf grid (TetCollider)
  std::vector<size_t> kindSamples_;  // per kind: its samples and its sample bodies'
  std::vector<char> kindStepLimit_;  // per kind: Shortcuts().stepLimit
  // Per kind: its samples lie on a deforming surface (face normals, 3-node stencils).
  std::vector<char> kindFaceSamples_;
  // Per kind: a PointCloud collider (ActorKind::PointCloud) and its self-contact.
  std::vector<char> kindCloud_, kindCloudSelf_;
  // Per kind in a point-cloud pair, at the evaluation under way (FormKindSides): its samples
  // with their hash (colliding) and its points (collider).
  std::vector<CloudSamples> cloudSamples_;
  std::vector<CloudPoints> cloudPoints_;
  std::vector<double> cloudCell_;  // per colliding kind: its hash's cell side [m]
  // Pair piece k's terms into *out (EvaluateCloudPoints at the request's configurations).
  void EvaluateCloudPiece(const KindView& kv, const KindPair& kp, const DissipationSetup* setup,
                          int order,
                          PairStencils* out,
                          std::vector<ContactSampleRecord>* records = nullptr) const;

  std::vector<KindPair> kindPairs_;
  // What kindPairs_ was formed from (FindPairs keeps it while both are unchanged): the broad
  // phase's overlaps and the filter's version; none since Configure when !pairsFormed_.
  std::vector<std::pair<int, int>> pairOverlaps_;
  long pairFilterVersion_ = 0;
  bool pairsFormed_ = false;
  // Per kind pair, its stencils: compact (12 dofs each, as rigid pairs') when all of them fit,
  // else wide (kindWide_[k]).
  std::vector<RigidPairStencils> kindResults_;
  std::vector<PairStencils> kindWideResults_;
  std::vector<char> kindWide_;
  // f(kind pair k's stencils), compact or wide.
  template <typename F>
  void WithKindResults(size_t k, F&& f) const {
    if (kindWide_[k])
      f(kindWideResults_[k]);
    else
      f(kindResults_[k]);
  }
  // Per kind, at the kind pairs' evaluation under way: its collider frame and its sample bodies,
  // formed once for all its pairs (FormKindSides; only for kinds in a pair in that role).
  std::vector<FrameSide> kindSides_;
  // A static kind's side (it is held where it was created: its x_n and x⁰ are the values of x)
  // is formed again only when x or the stage offsets change (a state set by hand).
  struct StaticSide {
    bool formed = false;
    Eigen::VectorXd x;
    std::vector<int> stageDof;
  };
  std::vector<StaticSide> staticSides_;
  void FormStaticSide(int k, const Eigen::VectorXd& x, const Eigen::VectorXd* qLast,
                      const Eigen::VectorXd* x0, const std::vector<int>& stageDof);
  std::vector<SampleBodyPoses> kindBodies_;
  std::vector<char> kindRoles_;  // per kind: 1 collider, 2 sample bodies (bits)
  // The pairs' slip use in the evaluation under way and, when recording, their buffers.
  std::vector<PairSlipUse> slipUse_;
  std::vector<PairSlips> slipRecord_;
  /// Sets slipUse_ for the pairs: buffers to record into or the records to read; left empty
  /// without slips in the context (plain simulation pays no per-pair work for them).
  void BeginSlips(const DissipationContext* dissipation);
  /// Pair k's slip use in the evaluation under way (none when the list is empty).
  PairSlipUse SlipUse(size_t k) const { return slipUse_.empty() ? PairSlipUse() : slipUse_[k]; }
  /// Recording: hands the buffers to the context's record.
  void EndSlips(const DissipationContext* dissipation);
};

}  // namespace superdex
