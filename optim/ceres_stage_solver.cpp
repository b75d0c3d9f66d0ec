#include "optim/ceres_stage_solver.h"

#include <ceres/ceres.h>

#include <sstream>

namespace superdex {
namespace {

/// r(s₀ ⊕ d) with the Jacobian J(s₀ ⊕ d) T(d), one parameter block d of size n.
class StageResidual : public ceres::CostFunction {
 public:
  explicit StageResidual(StageProblem* problem) : problem_(problem), n_(problem->NumDofs()) {
    set_num_residuals(n_);
    mutable_parameter_block_sizes()->push_back(n_);
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Eigen::VectorXd d = Eigen::Map<const Eigen::VectorXd>(parameters[0], n_);
    problem_->MoveInChart(d);
    Eigen::VectorXd r;
    Eigen::SparseMatrix<double> J;
    const bool withJacobian = jacobians && jacobians[0];
    problem_->EvaluateResidual(&r, withJacobian ? &J : nullptr);
    if (r.size() != n_ || !r.allFinite()) return false;
    Eigen::Map<Eigen::VectorXd>(residuals, n_) = r;
    if (withJacobian) {
      using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
      Eigen::Map<RowMajor>(jacobians[0], n_, n_) =
          Eigen::MatrixXd(J) * problem_->ChartTangentMap(d);
    }
    return true;
  }

 private:
  StageProblem* problem_;
  int n_;
};

}  // namespace

SolverStats SolveCeres(StageProblem& problem, const CeresStageParams& params) {
  SolverStats st;
  st.status = StageStatus::Diverged;
  if (!problem.SupportsChart()) {
    st.message = "ceres: the stage problem provides no chart";
    return st;
  }
  const int n = problem.NumDofs();
  if (n > kMaxCeresDofs) {
    std::ostringstream s;
    s << "ceres: " << n << " degrees of freedom exceed the dense-Jacobian limit " << kMaxCeresDofs
      << " of the check adapter";
    st.message = s.str();
    return st;
  }
  if (n == 0) {
    st.status = StageStatus::Converged;
    st.message = "no degrees of freedom";
    return st;
  }
  problem.SetChartOrigin();
  std::vector<double> d(n, 0.0);
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem nls(po);
  nls.AddResidualBlock(new StageResidual(&problem), nullptr, d.data());
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.function_tolerance = params.functionTolerance;
  so.gradient_tolerance = params.gradientTolerance;
  so.parameter_tolerance = params.parameterTolerance;
  so.max_num_iterations = params.maxIterations;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  so.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &nls, &summary);
  problem.MoveInChart(Eigen::Map<const Eigen::VectorXd>(d.data(), n));
  Eigen::VectorXd r;
  problem.EvaluateResidual(&r, nullptr);
  st.iterations = static_cast<int>(summary.iterations.size());
  st.finalValue = 0.5 * r.squaredNorm();
  st.finalGradientNorm = r.lpNorm<Eigen::Infinity>();
  st.message = "ceres: " + summary.BriefReport();
  if (summary.termination_type == ceres::CONVERGENCE) {
    st.status = StageStatus::Converged;
  } else if (summary.termination_type == ceres::NO_CONVERGENCE) {
    st.status = StageStatus::Stopped;
  }
  return st;
}

}  // namespace superdex
