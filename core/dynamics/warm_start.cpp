#include "core/dynamics/warm_start.h"


namespace superdex {

bool WarmStart(StageProblem& problem, Eigen::VectorXd d, double negligibleStep) {
  return WarmStart(problem, &d, negligibleStep);
}

bool WarmStart(StageProblem& problem, Eigen::VectorXd* step, double negligibleStep) {
  Eigen::VectorXd& d = *step;
  const int n = problem.NumDofs();
  if (n == 0 || d.size() != n || !d.allFinite() || problem.StepNorm(d) <= negligibleStep)
    return false;
  problem.LimitStep(&d);
  problem.Commit(d);
  return true;
}

bool WarmStart(StageProblem& problem, Eigen::VectorXd* step, Eigen::VectorXd* scratch,
               double negligibleStep, const std::vector<std::vector<int>>& unitDofs,
               const std::vector<char>& steady) {
  Eigen::VectorXd& d = *step;
  const int n = problem.NumDofs();
  if (n == 0 || d.size() != n || !d.allFinite() || problem.StepNorm(d) <= negligibleStep)
    return false;
  // `bounded` holds the moves of the units that did not move steadily and zero elsewhere (a zero
  // block lies inside any trust region), so that TrustStep shortens those units only.
  auto unsteady = [&](size_t k) { return k < steady.size() && !steady[k]; };
  Eigen::VectorXd& bounded = *scratch;
  bounded.setZero(n);
  bool any = false;
  for (size_t k = 0; k < unitDofs.size(); ++k) {
    if (!unsteady(k)) continue;
    for (int i : unitDofs[k])
      if (i >= 0) bounded[i] = d[i];
    any = true;
  }
  if (any && problem.TrustStep(&bounded)) {
    for (size_t k = 0; k < unitDofs.size(); ++k)
      if (unsteady(k))
        for (int i : unitDofs[k])
          if (i >= 0) d[i] = bounded[i];
  }
  problem.LimitStep(&d);
  problem.Commit(d);
  return true;
}

}  // namespace superdex
