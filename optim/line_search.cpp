#include "optim/line_search.h"

namespace superdex {

LineSearch::Start LineSearch::Start::Potential(double value, const Eigen::VectorXd& g,
                                               double slope, double newtonSlope) {
  Start s;
  s.merit = Merit::Potential;
  s.value = value;
  s.gradient = &g;
  s.slope = slope;
  s.newtonSlope = newtonSlope;
  return s;
}

LineSearch::Start LineSearch::Start::Residual(double theta, const Eigen::VectorXd& r,
                                              double decrement) {
  Start s;
  s.merit = Merit::ResidualSquared;
  s.value = theta;
  s.gradient = &r;
  s.decrement = decrement;
  return s;
}

void LineSearch::SetOptions(const Options& options) {
  options_ = options;
  split_ = false;
}

void LineSearch::ReadSplit(StageProblem& problem) {
  split_ = UsesParts() && parts_.Begin(problem);
}

void LineSearch::KeepDescent(const Eigen::VectorXd& g, const Eigen::VectorXd& d,
                             Eigen::VectorXd* limited) {
  if (split_) parts_.ShortenByParts(g, d, limited);
  if (!(g.dot(*limited) < 0.0)) *limited = SmallestFraction(d, *limited) * d;
}

double LineSearch::EvaluateTrial(StageProblem& problem, const Start& start, bool derivatives,
                                 const Eigen::VectorXd& step, Eigen::VectorXd* trialVector,
                                 Eigen::SparseMatrix<double>* trialMatrix, bool* withDerivatives) {
  if (start.merit == Merit::Potential) {
    // The exact Hessian, as the iteration after a full step tries first.
    double value = std::numeric_limits<double>::quiet_NaN();
    *withDerivatives = derivatives && problem.EvaluateAtStep(step, &value, trialVector,
                                                             trialMatrix, PsdProjection::None);
    if (!*withDerivatives) value = problem.Value(step);
    return value;
  }
  *withDerivatives = derivatives && problem.EvaluateResidualAtStep(step, trialVector, trialMatrix);
  if (!*withDerivatives) problem.Residual(step, trialVector);
  return 0.5 * trialVector->squaredNorm();
}

bool LineSearch::Accepts(const Start& start, double alpha, double trialMerit) const {
  const double c = options_.armijoConstant;
  const double m = start.value;
  const double band = kRoundoffBand * std::abs(m);
  if (start.merit == Merit::Potential)
    return trialMerit <= m + c * alpha * start.slope ||
           WithinRoundoff(trialMerit, m,
                          alpha * start.slope / start.newtonSlope * std::abs(start.newtonSlope),
                          band);
  return trialMerit <= (1.0 - 2.0 * c * alpha) * m ||
         WithinRoundoff(trialMerit, m, alpha * start.decrement, band);
}

LineSearch::Summary LineSearch::Search(StageProblem& problem, const Start& start,
                                       const Eigen::VectorXd& dir, Eigen::VectorXd* step,
                                       Eigen::VectorXd* trialVector,
                                       Eigen::SparseMatrix<double>* trialMatrix) {
  Summary s;
  const bool potential = start.merit == Merit::Potential;
  const bool none = options_.kind == LineSearchKind::None;
  const double beta = options_.backtrackFactor;
  const bool byParts = split_;  // never with LineSearchKind::None
  if (byParts) {
    if (potential) {
      parts_.StartMinimization(*start.gradient, dir);
    } else {
      const Eigen::VectorXd* linearized = nullptr;
      if (start.jacobian) {
        linearized_.noalias() = *start.jacobian * dir;
        linearized = &linearized_;
      }
      parts_.StartResidual(*start.gradient, dir, linearized);
    }
    if (start.firstStep) parts_.CapSteps(dir, *start.firstStep);
  } else if (start.firstStep) {
    s.alpha = SmallestFraction(dir, *start.firstStep);
  }
  const int trials = none ? 1 : options_.maxTrials;
  for (int trial = 0; trial < trials; ++trial) {
    if (byParts) {
      parts_.Step(dir, step);
    } else {
      step->noalias() = s.alpha * dir;  // no allocation: *step is preallocated
    }
    bool withDerivatives = false;
    s.trialMerit = EvaluateTrial(problem, start, trial == 0 && start.derivativesAtFirstTrial,
                                 *step, trialVector, trialMatrix, &withDerivatives);
    // Non-finite merits (e.g. an undefined state) are rejections; comparisons with NaN fail. By
    // parts, Test cuts the failing groups' step lengths itself.
    const bool finite = std::isfinite(s.trialMerit);
    const bool pass =
        finite && (byParts ? parts_.Test(problem, s.trialMerit, potential ? nullptr : trialVector,
                                         options_.armijoConstant, beta, kRoundoffBand)
                           : none || Accepts(start, s.alpha, s.trialMerit));
    if (pass) {
      s.accepted = true;
      if (withDerivatives) {
        s.withDerivatives = true;
        // The trial's split is the next state's.
        split_ = byParts ? parts_.AdoptTrial() : UsesParts() && parts_.Begin(problem);
      }
      break;
    }
    ++s.rejectedTrials;
    if (!byParts) {
      s.alpha *= beta;
    } else if (!finite) {
      parts_.CutAll(beta);
    }
  }
  if (byParts) s.alpha = s.accepted && parts_.AllFull() ? 1.0 : parts_.MinAlpha();
  return s;
}

}  // namespace superdex
