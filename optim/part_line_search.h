// A line search by the independent parts of a stage (StageProblem::LastSplit), the by-parts mode
// of optim/line_search.h.
//
// Where no term couples two groups of dofs, the objective splits, f = Σ_P f_P, and so does
// Newton's direction (the Hessian, or the residual's Jacobian, is block diagonal over the parts).
// One step length for all parts lets a single part that needs a short step cut every other
// part's step as well. Here each part P of the base state s — a connected component of the units
// joined by terms nonzero at s — gets its own step length α_P. The trial s ⊕ Σ_P α_P d_P is
// evaluated once for all parts; parts joined by a term nonzero at the trial form one group G,
// tested on its share:
//   minimization:  f_G(trial) <= f_G(s) + c Σ_{P∈G} α_P g_P·d_P
//   residual:      θ_G(trial) <= θ_G(s) − 2c Σ_{P∈G} α_P θ_P(s),   θ = ½‖r‖² over G's dofs
// (f_G(s) = Σ_{P∈G} f_P(s): the parts were uncoupled at s), or the round-off band: the group's
// change and its predicted change both within the band. Every part of a failing group has α_P
// cut by β, and the trial is evaluated again until every group passes; an accepted trial lowers
// f (θ) by the sum of its groups' decreases, as a single Armijo step would.
// See docs/solver.md; measurements: docs/optim-notes.md.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "optim/stage_problem.h"

namespace superdex {

/// The smallest fraction a blockwise shortening `limited` of d applied to any dof (1 if none):
/// min over d_k ≠ 0 of limited_k / d_k.
double SmallestFraction(const Eigen::VectorXd& d, const Eigen::VectorXd& limited);

class PartLineSearch {
 public:
  /// Reads the split of the evaluation just made at the base state s. False when the problem
  /// does not split or has a single part there (then use one step length).
  bool Begin(StageProblem& problem);
  /// Makes the split read by the last Test (a trial evaluated with derivatives and accepted) the
  /// base state's. False as Begin.
  bool AdoptTrial();
  int Parts() const { return parts_; }

  /// Base merits along the direction `dir`: f_P(s) and g_P·d_P (minimization), or θ_P(s) and
  /// ½|r_P·d_P| (residual). Every α_P is set to 1.
  void StartMinimization(const Eigen::VectorXd& g, const Eigen::VectorXd& dir);
  /// `linearized` (or null): J dir, the direction's first-order change of r; a part with
  /// r_P·(J dir)_P >= 0 (no first-order decrease of θ_P: the linear solve's error on P exceeds
  /// P's residual) gets α_P = 0, as a part without descent does in minimization.
  void StartResidual(const Eigen::VectorXd& r, const Eigen::VectorXd& dir,
                     const Eigen::VectorXd* linearized = nullptr);

  /// A Newton step the problem shortened blockwise (StageProblem::TrustStep, LimitStep): where a
  /// part's shortened step `limited` is no descent direction for its share (g_P·l_P >= 0: the
  /// shortening broke the coupled Newton direction of its blocks), the part takes its Newton
  /// direction d_P scaled by the smallest fraction the shortening applied to its dofs, a descent
  /// direction that respects every block's bound.
  void ShortenByParts(const Eigen::VectorXd& g, const Eigen::VectorXd& d, Eigen::VectorXd* limited);

  /// After StartResidual: α_P ← min(α_P, φ_P), φ_P the smallest fraction the shortening
  /// `limited` of d applied to a dof of P — the problem's trust region as the first step length
  /// along Newton's own direction, on which the residual merit test is exact.
  void CapSteps(const Eigen::VectorXd& d, const Eigen::VectorXd& limited);

  /// step = Σ_P α_P dir_P.
  void Step(const Eigen::VectorXd& dir, Eigen::VectorXd* step) const;

  /// Tests the trial just evaluated at Step(dir) (minimization: its value f, rTrial null;
  /// residual: its r). True if every group passes; otherwise cuts the failing groups' α_P by
  /// `beta` and returns false. `c` is the Armijo constant, `roundoff` the relative round-off band
  /// (applied to |f(s)| or θ(s)). A trial that does not split is tested as one group.
  bool Test(StageProblem& problem, double trialValue, const Eigen::VectorXd* rTrial, double c,
            double beta, double roundoff);
  /// Cuts every α_P by beta (a non-finite trial value).
  void CutAll(double beta);

  /// Whether every α_P is 1; the smallest α_P (over the parts that own a dof).
  bool AllFull() const;
  double MinAlpha() const;

 private:
  /// Union-find over parent_ (units in Label, parts in Test).
  int Find(int u);
  void Unite(int a, int b);
  /// Labels the units' parts from base_.joins.
  bool Label();
  /// partFraction_[P]: SmallestFraction over P's dofs.
  void PartFractions(const Eigen::VectorXd& d, const Eigen::VectorXd& limited);

  StageSplit base_, trial_;
  int parts_ = 0;
  std::vector<int> partOfUnit_;     // per unit: its part at s
  std::vector<char> partHasDofs_;   // per part: whether a dof belongs to it
  std::vector<double> alpha_;       // per part
  std::vector<double> value_;       // per part: f_P(s) or θ_P(s)
  std::vector<double> slope_;       // per part: g_P·d_P, or ½|r_P·d_P|
  bool residual_ = false;
  double scale_ = 0.0;              // |f(s)| or θ(s): the round-off band's scale
  // Scratch of Label and Test (no allocation once sized).
  std::vector<int> parent_, groupOf_;
  std::vector<double> groupTrial_, groupBase_, groupSlope_, groupRequired_;
  std::vector<char> groupFails_;
  std::vector<double> partSlope_, partFraction_;  // ShortenByParts, StartResidual; CapSteps
};

}  // namespace superdex
