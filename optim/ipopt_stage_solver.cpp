#include "optim/ipopt_stage_solver.h"

#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>
#include <cmath>
#include <sstream>

namespace superdex {
namespace {

using Ipopt::Index;
using Ipopt::Number;

/// The stage as an Ipopt TNLP over the chart vector d (no constraints).
class StageTnlp : public Ipopt::TNLP {
 public:
  explicit StageTnlp(StageProblem* problem) : problem_(problem), n_(problem->NumDofs()) {}

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = n_;
    m = 0;
    nnz_jac_g = 0;
    nnz_h_lag = n_ * (n_ + 1) / 2;
    index_style = C_STYLE;
    return true;
  }
  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index, Number*, Number*) override {
    for (Index i = 0; i < n; ++i) {
      x_l[i] = -2e19;
      x_u[i] = 2e19;
    }
    return true;
  }
  bool get_starting_point(Index n, bool init_x, Number* x, bool, Number*, Number*, Index, bool,
                          Number*) override {
    if (init_x)
      for (Index i = 0; i < n; ++i) x[i] = 0.0;
    return true;
  }
  bool eval_f(Index n, const Number* x, bool, Number& obj_value) override {
    MoveTo(n, x);
    obj_value = problem_->Value(Eigen::VectorXd::Zero(n));
    ++evaluations_;
    return std::isfinite(obj_value);
  }
  bool eval_grad_f(Index n, const Number* x, bool, Number* grad_f) override {
    MoveTo(n, x);
    Eigen::VectorXd g;
    problem_->Evaluate(&g, nullptr, PsdProjection::None);
    const Eigen::VectorXd gc = problem_->ChartTangentMap(d_).transpose() * g;
    Eigen::Map<Eigen::VectorXd>(grad_f, n) = gc;
    return gc.allFinite();
  }
  bool eval_g(Index, const Number*, bool, Index, Number*) override { return true; }
  bool eval_jac_g(Index, const Number*, bool, Index, Index, Index*, Index*, Number*) override {
    return true;
  }
  bool eval_h(Index n, const Number* x, bool, Number obj_factor, Index, const Number*, bool,
              Index, Index* iRow, Index* jCol, Number* values) override {
    if (!values) {
      Index k = 0;
      for (Index i = 0; i < n; ++i)
        for (Index j = 0; j <= i; ++j, ++k) {
          iRow[k] = i;
          jCol[k] = j;
        }
      return true;
    }
    MoveTo(n, x);
    Eigen::VectorXd g;
    Eigen::SparseMatrix<double> H;
    problem_->Evaluate(&g, &H, PsdProjection::None);
    const Eigen::MatrixXd T = problem_->ChartTangentMap(d_);
    const Eigen::MatrixXd Hc = T.transpose() * Eigen::MatrixXd(H) * T;
    Index k = 0;
    for (Index i = 0; i < n; ++i)
      for (Index j = 0; j <= i; ++j, ++k) values[k] = obj_factor * 0.5 * (Hc(i, j) + Hc(j, i));
    return Hc.allFinite();
  }
  void finalize_solution(Ipopt::SolverReturn status, Index n, const Number* x, const Number*,
                         const Number*, Index, const Number*, const Number*, Number obj_value,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    MoveTo(n, x);
    status_ = status;
    final_ = obj_value;
  }

  Ipopt::SolverReturn status_ = Ipopt::UNASSIGNED;
  double final_ = 0.0;
  int evaluations_ = 0;

 private:
  void MoveTo(Index n, const Number* x) {
    d_ = Eigen::Map<const Eigen::VectorXd>(x, n);
    problem_->MoveInChart(d_);
  }
  StageProblem* problem_;
  Index n_;
  Eigen::VectorXd d_;
};

}  // namespace

SolverStats MinimizeIpopt(StageProblem& problem, const IpoptStageParams& params) {
  SolverStats st;
  st.status = StageStatus::Diverged;
  if (!problem.IsPotential()) {
    st.message = "ipopt minimizes potential stages only; this stage is not a potential (its "
                 "dissipation with explicit_normals = false, or an applied torque): use the "
                 "newton or ceres stage solver";
    return st;
  }
  if (!problem.SupportsChart()) {
    st.message = "ipopt: the stage problem provides no chart";
    return st;
  }
  if (problem.NumDofs() > kMaxIpoptDofs) {
    std::ostringstream s;
    s << "ipopt: " << problem.NumDofs() << " degrees of freedom exceed the dense-Hessian limit "
      << kMaxIpoptDofs << " of the check adapter";
    st.message = s.str();
    return st;
  }
  if (problem.NumDofs() == 0) {
    st.status = StageStatus::Converged;
    st.message = "no degrees of freedom";
    return st;
  }
  problem.SetChartOrigin();
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetStringValue("sb", "yes");
  app->Options()->SetNumericValue("tol", params.tolerance);
  app->Options()->SetNumericValue("acceptable_tol", params.tolerance);
  app->Options()->SetIntegerValue("max_iter", params.maxIterations);
  app->Options()->SetStringValue("nlp_scaling_method", "none");
  app->Options()->SetStringValue("hessian_approximation", "exact");
  if (app->Initialize() != Ipopt::Solve_Succeeded) {
    st.message = "ipopt: initialization failed";
    return st;
  }
  Ipopt::SmartPtr<StageTnlp> nlp = new StageTnlp(&problem);
  const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(nlp);
  st.iterations = IsValid(app->Statistics()) ? app->Statistics()->IterationCount() : 0;
  st.finalValue = nlp->final_;
  Eigen::VectorXd g;
  problem.Evaluate(&g, nullptr, PsdProjection::None);
  st.finalGradientNorm = g.lpNorm<Eigen::Infinity>();
  std::ostringstream s;
  s << "ipopt status " << static_cast<int>(status) << " after " << st.iterations
    << " iterations (|g|_inf = " << st.finalGradientNorm << ")";
  st.message = s.str();
  if (status == Ipopt::Solve_Succeeded || status == Ipopt::Solved_To_Acceptable_Level) {
    st.status = StageStatus::Converged;
  } else if (status == Ipopt::Maximum_Iterations_Exceeded) {
    st.status = StageStatus::Stopped;
  }
  return st;
}

}  // namespace superdex
