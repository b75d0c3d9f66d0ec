#include "optim/part_line_search.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace superdex {

int PartLineSearch::Find(int u) {
  while (parent_[u] != u) {
    parent_[u] = parent_[parent_[u]];
    u = parent_[u];
  }
  return u;
}

void PartLineSearch::Unite(int a, int b) {
  a = Find(a);
  b = Find(b);
  if (a != b) parent_[std::max(a, b)] = std::min(a, b);  // the root is the smallest index
}

bool PartLineSearch::Label() {
  parts_ = 0;
  const int units = base_.units;
  if (units < 2 || static_cast<int>(base_.share.size()) != units) return false;
  parent_.resize(units);
  for (int u = 0; u < units; ++u) parent_[u] = u;
  for (const std::pair<int, int>& j : base_.joins) Unite(j.first, j.second);
  // Parts numbered in the order of their smallest unit (deterministic).
  partOfUnit_.assign(units, -1);
  for (int u = 0; u < units; ++u) {
    const int root = Find(u);
    if (partOfUnit_[root] < 0) partOfUnit_[root] = parts_++;
    partOfUnit_[u] = partOfUnit_[root];
  }
  // A part without a dof (a unit the problem reports with none) takes no step: it neither
  // holds back the reported step length nor makes a second part.
  partHasDofs_.assign(parts_, 0);
  for (int u : base_.unitOfDof) partHasDofs_[partOfUnit_[u]] = 1;
  return std::count(partHasDofs_.begin(), partHasDofs_.end(), 1) > 1;
}

bool PartLineSearch::Begin(StageProblem& problem) {
  parts_ = 0;
  return problem.LastSplit(&base_) && Label();
}

bool PartLineSearch::AdoptTrial() {
  std::swap(base_, trial_);
  return Label();
}

void PartLineSearch::StartMinimization(const Eigen::VectorXd& g, const Eigen::VectorXd& dir) {
  residual_ = false;
  alpha_.assign(parts_, 1.0);
  value_.assign(parts_, 0.0);
  slope_.assign(parts_, 0.0);
  double f = 0.0;
  for (int u = 0; u < base_.units; ++u) {
    value_[partOfUnit_[u]] += base_.share[u];
    f += base_.share[u];
  }
  for (Eigen::Index k = 0; k < dir.size(); ++k)
    slope_[partOfUnit_[base_.unitOfDof[k]]] += g[k] * dir[k];
  // g·d < 0 overall does not make every part's g_P·d_P negative (an indefinite exact Hessian, or
  // a step the problem shortened blockwise): such a part stays where it is this iteration.
  for (int p = 0; p < parts_; ++p)
    if (!(slope_[p] < 0.0)) {
      alpha_[p] = 0.0;
      slope_[p] = 0.0;
    }
  scale_ = std::abs(f);
}

double SmallestFraction(const Eigen::VectorXd& d, const Eigen::VectorXd& limited) {
  double fraction = 1.0;
  for (Eigen::Index k = 0; k < d.size(); ++k)
    if (d[k] != 0.0) fraction = std::min(fraction, limited[k] / d[k]);
  return fraction;
}

void PartLineSearch::PartFractions(const Eigen::VectorXd& d, const Eigen::VectorXd& limited) {
  partFraction_.assign(parts_, 1.0);
  for (Eigen::Index k = 0; k < d.size(); ++k)
    if (d[k] != 0.0) {
      const int p = partOfUnit_[base_.unitOfDof[k]];
      partFraction_[p] = std::min(partFraction_[p], limited[k] / d[k]);
    }
}

void PartLineSearch::ShortenByParts(const Eigen::VectorXd& g, const Eigen::VectorXd& d,
                                    Eigen::VectorXd* limited) {
  Eigen::VectorXd& l = *limited;
  PartFractions(d, l);
  partSlope_.assign(parts_, 0.0);
  for (Eigen::Index k = 0; k < d.size(); ++k)
    partSlope_[partOfUnit_[base_.unitOfDof[k]]] += g[k] * l[k];
  for (Eigen::Index k = 0; k < d.size(); ++k) {
    const int p = partOfUnit_[base_.unitOfDof[k]];
    if (!(partSlope_[p] < 0.0)) l[k] = partFraction_[p] * d[k];
  }
}

void PartLineSearch::CapSteps(const Eigen::VectorXd& d, const Eigen::VectorXd& limited) {
  PartFractions(d, limited);
  for (int p = 0; p < parts_; ++p) alpha_[p] = std::min(alpha_[p], partFraction_[p]);
}

void PartLineSearch::StartResidual(const Eigen::VectorXd& r, const Eigen::VectorXd& dir,
                                   const Eigen::VectorXd* linearized) {
  residual_ = true;
  alpha_.assign(parts_, 1.0);
  value_.assign(parts_, 0.0);
  slope_.assign(parts_, 0.0);
  partSlope_.assign(parts_, 0.0);  // r_P·(J dir)_P: dθ_P/dα at α = 0 (J is block diagonal by part)
  for (Eigen::Index k = 0; k < dir.size(); ++k) {
    const int p = partOfUnit_[base_.unitOfDof[k]];
    value_[p] += 0.5 * r[k] * r[k];
    slope_[p] += r[k] * dir[k];
    if (linearized) partSlope_[p] += r[k] * (*linearized)[k];
  }
  scale_ = 0.0;
  for (int p = 0; p < parts_; ++p) {
    slope_[p] = 0.5 * std::abs(slope_[p]);
    scale_ += value_[p];
    // Exact Newton gives r_P·(J d)_P = −2θ_P < 0; an inexact solve (the Krylov forcing term is
    // relative to the whole ‖r‖) can leave a part with a tiny residual no descent at all, whose
    // test no step length passes until the round-off band does. Such a part stays.
    if (linearized && !(partSlope_[p] < 0.0)) {
      alpha_[p] = 0.0;
      slope_[p] = 0.0;
    }
  }
}

void PartLineSearch::Step(const Eigen::VectorXd& dir, Eigen::VectorXd* step) const {
  step->resize(dir.size());
  for (Eigen::Index k = 0; k < dir.size(); ++k)
    (*step)[k] = alpha_[partOfUnit_[base_.unitOfDof[k]]] * dir[k];
}

void PartLineSearch::CutAll(double beta) {
  for (double& a : alpha_) a *= beta;
}

bool PartLineSearch::Test(StageProblem& problem, double trialValue, const Eigen::VectorXd* rTrial,
                          double c, double beta, double roundoff) {
  // Groups: the base parts joined by the trial's coupling terms (all one group when the trial
  // does not split).
  parent_.resize(parts_);
  for (int p = 0; p < parts_; ++p) parent_[p] = p;
  const bool split = problem.LastSplit(&trial_) && trial_.units == base_.units &&
                     static_cast<int>(trial_.share.size()) == base_.units;
  if (split) {
    for (const std::pair<int, int>& j : trial_.joins)
      Unite(partOfUnit_[j.first], partOfUnit_[j.second]);
  } else {
    for (int p = 1; p < parts_; ++p) parent_[p] = 0;
  }
  groupOf_.resize(parts_);
  for (int p = 0; p < parts_; ++p) groupOf_[p] = Find(p);
  groupTrial_.assign(parts_, 0.0);
  groupBase_.assign(parts_, 0.0);
  groupSlope_.assign(parts_, 0.0);
  // Per group: the trial's merit, the base merit, the predicted change Σ α_P slope_P and
  // (residual) the required decrease 2c Σ α_P θ_P(s).
  std::vector<double>& required = groupRequired_;
  required.assign(parts_, 0.0);
  if (residual_) {
    for (Eigen::Index k = 0; k < rTrial->size(); ++k) {
      const double rk = (*rTrial)[k];
      groupTrial_[groupOf_[partOfUnit_[base_.unitOfDof[k]]]] += 0.5 * rk * rk;
    }
  } else if (split) {
    for (int u = 0; u < base_.units; ++u)
      groupTrial_[groupOf_[partOfUnit_[u]]] += trial_.share[u];
  } else {
    groupTrial_[0] = trialValue;
  }
  for (int p = 0; p < parts_; ++p) {
    const int g = groupOf_[p];
    groupBase_[g] += value_[p];
    groupSlope_[g] += alpha_[p] * slope_[p];
    if (residual_) required[g] += 2.0 * c * alpha_[p] * value_[p];
  }
  const double band = roundoff * scale_;
  groupFails_.assign(parts_, 0);
  bool all = true;
  for (int p = 0; p < parts_; ++p) {
    if (groupOf_[p] != p) continue;  // not a group's root
    bool pass;
    if (residual_) {
      pass = std::isfinite(groupTrial_[p]) &&
             (groupTrial_[p] <= groupBase_[p] - required[p] ||
              (std::abs(groupTrial_[p] - groupBase_[p]) <= band && groupSlope_[p] <= band));
    } else {
      pass = std::isfinite(groupTrial_[p]) &&
             (groupTrial_[p] <= groupBase_[p] + c * groupSlope_[p] ||
              (std::abs(groupTrial_[p] - groupBase_[p]) <= band &&
               std::abs(groupSlope_[p]) <= band));
    }
    if (!pass) {
      groupFails_[p] = 1;
      all = false;
    }
  }
  if (all) return true;
  for (int p = 0; p < parts_; ++p)
    if (groupFails_[groupOf_[p]]) alpha_[p] *= beta;
  return false;
}

bool PartLineSearch::AllFull() const { return MinAlpha() == 1.0; }

double PartLineSearch::MinAlpha() const {
  double m = 1.0;
  for (int p = 0; p < parts_; ++p)
    if (partHasDofs_[p]) m = std::min(m, alpha_[p]);
  return m;
}

}  // namespace superdex
