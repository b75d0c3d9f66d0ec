// RowOperator against Eigen's column-major sparse × dense product: the same bits, on the serial
// and the parallel path, with rows summed one by one and in groups that share a pattern, and
// after new values and a new pattern.
#include <catch2/catch.hpp>
#include <random>

#include "optim/row_operator.h"
#include "random_sparse.h"

using namespace superdex;

namespace {

/// A diagonally dominant, unsymmetric sparse matrix.
Eigen::SparseMatrix<double> RandomMatrix(int n, std::mt19937* rng) {
  return test::RandomUnsymmetric(n, 40.0, 1e-3, rng);
}

Eigen::VectorXd RandomVector(int n, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = u(*rng);
  return x;
}

/// op's product of x, written over a vector of sevens, bit for bit Eigen's A x.
bool MultiplyIsEigensProduct(const RowOperator& op, const Eigen::SparseMatrix<double>& A,
                             const Eigen::VectorXd& x) {
  Eigen::VectorXd y = Eigen::VectorXd::Constant(x.size(), 7.0);
  op.Multiply(x.data(), y.data());
  const Eigen::VectorXd yRef = A * x;
  return test::SameBits(y, yRef);
}

}  // namespace

TEST_CASE("RowOperator: Eigen's column-major product bit for bit, serial and parallel",
          "[optim]") {
  std::mt19937 rng(5);
  for (int n : {10, 300, 5000}) {  // the last one above the parallel grain
    const Eigen::SparseMatrix<double> A = RandomMatrix(n, &rng);
    RowOperator op;
    op.Set(A);
    CHECK(op.RowGroups() == n);  // random rows: no two share a pattern
    const Eigen::VectorXd x = RandomVector(n, &rng);
    DYNAMIC_SECTION("n = " << n) { CHECK(MultiplyIsEigensProduct(op, A, x)); }
  }
}

TEST_CASE("RowOperator: rows that share a pattern, summed in groups, bit for bit", "[optim]") {
  // Row blocks of 1 to 7 rows (7: a group of 6, then one), below and above the parallel grain.
  std::mt19937 rng(21);
  for (int n : {40, 3000}) {
    const std::vector<int> sizes{3, 6, 1, 2, 5, 4, 7, 3};  // 31 rows in 9 groups
    const Eigen::SparseMatrix<double> A = test::RandomBlocked(n, sizes, &rng);
    RowOperator op;
    op.Set(A);
    CHECK(op.RowGroups() <= (n / 31 + 1) * 9);
    CHECK(op.RowGroups() >= n / 31 * 9);
    const Eigen::VectorXd x = RandomVector(n, &rng);
    DYNAMIC_SECTION("n = " << n) { CHECK(MultiplyIsEigensProduct(op, A, x)); }
  }
}

TEST_CASE("RowOperator: new values on the same pattern, then a new pattern", "[optim]") {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 2500;
  Eigen::SparseMatrix<double> A = RandomMatrix(n, &rng);
  RowOperator op;
  op.Set(A);
  const Eigen::VectorXd x = RandomVector(n, &rng);
  for (int round = 0; round < 2; ++round) {
    for (int k = 0; k < A.nonZeros(); ++k) A.valuePtr()[k] = u(rng);  // same pattern
    op.Set(A);
    CHECK(MultiplyIsEigensProduct(op, A, x));
  }
  A = RandomMatrix(n, &rng);  // another pattern
  op.Set(A);
  CHECK(MultiplyIsEigensProduct(op, A, x));
}
