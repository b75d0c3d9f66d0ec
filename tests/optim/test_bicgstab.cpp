// SolveBiCgStab (optim/bicgstab.h) against Eigen::BiCGSTAB on the same matrix and preconditioner:
// the same iterates bit for bit, the same iteration count and residual estimate, converged or
// stopped by the iteration cap, with a workspace reused across systems of different sizes.
#include <catch2/catch.hpp>
#include <random>

#include <Eigen/IterativeLinearSolvers>

#include "optim/bicgstab.h"
#include "random_sparse.h"

using namespace superdex;

using test::SameBits;

TEST_CASE("SolveBiCgStab: Eigen's BiCGSTAB iterates bit for bit, on a reused workspace",
          "[optim]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BiCgStabWorkspace work;  // one workspace for every system below
  struct Case {
    int n;
    double diagonal;  // smaller: harder systems, more iterations
    int maxIterations;
  };
  for (const Case c : {Case{12, 40.0, 200}, Case{600, 6.0, 200}, Case{3000, 4.0, 300},
                       Case{600, 6.0, 3}}) {  // the last one stops at its cap
    DYNAMIC_SECTION("n = " << c.n << ", diagonal " << c.diagonal << ", cap " << c.maxIterations) {
      const Eigen::SparseMatrix<double> A = test::RandomUnsymmetric(c.n, c.diagonal, 1e-2, &rng);
      Eigen::VectorXd b(c.n);
      for (int i = 0; i < c.n; ++i) b[i] = u(rng);
      RowOperator op;
      op.Set(A);
      BlockJacobi M;
      M.compute(A);
      const double tolerance = 1e-10;
      Eigen::VectorXd x = Eigen::VectorXd::Constant(3, 1.0);  // resized and zeroed by the solve
      const BiCgStabResult result = SolveBiCgStab(op, M, b, tolerance, c.maxIterations, &x, &work);

      Eigen::BiCGSTAB<Eigen::SparseMatrix<double>, BlockJacobi> reference;
      reference.setTolerance(tolerance);
      reference.setMaxIterations(c.maxIterations);
      reference.compute(A);
      const Eigen::VectorXd xRef = reference.solve(b);
      CHECK(result.iterations == reference.iterations());
      CHECK(result.relativeResidual == reference.error());
      CHECK(SameBits(x, xRef));
      if (c.maxIterations > 3) {
        CHECK(result.converged);
        CHECK(result.iterations > 1);
        INFO("iterations " << result.iterations);
        CHECK((A * x - b).norm() <= 1e-9 * b.norm());
      } else {
        CHECK_FALSE(result.converged);
        CHECK(result.iterations == c.maxIterations);
        CHECK(result.relativeResidual > tolerance);
      }
      // Solving again on the reused workspace repeats the bits.
      Eigen::VectorXd again;
      const BiCgStabResult second = SolveBiCgStab(op, M, b, tolerance, c.maxIterations, &again, &work);
      CHECK(second.iterations == result.iterations);
      CHECK(SameBits(again, x));
      // b = 0: x = 0 at once.
      const BiCgStabResult zero =
          SolveBiCgStab(op, M, Eigen::VectorXd::Zero(c.n), tolerance, c.maxIterations, &x, &work);
      CHECK(zero.converged);
      CHECK(zero.iterations == 0);
      CHECK(x.size() == c.n);
      CHECK(x.isZero(0.0));
    }
  }
}
