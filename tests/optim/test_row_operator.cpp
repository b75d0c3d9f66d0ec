// RowOperator against Eigen's column-major sparse × dense product: the same bits, on the serial
// and the parallel path, and Eigen's BiCGSTAB routine on it against Eigen::BiCGSTAB on the
// matrix itself (same iterates, same iteration count).
#include <catch2/catch.hpp>
#include <random>

#include <Eigen/IterativeLinearSolvers>

#include "optim/block_jacobi.h"
#include "optim/row_operator.h"
#include "random_sparse.h"

using namespace superdex;

namespace {

using test::SameBits;

/// A diagonally dominant, unsymmetric sparse matrix.
Eigen::SparseMatrix<double> RandomMatrix(int n, std::mt19937* rng) {
  return test::RandomUnsymmetric(n, 40.0, 1e-3, rng);
}

}  // namespace

TEST_CASE("RowOperator: Eigen's column-major product bit for bit, serial and parallel",
          "[optim]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n : {10, 300, 5000}) {  // the last one above the parallel grain
    const Eigen::SparseMatrix<double> A = RandomMatrix(n, &rng);
    RowOperator op;
    op.Set(A);
    CHECK(op.RowGroups() == n);  // random rows: no two share a pattern
    Eigen::VectorXd x(n), b(n);
    for (int i = 0; i < n; ++i) {
      x[i] = u(rng);
      b[i] = u(rng);
    }
    DYNAMIC_SECTION("n = " << n) {
      Eigen::VectorXd y(n), yRef(n);
      y.noalias() = op * x;
      yRef.noalias() = A * x;
      CHECK(SameBits(y, yRef));
      Eigen::VectorXd assigned = Eigen::VectorXd::Constant(n, 7.0);  // Multiply overwrites
      op.Multiply(x.data(), assigned.data());
      CHECK(SameBits(assigned, yRef));
      // b − A x: Eigen subtracts a sparse matrix's product in place (what ScaleAndAdd with −1
      // does), but evaluates an operator's product into a temporary first; from x = 0 (every
      // solve's start) both give b.
      Eigen::VectorXd r = b;
      op.ScaleAndAdd(x.data(), -1.0, r.data());
      const Eigen::VectorXd rRef = b - A * x;
      CHECK(SameBits(r, rRef));
      Eigen::VectorXd z = b, zRef = b;
      op.ScaleAndAdd(x.data(), -0.37, z.data());
      zRef.noalias() += (-0.37) * (A * x);
      CHECK((z - zRef).norm() <= 1e-14 * zRef.norm());
      // Eigen's BiCGSTAB routine on the operator against the solver class on A.
      BlockJacobi precond;
      precond.compute(A);
      Eigen::VectorXd sol = Eigen::VectorXd::Zero(n);
      Eigen::Index iterations = 200;
      double error = 1e-10;
      REQUIRE(Eigen::internal::bicgstab(op, b, sol, precond, iterations, error));
      Eigen::BiCGSTAB<Eigen::SparseMatrix<double>, BlockJacobi> reference;
      reference.setTolerance(1e-10);
      reference.setMaxIterations(200);
      reference.compute(A);
      const Eigen::VectorXd solRef = reference.solve(b);
      CHECK(iterations == reference.iterations());
      CHECK(error == reference.error());
      CHECK(SameBits(sol, solRef));
      CHECK((A * sol - b).norm() <= 1e-9 * b.norm());
    }
  }
}

TEST_CASE("RowOperator: rows that share a pattern, summed in groups, bit for bit", "[optim]") {
  // Row blocks of 1 to 7 rows (7: a group of 6, then one), below and above the parallel grain.
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n : {40, 3000}) {
    const std::vector<int> sizes{3, 6, 1, 2, 5, 4, 7, 3};  // 31 rows in 9 groups
    const Eigen::SparseMatrix<double> A = test::RandomBlocked(n, sizes, &rng);
    RowOperator op;
    op.Set(A);
    CHECK(op.RowGroups() <= (n / 31 + 1) * 9);
    CHECK(op.RowGroups() >= n / 31 * 9);
    Eigen::VectorXd x(n), b(n);
    for (int i = 0; i < n; ++i) {
      x[i] = u(rng);
      b[i] = u(rng);
    }
    DYNAMIC_SECTION("n = " << n) {
      const Eigen::VectorXd yRef = A * x;
      Eigen::VectorXd y(n);
      op.Multiply(x.data(), y.data());
      CHECK(SameBits(y, yRef));
      Eigen::VectorXd r = b;
      op.ScaleAndAdd(x.data(), -1.0, r.data());
      const Eigen::VectorXd rRef = b - A * x;
      CHECK(SameBits(r, rRef));
    }
  }
}

TEST_CASE("RowOperator: new values on the same pattern, then a new pattern", "[optim]") {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 2500;
  Eigen::SparseMatrix<double> A = RandomMatrix(n, &rng);
  RowOperator op;
  op.Set(A);
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = u(rng);
  for (int round = 0; round < 2; ++round) {
    for (int k = 0; k < A.nonZeros(); ++k) A.valuePtr()[k] = u(rng);  // same pattern
    op.Set(A);
    Eigen::VectorXd y(n), yRef(n);
    y.noalias() = op * x;
    yRef.noalias() = A * x;
    CHECK(SameBits(y, yRef));
  }
  A = RandomMatrix(n, &rng);  // another pattern
  op.Set(A);
  Eigen::VectorXd y(n), yRef(n);
  y.noalias() = op * x;
  yRef.noalias() = A * x;
  CHECK(SameBits(y, yRef));
}
