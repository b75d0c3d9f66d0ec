// The backtracking (Armijo) line search of both Newton solvers (optim/newton_solver.h,
// optim/residual_newton.h), on one of two merits m along a direction p from the state s:
//   Potential:        m = Φ,            accept α where Φ(s ⊕ αp) <= Φ(s) + c α g·p
//   ResidualSquared:  m = θ = ½‖r‖²,    accept α where θ(s ⊕ αp) <= (1 − 2cα) θ(s)
//                     (p is Newton's direction, J p = −r: θ's slope along p is −2θ)
// or, as a round-off band, where |m(s ⊕ αp) − m(s)| <= ε|m(s)| while the predicted change is
// itself <= ε|m(s)| (ε = kRoundoffBand: m cannot resolve the decrease any more). Trials
// α = α₀, α₀β, α₀β², ... (β = backtrackFactor, α₀ = 1 unless Start::firstStep says less); a
// non-finite trial merit is a rejection; after maxTrials rejections the search fails.
// LineSearchKind::None takes the single trial α₀ = 1 if its merit is finite.
// By parts: where the problem splits (StageProblem::LastSplit) and Options::byParts is set, each
// independent part gets its own α, tested on its own share of the merit (optim/part_line_search.h).
// See docs/solver.md; notes: docs/optim-notes.md.
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "optim/part_line_search.h"
#include "optim/stage_problem.h"

namespace superdex {

enum class LineSearchKind {
  Armijo,  ///< backtracking until the merit's Armijo condition holds
  None,    ///< full Newton steps
};

/// Relative width ε of the line search's round-off band: merits with |m − m(s)| <= ε |m(s)| cannot
/// be told apart from m(s) in double precision once m is a sum of many terms.
constexpr double kRoundoffBand = 1e-14;

/// The round-off band test: `trial` cannot be told from `base`, and neither can the `predicted`
/// change, within `band` (= kRoundoffBand |base|).
inline bool WithinRoundoff(double trial, double base, double predicted, double band) {
  return std::abs(trial - base) <= band && predicted <= band;
}

class LineSearch {
 public:
  enum class Merit { Potential, ResidualSquared };

  struct Options {
    LineSearchKind kind = LineSearchKind::Armijo;
    double armijoConstant = 1e-4;  ///< c
    double backtrackFactor = 0.5;  ///< β
    int maxTrials = 40;            ///< rejections before the search fails (Armijo)
    bool byParts = true;           ///< one α per independent part where the problem splits
  };

  /// The base point of one search.
  struct Start {
    Merit merit = Merit::Potential;
    double value = 0.0;                         ///< m(s)
    const Eigen::VectorXd* gradient = nullptr;  ///< Φ's gradient g, or the residual r, at s
    /// Potential: g·p (Armijo) and g·d, d the unshortened Newton direction; the band's predicted
    /// change is (α g·p / g·d) |g·d|.
    double slope = 0.0, newtonSlope = 0.0;
    /// ResidualSquared: ½|r·p|; the band's predicted change is α ½|r·p|.
    double decrement = 0.0;
    /// ResidualSquared: the Jacobian J of r at s, or null. By parts, a part P whose merit θ_P does
    /// not decrease along the direction to first order (r_P·(J p)_P >= 0: an inexact linear solve
    /// whose error on P exceeds P's own residual) stays where it is this iteration.
    const Eigen::SparseMatrix<double>* jacobian = nullptr;
    /// A blockwise shortening of p (StageProblem::TrustStep) or null: each part's first α (the
    /// whole step's, without parts) is the smallest fraction its dofs were shortened to.
    const Eigen::VectorXd* firstStep = nullptr;
    /// Evaluate the first trial with its derivatives where the problem offers it
    /// (EvaluateAtStep with the exact Hessian, EvaluateResidualAtStep).
    bool derivativesAtFirstTrial = true;

    static Start Potential(double value, const Eigen::VectorXd& g, double slope,
                           double newtonSlope);
    static Start Residual(double theta, const Eigen::VectorXd& r, double decrement);
  };

  struct Summary {
    bool accepted = false;
    /// Without parts the last trial's α; by parts 1 if the search accepted with every α_P = 1,
    /// else the smallest α_P.
    double alpha = 1.0;
    double trialMerit = std::numeric_limits<double>::quiet_NaN();  ///< m at the last trial
    int rejectedTrials = 0;
    /// The accepted trial was evaluated with its derivatives, now in the trial buffers: they are
    /// the accepted state's (swap them in instead of evaluating it again).
    bool withDerivatives = false;
  };

  /// For the next solve (resets the split).
  void SetOptions(const Options& options);
  const Options& GetOptions() const { return options_; }

  /// Reads the split of the evaluation just made at the current state (call after evaluating it,
  /// unless the state was adopted from an accepted trial: Search has read its split).
  void ReadSplit(StageProblem& problem);
  /// Whether the current state has independent parts the search steps separately.
  bool Split() const { return split_; }

  /// A blockwise shortening `limited` of the Newton direction d made a descent direction of Φ:
  /// where a part's share (the whole step's, finally) has g·l >= 0, the part takes d scaled by
  /// the smallest fraction its dofs were shortened to (never the unshortened d).
  void KeepDescent(const Eigen::VectorXd& g, const Eigen::VectorXd& d, Eigen::VectorXd* limited);

  /// Searches along `dir` from the problem's current state (left unchanged: the caller commits
  /// *step). *step is the last trial's step, *trialVector / *trialMatrix its gradient and Hessian
  /// (Potential) or residual and Jacobian (ResidualSquared) as far as evaluated.
  Summary Search(StageProblem& problem, const Start& start, const Eigen::VectorXd& dir,
                 Eigen::VectorXd* step, Eigen::VectorXd* trialVector,
                 Eigen::SparseMatrix<double>* trialMatrix);

 private:
  /// The trial's merit; *withDerivatives where it was evaluated with them.
  double EvaluateTrial(StageProblem& problem, const Start& start, bool derivatives,
                       const Eigen::VectorXd& step, Eigen::VectorXd* trialVector,
                       Eigen::SparseMatrix<double>* trialMatrix, bool* withDerivatives);
  /// The Armijo or round-off test of one step length for all dofs.
  bool Accepts(const Start& start, double alpha, double trialMerit) const;
  bool UsesParts() const { return options_.byParts && options_.kind != LineSearchKind::None; }

  Options options_;
  PartLineSearch parts_;
  bool split_ = false;
  Eigen::VectorXd linearized_;  // J p (Start::jacobian), by parts
};

}  // namespace superdex
