// The residual Newton solver (optim/residual_newton.h) on small synthetic problems: a smooth root
// is found (its last correction unchecked only in the quadratic regime), and a residual without a
// root (a kink at the merit's minimum) is reported as failed by its stagnation rule, early,
// instead of after the iteration cap.
#include <catch2/catch.hpp>
#include <cmath>

#include "optim/residual_newton.h"

using namespace superdex;

namespace {

/// r(x) = |x − c| + offset in one dimension, J = sign(x − c) (1 at the kink): with offset > 0 it
/// has no root, its merit ½ r² has a kink at its minimum x = c, and Newton's full step always
/// overshoots (to x − (x − c) − offset); only steps cut to α < 2|x − c| / (|x − c| + offset)
/// lower the merit.
class KinkedResidual : public StageProblem {
 public:
  KinkedResidual(double x0, double c, double offset) : x_(x0), c_(c), offset_(offset) {}
  int NumDofs() const override { return 1; }
  double Value(const Eigen::VectorXd& d) override {
    const double r = R(x_ + d[0]);
    return 0.5 * r * r;
  }
  double Evaluate(Eigen::VectorXd* g, Eigen::SparseMatrix<double>* H, PsdProjection) override {
    const double r = R(x_);
    g->setConstant(1, r * Slope(x_));
    if (H) {
      H->resize(1, 1);
      H->insert(0, 0) = 1.0;
      H->makeCompressed();
    }
    return 0.5 * r * r;
  }
  void Commit(const Eigen::VectorXd& d) override { x_ += d[0]; }
  bool IsPotential() const override { return false; }
  void Residual(const Eigen::VectorXd& d, Eigen::VectorXd* r) override {
    r->setConstant(1, R(x_ + d[0]));
  }
  void EvaluateResidual(Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J) override {
    r->setConstant(1, R(x_));
    J->resize(1, 1);
    J->insert(0, 0) = Slope(x_);
    J->makeCompressed();
  }
  double x() const { return x_; }

 private:
  double R(double x) const { return std::abs(x - c_) + offset_; }
  double Slope(double x) const { return x >= c_ ? 1.0 : -1.0; }
  double x_, c_, offset_;
};

/// r(x) = x³ + x − 2 (root x = 1, J = 3x² + 1 > 0): Newton converges quadratically; counts the
/// residual-only evaluations.
class SmoothCubic : public StageProblem {
 public:
  explicit SmoothCubic(double x0) : x_(x0) {}
  int NumDofs() const override { return 1; }
  double Value(const Eigen::VectorXd& d) override { return 0.5 * R(x_ + d[0]) * R(x_ + d[0]); }
  double Evaluate(Eigen::VectorXd* g, Eigen::SparseMatrix<double>*, PsdProjection) override {
    g->setConstant(1, R(x_) * (3 * x_ * x_ + 1));
    return Value(Eigen::VectorXd::Zero(1));
  }
  void Commit(const Eigen::VectorXd& d) override { x_ += d[0]; }
  bool IsPotential() const override { return false; }
  void Residual(const Eigen::VectorXd& d, Eigen::VectorXd* r) override {
    ++residualCalls;
    r->setConstant(1, R(x_ + d[0]));
  }
  void EvaluateResidual(Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J) override {
    r->setConstant(1, R(x_));
    J->resize(1, 1);
    J->insert(0, 0) = 3 * x_ * x_ + 1;
    J->makeCompressed();
  }
  double x() const { return x_; }
  int residualCalls = 0;

 private:
  static double R(double x) { return x * x * x + x - 2.0; }
  double x_;
};

}  // namespace

TEST_CASE("residual Newton: the last correction is taken unchecked only in the quadratic regime",
          "[optim]") {
  NonlinearSolverParams params;
  SECTION("from x = 3: full steps, the last one after a quadratic contraction") {
    SmoothCubic p(3.0);
    const SolverStats st = SolveResidualNewton(p, params, 1.0, nullptr);
    INFO(st.Message() << " after " << st.iterations << " iterations");
    CHECK(st.status == StageStatus::Converged);
    CHECK(st.lineSearchSteps == 0);
    CHECK(std::abs(p.x() - 1.0) < 1e-15);
    // One line-search trial per iteration but the last: the final correction costs no residual.
    CHECK(p.residualCalls == st.iterations - 1);
  }
  SECTION("converged at the start: the correction is checked") {
    SmoothCubic p(1.0 + 1e-14);
    const SolverStats st = SolveResidualNewton(p, params, 1.0, nullptr);
    CHECK(st.status == StageStatus::Converged);
    CHECK(st.iterations == 1);
    CHECK(p.residualCalls == 1);
    CHECK(std::abs(p.x() - 1.0) < 1e-15);
  }
}

TEST_CASE("residual Newton: a kinked residual without a root stagnates and is reported early",
          "[optim]") {
  NonlinearSolverParams params;
  SECTION("a root (offset 0): converged in one step") {
    KinkedResidual p(0.3, 0.1, 0.0);
    const SolverStats st = SolveResidualNewton(p, params, 1.0, nullptr);
    INFO(st.Message());
    CHECK(st.status == StageStatus::Converged);
    CHECK(std::abs(p.x() - 0.1) < 1e-12);
  }
  SECTION("no root (offset 1): Diverged by the stagnation rule, not the iteration cap") {
    KinkedResidual p(0.3, 0.1, 1.0);
    const SolverStats st = SolveResidualNewton(p, params, 1.0, nullptr);
    INFO(st.Message() << " after " << st.iterations << " iterations, " << st.lineSearchSteps
                      << " rejected trials");
    CHECK(st.status == StageStatus::Diverged);
    CHECK(st.Message().find("merit stagnation") != std::string::npos);
    // The merit still went down to its kink: x approaches c.
    CHECK(std::abs(p.x() - 0.1) < 1e-5);
    // Measured: 16 iterations and 203 rejected trials; without the rule 28 iterations and 599,
    // until a line search rejected all 40 of its trials.
    CHECK(st.iterations < params.maxIterations);
    CHECK(st.lineSearchSteps < 400);
  }
}
