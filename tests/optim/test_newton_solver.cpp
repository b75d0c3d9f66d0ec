#include <catch2/catch.hpp>
#include <cmath>

#include "optim/newton_solver.h"

using namespace superdex;

namespace {

// Rosenbrock f = (1 − x)² + 100 (y − x²)² in R² with the plain retraction s ← s + d.
class Rosenbrock : public StageProblem {
 public:
  Eigen::Vector2d s{-1.2, 1.0};
  int NumDofs() const override { return 2; }
  double F(const Eigen::Vector2d& z) const {
    return (1 - z.x()) * (1 - z.x()) + 100 * std::pow(z.y() - z.x() * z.x(), 2);
  }
  double Value(const Eigen::VectorXd& d) override { return F(s + d); }
  double Evaluate(Eigen::VectorXd* g, Eigen::SparseMatrix<double>* H, PsdProjection) override {
    const double x = s.x(), y = s.y();
    g->resize(2);
    (*g) << -2 * (1 - x) - 400 * x * (y - x * x), 200 * (y - x * x);
    if (H) {
      Eigen::Matrix2d h;
      h << 2 - 400 * (y - x * x) + 800 * x * x, -400 * x, -400 * x, 200;
      H->resize(2, 2);
      std::vector<Eigen::Triplet<double>> t;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) t.emplace_back(i, j, h(i, j));
      H->setFromTriplets(t.begin(), t.end());
    }
    return F(s);
  }
  void Commit(const Eigen::VectorXd& d) override { s += d; }
};

}  // namespace

TEST_CASE("projected Newton reaches the Rosenbrock minimum", "[optim]") {
  Rosenbrock p;
  NonlinearSolverParams params;
  const SolverStats st = MinimizeNewton(p, params, 1.0);
  INFO(st.message << ", " << st.iterations << " iterations");
  CHECK(st.status == StageStatus::Converged);
  CHECK((p.s - Eigen::Vector2d(1, 1)).norm() < 1e-8);
}

TEST_CASE("an iteration cap is reported as Stopped, never Converged", "[optim]") {
  Rosenbrock p;
  NonlinearSolverParams params;
  params.maxIterations = 2;
  const SolverStats st = MinimizeNewton(p, params, 1.0);
  CHECK(st.status == StageStatus::Stopped);
  CHECK(st.iterations == 2);
}

TEST_CASE("solver parameters are validated by name", "[optim]") {
  NonlinearSolverParams p;
  CHECK(Validate(p).empty());
  p.maxIterations = 0;
  CHECK(Validate(p) == "max_iterations: must be >= 1, got 0");
  p = NonlinearSolverParams();
  p.armijoConstant = 1.5;
  CHECK(Validate(p) == "armijo_constant: must be in (0, 1), got 1.5");
}
