#include <catch2/catch.hpp>
#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "optim/block_jacobi.h"
#include "seeded_random.h"
#include "optim/linear_solver.h"

using namespace superdex;

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Weighted graph Laplacian of a random graph on n nodes (a path through all nodes plus `extra`
// random edges) plus a positive diagonal: symmetric positive definite, full storage.
SparseMatrix RandomSpd(int n, int extra, std::mt19937& rng, double diagonalShift = 0.1) {
  std::uniform_int_distribution<int> node(0, n - 1);
  std::uniform_real_distribution<double> weight(0.1, 2.0);
  std::vector<Eigen::Triplet<double>> t;
  auto edge = [&](int i, int j) {
    if (i == j) return;
    const double w = weight(rng);
    t.emplace_back(i, i, w);
    t.emplace_back(j, j, w);
    t.emplace_back(i, j, -w);
    t.emplace_back(j, i, -w);
  };
  for (int i = 0; i + 1 < n; ++i) edge(i, i + 1);
  for (int e = 0; e < extra; ++e) edge(node(rng), node(rng));
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, diagonalShift * weight(rng));
  SparseMatrix H(n, n);
  H.setFromTriplets(t.begin(), t.end());
  H.makeCompressed();
  return H;
}

// Same pattern as H, new values: off-diagonal weights rescaled, diagonal made dominant again.
SparseMatrix NewValuesSamePattern(const SparseMatrix& H, std::mt19937& rng) {
  std::uniform_real_distribution<double> factor(0.5, 1.5);
  SparseMatrix A = H;
  // Symmetric rescaling: scale (i, j) and (j, i) by the same factor.
  const Eigen::Index n = A.rows();
  std::vector<double> offSum(n, 0.0);
  for (Eigen::Index k = 0; k < n; ++k)
    for (SparseMatrix::InnerIterator e(A, k); e; ++e)
      if (e.row() > e.col()) {
        const double s = factor(rng);
        e.valueRef() *= s;
        A.coeffRef(e.col(), e.row()) *= s;
      }
  for (Eigen::Index k = 0; k < n; ++k)
    for (SparseMatrix::InnerIterator e(A, k); e; ++e)
      if (e.row() != e.col()) offSum[e.row()] += std::abs(e.value());
  for (Eigen::Index k = 0; k < n; ++k) A.coeffRef(k, k) = offSum[k] + factor(rng);
  return A;
}

double RelativeResidual(const SparseMatrix& H, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  return (H * x - b).norm() / b.norm();
}

}  // namespace

TEST_CASE("CHOLMOD solves random sparse SPD systems", "[optim]") {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const SparseMatrix H = RandomSpd(200, 400, rng);
    const Eigen::VectorXd b = test::UniformVector(200, rng);
    SymmetricSolver solver;
    REQUIRE(solver.Factorize(H));
    CHECK(std::string(solver.Backend()) == "cholmod");
    const Eigen::VectorXd x = solver.Solve(b);
    CHECK(RelativeResidual(H, x, b) <= 1e-10);
  }
}

TEST_CASE("a second factorization with the same pattern reuses the analysis", "[optim]") {
  std::mt19937 rng(11);
  const SparseMatrix H1 = RandomSpd(200, 300, rng);
  const SparseMatrix H2 = NewValuesSamePattern(H1, rng);
  REQUIRE(H2.nonZeros() == H1.nonZeros());
  REQUIRE((H2 - H1).norm() > 1e-3 * H1.norm());
  const Eigen::VectorXd b = test::UniformVector(200, rng);

  SymmetricSolver reused;
  REQUIRE(reused.Factorize(H1));
  const Eigen::VectorXd x1 = reused.Solve(b);
  REQUIRE(reused.Factorize(H2));
  CHECK(std::string(reused.Backend()) == "cholmod");
  const Eigen::VectorXd x2 = reused.Solve(b);

  SymmetricSolver fresh;
  REQUIRE(fresh.Factorize(H2));
  const Eigen::VectorXd x2Fresh = fresh.Solve(b);

  CHECK(RelativeResidual(H1, x1, b) <= 1e-10);
  CHECK(RelativeResidual(H2, x2, b) <= 1e-10);
  CHECK((x2 - x2Fresh).norm() <= 1e-12 * x2Fresh.norm());
  CHECK((x2 - x1).norm() > 1e-6 * x1.norm());  // the new values were really used

  // Back to the first values: same answer as the first solve.
  REQUIRE(reused.Factorize(H1));
  CHECK((reused.Solve(b) - x1).norm() <= 1e-12 * x1.norm());
}

TEST_CASE("a different pattern triggers a new analysis", "[optim]") {
  std::mt19937 rng(3);
  SymmetricSolver solver;
  for (int n : {50, 120, 120}) {
    const SparseMatrix H = RandomSpd(n, 2 * n, rng);
    const Eigen::VectorXd b = test::UniformVector(n, rng);
    REQUIRE(solver.Factorize(H));
    CHECK(RelativeResidual(H, solver.Solve(b), b) <= 1e-10);
  }
}

TEST_CASE("small systems: the dense Cholesky, with fixed sizes for one rigid body", "[optim]") {
  // n = 6 (one rigid body) takes the compile-time-size factorization, n = 5 and 12 the dynamic
  // one; all solve to round-off, and a 6 × 6 indefinite matrix is rejected as before.
  std::mt19937 rng(11);
  for (int n : {5, 6, 12}) {
    DYNAMIC_SECTION("n = " << n) {
      const SparseMatrix H = RandomSpd(n, 2 * n, rng);
      const Eigen::VectorXd b = test::UniformVector(n, rng);
      SymmetricSolver solver;
      REQUIRE(solver.Factorize(H));
      CHECK(std::string(solver.Backend()) == "dense");
      const Eigen::VectorXd x = solver.Solve(b);
      CHECK(RelativeResidual(H, x, b) <= 1e-13);
      const Eigen::VectorXd reference = Eigen::MatrixXd(H).llt().solve(b);
      CHECK((x - reference).norm() <= 1e-12 * reference.norm());
      SparseMatrix indefinite = H;
      indefinite.coeffRef(n / 2, n / 2) = -1.0;
      CHECK_FALSE(solver.Factorize(indefinite));
      CHECK(std::string(solver.Backend()) == "none");
      CHECK_FALSE(solver.Solve(b).allFinite());
      REQUIRE(solver.Factorize(H));
      CHECK(RelativeResidual(H, solver.Solve(b), b) <= 1e-13);
    }
  }
}

TEST_CASE("an indefinite matrix is rejected, and the solver recovers", "[optim]") {
  std::mt19937 rng(5);
  const SparseMatrix H = RandomSpd(200, 400, rng);
  SparseMatrix indefinite = H;
  indefinite.coeffRef(100, 100) = -1.0;  // same pattern, one negative pivot
  SymmetricSolver solver;
  CHECK_FALSE(solver.Factorize(indefinite));
  CHECK(std::string(solver.Backend()) == "none");
  CHECK_FALSE(solver.Solve(Eigen::VectorXd::Ones(200)).allFinite());

  // Negative definite and singular matrices too.
  CHECK_FALSE(solver.Factorize(SparseMatrix(-H)));
  // A pure graph Laplacian (no diagonal shift) is singular: the constant vector is in its kernel.
  const SparseMatrix laplacian = RandomSpd(60, 100, rng, 0.0);
  CHECK_FALSE(solver.Factorize(laplacian));

  // The same pattern with positive definite values factorizes again after the failures.
  const Eigen::VectorXd b = test::UniformVector(200, rng);
  REQUIRE(solver.Factorize(H));
  CHECK(std::string(solver.Backend()) == "cholmod");
  CHECK(RelativeResidual(H, solver.Solve(b), b) <= 1e-10);
}

TEST_CASE("non-finite entries and uncompressed input", "[optim]") {
  std::mt19937 rng(9);
  SparseMatrix H = RandomSpd(40, 60, rng);
  SymmetricSolver solver;
  SparseMatrix bad = H;
  bad.coeffRef(3, 3) = std::numeric_limits<double>::quiet_NaN();
  CHECK_FALSE(solver.Factorize(bad));

  SparseMatrix uncompressed = H;
  uncompressed.uncompress();
  REQUIRE_FALSE(uncompressed.isCompressed());
  const Eigen::VectorXd b = test::UniformVector(40, rng);
  REQUIRE(solver.Factorize(uncompressed));
  CHECK(RelativeResidual(H, solver.Solve(b), b) <= 1e-10);
}

TEST_CASE("Krylov solves: conjugate gradients and BiCGSTAB agree with the direct solves",
          "[optim]") {
  std::mt19937 rng(11);
  LinearSolverSettings iterative;
  iterative.kind = LinearSolverKind::Iterative;
  iterative.tolerance = 1e-10;
  for (int trial = 0; trial < 3; ++trial) {
    const SparseMatrix H = RandomSpd(400, 800, rng, 5.0);
    const Eigen::VectorXd b = test::UniformVector(400, rng);
    SymmetricSolver direct, krylov;
    krylov.SetSettings(iterative);
    REQUIRE(direct.Factorize(H));
    REQUIRE(krylov.Factorize(H));
    CHECK(std::string(krylov.Backend()) == "pcg");
    const Eigen::VectorXd x = krylov.Solve(b);
    CHECK(krylov.LastSolve().iterative);
    CHECK(!krylov.LastSolve().fellBack);
    CHECK(krylov.LastSolve().iterations > 1);
    CHECK(RelativeResidual(H, x, b) <= 1e-10);
    const Eigen::VectorXd xd = direct.Solve(b);
    CHECK((x - xd).norm() <= 1e-8 * xd.norm());
    // An unsymmetric perturbation of the same pattern: BiCGSTAB against UMFPACK.
    SparseMatrix J = H;
    for (Eigen::Index k = 0; k < J.outerSize(); ++k)
      for (SparseMatrix::InnerIterator e(J, k); e; ++e)
        if (e.row() > e.col()) e.valueRef() *= 1.3;
    UnsymmetricSolver lu, bicg;
    bicg.SetSettings(iterative);
    REQUIRE(lu.Factorize(J));
    REQUIRE(bicg.Factorize(J));
    const Eigen::VectorXd y = bicg.Solve(b);
    CHECK(bicg.LastSolve().iterative);
    CHECK(!bicg.LastSolve().fellBack);
    CHECK(RelativeResidual(J, y, b) <= 1e-9);
    CHECK((y - lu.Solve(b)).norm() <= 1e-8 * y.norm());
  }
}

TEST_CASE("Krylov solves: too few iterations fall back to the direct solve; indefinite matrices "
          "are reported as a failed Cholesky would be", "[optim]") {
  std::mt19937 rng(12);
  const SparseMatrix H = RandomSpd(300, 300, rng, 1e-3);  // ill-conditioned
  const Eigen::VectorXd b = test::UniformVector(300, rng);
  LinearSolverSettings few;
  few.kind = LinearSolverKind::Iterative;
  few.maxIterations = 3;
  SymmetricSolver s;
  s.SetSettings(few);
  REQUIRE(s.Factorize(H));
  const Eigen::VectorXd x = s.Solve(b);
  CHECK(s.LastSolve().fellBack);
  CHECK(s.LastSolve().iterations == 3);
  CHECK(RelativeResidual(H, x, b) <= 1e-10);
  UnsymmetricSolver u;
  u.SetSettings(few);
  REQUIRE(u.Factorize(H));
  const Eigen::VectorXd y = u.Solve(b);
  CHECK(u.LastSolve().fellBack);
  CHECK(RelativeResidual(H, y, b) <= 1e-10);
  // Indefinite: positive definite 3x3 diagonal blocks, but a direction of negative curvature
  // through the coupling of two blocks.
  SparseMatrix A = H;
  A.coeffRef(0, 3) = A.coeffRef(3, 0) = 10.0 * std::max(A.coeff(0, 0), A.coeff(3, 3));
  few.maxIterations = 500;
  s.SetSettings(few);
  REQUIRE(s.Factorize(A));
  CHECK(!s.Solve(b).allFinite());
  // A non-positive diagonal entry is rejected at once.
  A = H;
  A.coeffRef(5, 5) = -1.0;
  CHECK(!s.Factorize(A));
  // Auto: direct below kAutoIterativeUnknowns.
  LinearSolverSettings automatic;
  automatic.kind = LinearSolverKind::Auto;
  s.SetSettings(automatic);
  REQUIRE(s.Factorize(H));
  CHECK(std::string(s.Backend()) == "cholmod");
}

TEST_CASE("linear solver settings are validated with the scene file's names", "[optim]") {
  LinearSolverSettings s;
  CHECK(Validate(s).empty());
  s.tolerance = 0.0;
  CHECK(Validate(s) == "linear_tolerance: must be in (0, 1), got 0");
  s.tolerance = 1e-8;
  s.maxIterations = 0;
  CHECK(Validate(s) == "linear_max_iterations: must be >= 1, got 0");
  LinearSolverKind k;
  CHECK(ParseLinearSolverKind("iterative", &k));
  CHECK(k == LinearSolverKind::Iterative);
  CHECK(!ParseLinearSolverKind("cg", &k));
}

TEST_CASE("block-Jacobi preconditioner: exact on a 3x3-block-diagonal matrix", "[optim]") {
  std::mt19937 rng(5);
  std::normal_distribution<double> n01;
  const int blocks = 50;
  std::vector<Eigen::Triplet<double>> t;
  for (int b = 0; b < blocks; ++b) {
    Eigen::Matrix3d M;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) M(i, j) = n01(rng);
    const Eigen::Matrix3d S = M * M.transpose() + 0.1 * Eigen::Matrix3d::Identity();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) t.emplace_back(3 * b + i, 3 * b + j, S(i, j));
  }
  SparseMatrix H(3 * blocks, 3 * blocks);
  H.setFromTriplets(t.begin(), t.end());
  H.makeCompressed();
  const Eigen::VectorXd b = test::UniformVector(3 * blocks, rng);
  BlockJacobi P;
  P.compute(H);
  CHECK(P.PositiveDefinite());
  CHECK(RelativeResidual(H, P.solve(b), b) < 1e-12);
  // Conjugate gradients with it: one iteration.
  LinearSolverSettings iterative;
  iterative.kind = LinearSolverKind::Iterative;
  SymmetricSolver s;
  s.SetSettings(iterative);
  REQUIRE(s.Factorize(H));
  CHECK(RelativeResidual(H, s.Solve(b), b) < 1e-12);
  CHECK(s.LastSolve().iterations == 1);
  // An indefinite diagonal block is reported.
  H.coeffRef(0, 0) = -1.0;
  P.compute(H);
  CHECK(!P.PositiveDefinite());
  CHECK(!s.Factorize(H));
}

TEST_CASE("block-Jacobi preconditioner: one 6x6 block per rigid body, 3x3 blocks after them",
          "[optim]") {
  // k rigid bodies (6×6 blocks, translation and rotation coupled) then soft nodes (3×3 blocks).
  std::mt19937 rng(8);
  std::normal_distribution<double> n01;
  const int bodies = 40, nodes = 30;
  const int n = 6 * bodies + 3 * nodes;
  std::vector<Eigen::Triplet<double>> t;
  auto addBlock = [&](int offset, int size) {
    Eigen::MatrixXd M(size, size);
    for (int i = 0; i < size; ++i)
      for (int j = 0; j < size; ++j) M(i, j) = n01(rng);
    const Eigen::MatrixXd S = M * M.transpose() + 0.1 * Eigen::MatrixXd::Identity(size, size);
    for (int i = 0; i < size; ++i)
      for (int j = 0; j < size; ++j) t.emplace_back(offset + i, offset + j, S(i, j));
  };
  for (int b = 0; b < bodies; ++b) addBlock(6 * b, 6);
  for (int v = 0; v < nodes; ++v) addBlock(6 * bodies + 3 * v, 3);
  SparseMatrix H(n, n);
  H.setFromTriplets(t.begin(), t.end());
  H.makeCompressed();
  const Eigen::VectorXd b = test::UniformVector(n, rng);
  BlockJacobi P;
  P.SetLayout(DofBlockLayout::LeadingSix(bodies));
  P.compute(H);
  CHECK(P.PositiveDefinite());
  CHECK(RelativeResidual(H, P.solve(b), b) < 1e-12);
  // Without the layout the 3×3 blocks split each body's translation from its rotation: no longer
  // the inverse.
  BlockJacobi P3;
  P3.compute(H);
  CHECK(P3.PositiveDefinite());
  CHECK(RelativeResidual(H, P3.solve(b), b) > 1e-3);
  // Conjugate gradients and BiCGSTAB: one iteration with the layout, more without.
  LinearSolverSettings iterative;
  iterative.kind = LinearSolverKind::Iterative;
  for (int k : {bodies, 0}) {
    SymmetricSolver s;
    s.SetSettings(iterative);
    s.SetBlockLayout(DofBlockLayout::LeadingSix(k));
    REQUIRE(s.Factorize(H));
    CHECK(RelativeResidual(H, s.Solve(b), b) < 1e-8);
    UnsymmetricSolver u;
    u.SetSettings(iterative);
    u.SetBlockLayout(DofBlockLayout::LeadingSix(k));
    REQUIRE(u.Factorize(H));
    CHECK(RelativeResidual(H, u.Solve(b), b) < 1e-8);
    CHECK(!s.LastSolve().fellBack);
    CHECK(!u.LastSolve().fellBack);
    if (k == bodies) {
      CHECK(s.LastSolve().iterations == 1);
      CHECK(u.LastSolve().iterations <= 1);
    } else {
      CHECK(s.LastSolve().iterations > 1);
      CHECK(u.LastSolve().iterations > 1);
    }
  }
  // A layout that does not fit the matrix (more bodies than unknowns) falls back to the diagonal.
  BlockJacobi P7;
  P7.SetLayout(DofBlockLayout::LeadingSix(n));
  P7.compute(H);
  CHECK(P7.PositiveDefinite());
  const Eigen::VectorXd z = P7.solve(b);
  for (int i = 0; i < n; ++i) CHECK(z[i] == Approx(b[i] / H.coeff(i, i)).epsilon(1e-14));
  // An indefinite 6×6 block is reported.
  SparseMatrix Hi = H;
  Hi.coeffRef(7, 7) = -1.0;
  P.compute(Hi);
  CHECK(!P.PositiveDefinite());
}

TEST_CASE("transposed solves with the LU factors: sparse LU, dense and after an iterative "
          "factorization", "[optim]") {
  std::mt19937 rng(21);
  for (int n : {30, 400}) {  // dense LU below 48 unknowns, the sparse LU above
    SparseMatrix J = RandomSpd(n, 3 * n, rng);
    for (Eigen::Index k = 0; k < J.outerSize(); ++k)
      for (SparseMatrix::InnerIterator e(J, k); e; ++e)
        if (e.row() > e.col()) e.valueRef() *= 1.7;  // unsymmetric
    const SparseMatrix Jt = J.transpose();
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
    UnsymmetricSolver lu;
    REQUIRE(lu.Factorize(J));
    const Eigen::VectorXd x = lu.SolveTransposed(b);
    CHECK(RelativeResidual(Jt, x, b) <= 1e-12);
    CHECK(RelativeResidual(Jt, lu.Solve(b), b) > 1e-3);  // not the plain solve
    LinearSolverSettings iterative;
    iterative.kind = LinearSolverKind::Iterative;
    UnsymmetricSolver bicg;
    bicg.SetSettings(iterative);
    REQUIRE(bicg.Factorize(J));
    CHECK(RelativeResidual(Jt, bicg.SolveTransposed(b), b) <= 1e-12);
  }
}

TEST_CASE("unsymmetric LU: KLU on a sparse contact graph, UMFPACK on a filling mesh; solves, "
          "transposed solves and singular matrices on both", "[optim]") {
  std::mt19937 rng(31);
  // A contact graph: 300 bodies, each touching a few near neighbours (a geometric graph: its
  // factors stay sparse, where a random graph's fill in like a mesh's).
  std::vector<Eigen::Triplet<double>> g;
  std::uniform_int_distribution<int> near(1, 6);
  for (int a = 0; a < 300; ++a) {
    g.emplace_back(a, a, 10.0);
    for (int e = 0; e < 2; ++e) {
      const int b = a + near(rng);
      if (b >= 300) continue;
      g.emplace_back(a, b, -1.0);
      g.emplace_back(b, a, -1.0);
    }
  }
  SparseMatrix graph(300, 300);
  graph.setFromTriplets(g.begin(), g.end());
  graph.makeCompressed();
  // A mesh: a 3D grid of 9³ nodes with three unknowns each and every unknown of a node coupled
  // to those of its six neighbours (the block pattern of a tet mesh's stiffness; its factors
  // fill in).
  const int m = 9, nodes = m * m * m;
  std::vector<Eigen::Triplet<double>> t;
  auto id = [m](int i, int j, int k) { return (i * m + j) * m + k; };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        const int a = id(i, j, k);
        for (int c = 0; c < 3; ++c) t.emplace_back(3 * a + c, 3 * a + c, 30.0);
        const int next[3][3] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
        for (const auto& q : next) {
          if (q[0] >= m || q[1] >= m || q[2] >= m) continue;
          const int b = id(q[0], q[1], q[2]);
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
              t.emplace_back(3 * a + r, 3 * b + c, -0.5 - 0.1 * r);
              t.emplace_back(3 * b + c, 3 * a + r, -0.5 - 0.1 * r);
            }
        }
      }
  SparseMatrix mesh(3 * nodes, 3 * nodes);
  mesh.setFromTriplets(t.begin(), t.end());
  mesh.makeCompressed();
  for (const auto& [H, backend] : {std::pair<SparseMatrix, std::string>{graph, "klu"},
                                   std::pair<SparseMatrix, std::string>{mesh, "umfpack"}}) {
    SparseMatrix J = H;
    for (Eigen::Index k = 0; k < J.outerSize(); ++k)
      for (SparseMatrix::InnerIterator e(J, k); e; ++e)
        if (e.row() > e.col()) e.valueRef() *= 1.4;  // unsymmetric
    const SparseMatrix Jt = J.transpose();
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(J.rows(), -1.0, 2.0);
    UnsymmetricSolver lu;
    INFO(backend << ", " << J.rows() << " unknowns");
    REQUIRE(lu.Factorize(J));
    CHECK(std::string(lu.Backend()) == backend);
    CHECK(RelativeResidual(J, lu.Solve(b), b) <= 1e-12);
    CHECK(RelativeResidual(Jt, lu.SolveTransposed(b), b) <= 1e-12);
    // Singular (a zero column, same pattern): reported, and the next matrix factorizes again.
    SparseMatrix singular = J;
    for (SparseMatrix::InnerIterator e(singular, 7); e; ++e) e.valueRef() = 0.0;
    CHECK_FALSE(lu.Factorize(singular));
    REQUIRE(lu.Factorize(J));
    CHECK(RelativeResidual(J, lu.Solve(b), b) <= 1e-12);
  }
}
