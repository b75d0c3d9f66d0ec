#include <catch2/catch.hpp>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "optim/finite_difference.h"
#include "optim/newton_solver.h"

using namespace superdex;

namespace {

/// Projects a symmetric matrix as `projection` says (eigenvalues clamped at 0 or made absolute).
Eigen::MatrixXd Project(const Eigen::MatrixXd& H, PsdProjection projection) {
  if (projection == PsdProjection::None) return H;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H);
  Eigen::VectorXd lambda = eig.eigenvalues();
  for (Eigen::Index i = 0; i < lambda.size(); ++i)
    lambda[i] = projection == PsdProjection::Clamp ? std::max(lambda[i], 0.0) : std::abs(lambda[i]);
  return eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
}

/// Full-storage sparse copy of a dense symmetric matrix; exact zeros are left out of the pattern
/// (so the solver also sees Hessians with structurally missing diagonal entries).
Eigen::SparseMatrix<double> ToSparse(const Eigen::MatrixXd& H) {
  return H.sparseView(0.0, 0.0);
}

/// A problem in R^n with the plain retraction x ← x + d. Records ‖g‖∞ at each Evaluate.
class EuclideanProblem : public StageProblem {
 public:
  explicit EuclideanProblem(Eigen::VectorXd x0) : x(std::move(x0)) {}
  virtual double F(const Eigen::VectorXd& z) const = 0;
  virtual Eigen::VectorXd Gradient(const Eigen::VectorXd& z) const = 0;
  virtual Eigen::MatrixXd Hessian(const Eigen::VectorXd& z) const = 0;

  int NumDofs() const override { return static_cast<int>(x.size()); }
  double Value(const Eigen::VectorXd& d) override {
    ++valueCalls;
    return F(x + d);
  }
  double Evaluate(Eigen::VectorXd* g, Eigen::SparseMatrix<double>* H,
                  PsdProjection projection) override {
    *g = Gradient(x);
    gradientNorms.push_back(g->lpNorm<Eigen::Infinity>());
    if (H) *H = ToSparse(Project(Hessian(x), projection));
    return F(x);
  }
  void Commit(const Eigen::VectorXd& d) override {
    ++commits;
    x += d;
  }

  Eigen::VectorXd x;
  std::vector<double> gradientNorms;
  int valueCalls = 0;
  int commits = 0;
};

/// f = Σ ½ a_i (x_i − c_i)², a_i > 0.
class SeparableQuadratic : public EuclideanProblem {
 public:
  SeparableQuadratic(Eigen::VectorXd a_, Eigen::VectorXd c_)
      : EuclideanProblem(Eigen::VectorXd::Zero(a_.size())), a(std::move(a_)), c(std::move(c_)) {}
  double F(const Eigen::VectorXd& z) const override {
    return 0.5 * (a.array() * (z - c).array().square()).sum();
  }
  Eigen::VectorXd Gradient(const Eigen::VectorXd& z) const override {
    return a.cwiseProduct(z - c);
  }
  Eigen::MatrixXd Hessian(const Eigen::VectorXd&) const override {
    return a.asDiagonal().toDenseMatrix();
  }
  Eigen::VectorXd a, c;
};

/// f = Σ cosh(x_i − c_i) + ½ κ Σ (x_{i+1} − x_i)²: strictly convex, not quadratic.
class CoshChain : public EuclideanProblem {
 public:
  CoshChain(Eigen::VectorXd c_, double kappa_)
      : EuclideanProblem(Eigen::VectorXd::Zero(c_.size())), c(std::move(c_)), kappa(kappa_) {}
  double F(const Eigen::VectorXd& z) const override {
    const Eigen::Index n = z.size();
    const Eigen::VectorXd diff = z.tail(n - 1) - z.head(n - 1);
    return (z - c).array().cosh().sum() + 0.5 * kappa * diff.squaredNorm();
  }
  Eigen::VectorXd Gradient(const Eigen::VectorXd& z) const override {
    const Eigen::Index n = z.size();
    Eigen::VectorXd g = (z - c).array().sinh().matrix();
    for (Eigen::Index i = 0; i + 1 < n; ++i) {
      const double t = kappa * (z[i + 1] - z[i]);
      g[i] -= t;
      g[i + 1] += t;
    }
    return g;
  }
  Eigen::MatrixXd Hessian(const Eigen::VectorXd& z) const override {
    const Eigen::Index n = z.size();
    Eigen::MatrixXd H = (z - c).array().cosh().matrix().asDiagonal();
    for (Eigen::Index i = 0; i + 1 < n; ++i) {
      H(i, i) += kappa;
      H(i + 1, i + 1) += kappa;
      H(i, i + 1) -= kappa;
      H(i + 1, i) -= kappa;
    }
    return H;
  }
  Eigen::VectorXd c;
  double kappa;
};

/// Rosenbrock f = (1 − x)² + 100 (y − x²)², minimum 0 at (1, 1).
class Rosenbrock : public EuclideanProblem {
 public:
  Rosenbrock() : EuclideanProblem(Eigen::Vector2d(-1.2, 1.0)) {}
  double F(const Eigen::VectorXd& z) const override {
    return std::pow(1 - z[0], 2) + 100 * std::pow(z[1] - z[0] * z[0], 2);
  }
  Eigen::VectorXd Gradient(const Eigen::VectorXd& z) const override {
    const double x = z[0], y = z[1];
    return Eigen::Vector2d(-2 * (1 - x) - 400 * x * (y - x * x), 200 * (y - x * x));
  }
  Eigen::MatrixXd Hessian(const Eigen::VectorXd& z) const override {
    const double x = z[0], y = z[1];
    Eigen::Matrix2d h;
    h << 2 - 400 * (y - x * x) + 800 * x * x, -400 * x, -400 * x, 200;
    return h;
  }
};

/// f = x⁴ + y⁴ + x y: indefinite near the origin, minima −1/8 at ±(½, −½). Its exact Hessian
/// [[12x², 1], [1, 12y²]] has no diagonal entry where x or y is 0.
class QuarticSaddle : public EuclideanProblem {
 public:
  QuarticSaddle() : EuclideanProblem(Eigen::Vector2d(0.0, 0.2)) {}
  double F(const Eigen::VectorXd& z) const override {
    return std::pow(z[0], 4) + std::pow(z[1], 4) + z[0] * z[1];
  }
  Eigen::VectorXd Gradient(const Eigen::VectorXd& z) const override {
    return Eigen::Vector2d(4 * std::pow(z[0], 3) + z[1], 4 * std::pow(z[1], 3) + z[0]);
  }
  Eigen::MatrixXd Hessian(const Eigen::VectorXd& z) const override {
    Eigen::Matrix2d h;
    h << 12 * z[0] * z[0], 1, 1, 12 * z[1] * z[1];
    return h;
  }
};

/// f = ½ (a + b) x² − c x as the sum of two "elements" ½ a x² (a > 0) and ½ b x² (b < 0), whose
/// Hessians are projected one by one, as a stage's local Hessians are: the projected Hessian is
/// a (the element b clamped to 0, Clamp) or a + |b| (Abs), the exact one a + b > 0. Records the
/// projection each evaluation asked for.
class ElementwiseQuadratic : public StageProblem {
 public:
  ElementwiseQuadratic(double a, double b, double c) : a(a), b(b), c(c) {}
  int NumDofs() const override { return 1; }
  double F(double z) const { return 0.5 * (a + b) * z * z - c * z; }
  double Value(const Eigen::VectorXd& d) override { return F(x + d[0]); }
  double Evaluate(Eigen::VectorXd* g, Eigen::SparseMatrix<double>* H,
                  PsdProjection projection) override {
    projections.push_back(projection);
    *g = Eigen::VectorXd::Constant(1, (a + b) * x - c);
    if (H) {
      const double hb = projection == PsdProjection::None  ? b
                        : projection == PsdProjection::Abs ? std::abs(b)
                                                           : std::max(b, 0.0);
      *H = ToSparse(Eigen::MatrixXd::Constant(1, 1, a + hb));
    }
    return F(x);
  }
  void Commit(const Eigen::VectorXd& d) override { x += d[0]; }

  double a, b, c, x = 0.0;
  std::vector<PsdProjection> projections;
};

/// A quadratic whose value is NaN everywhere except at the current state.
class NanOffStart : public SeparableQuadratic {
 public:
  NanOffStart() : SeparableQuadratic(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 1, 1)) {}
  double Value(const Eigen::VectorXd& d) override {
    ++valueCalls;
    return d.squaredNorm() == 0.0 ? F(x) : std::numeric_limits<double>::quiet_NaN();
  }
};

Eigen::Matrix3d Exp(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

/// f(R) = −tr(Aᵀ R) over R ∈ SO(3), retraction R ← exp([d]×) R. With B = R Aᵀ:
///   f(exp([d]×) R) = −tr(exp([d]×) B) = −tr(B) − tr([d]× B) − ½ tr([d]×² B) − O(|d|³),
///   tr([d]× B) = −d · vee(B − Bᵀ),  [d]×² = d dᵀ − |d|² I,
/// so the tangent gradient is g = vee(B − Bᵀ) = (B₂₁ − B₁₂, B₀₂ − B₂₀, B₁₀ − B₀₁) and the tangent
/// Hessian is H = tr(B) I − ½ (B + Bᵀ). The minimizer is the rotation polar factor of A.
class RotationAlignment : public StageProblem {
 public:
  RotationAlignment(Eigen::Matrix3d A_, Eigen::Matrix3d R0) : A(std::move(A_)), R(std::move(R0)) {}
  int NumDofs() const override { return 3; }
  double F(const Eigen::Matrix3d& Q) const { return -(A.transpose() * Q).trace(); }
  double Value(const Eigen::VectorXd& d) override { return F(Exp(d) * R); }
  double Evaluate(Eigen::VectorXd* g, Eigen::SparseMatrix<double>* H,
                  PsdProjection projection) override {
    const Eigen::Matrix3d B = R * A.transpose();
    *g = Eigen::Vector3d(B(2, 1) - B(1, 2), B(0, 2) - B(2, 0), B(1, 0) - B(0, 1));
    gradientNorms.push_back(g->lpNorm<Eigen::Infinity>());
    if (H) {
      const Eigen::Matrix3d h =
          B.trace() * Eigen::Matrix3d::Identity() - 0.5 * (B + B.transpose());
      *H = ToSparse(Project(h, projection));
    }
    return F(R);
  }
  void Commit(const Eigen::VectorXd& d) override { R = Exp(d) * R; }
  // Rotation angle of the step [rad] (a length in the unit-sphere sense).
  double StepNorm(const Eigen::VectorXd& d) const override { return d.norm(); }

  Eigen::Matrix3d A, R;
  std::vector<double> gradientNorms;
};

/// Tight tolerances, so that the convergence test that ends the solve is the decrement one.
NonlinearSolverParams TightParams() {
  NonlinearSolverParams p;
  p.absoluteTolerance = 1e-24;
  p.relativeTolerance = 0.0;
  p.stepTolerance = 0.0;
  return p;
}

std::string Describe(const SolverStats& st) {
  return std::string(ToString(st.status)) + " after " + std::to_string(st.iterations) +
         " iterations, " + std::to_string(st.lineSearchSteps) + " rejected trials, " +
         std::to_string(st.regularizations) + " regularizations: " + st.Message();
}

}  // namespace

TEST_CASE("a separable quadratic converges after one Newton step", "[optim]") {
  const Eigen::VectorXd a = (Eigen::VectorXd(6) << 1, 10, 100, 0.5, 3, 7).finished();
  const Eigen::VectorXd c = (Eigen::VectorXd(6) << 1, -2, 0.5, 4, -1, 3).finished();
  SeparableQuadratic p(a, c);
  const SolverStats st = MinimizeNewton(p, NonlinearSolverParams(), 1.0);
  INFO(Describe(st));
  CHECK(st.status == StageStatus::Converged);
  // Iteration 1 takes the exact step (α = 1 accepted at once); iteration 2 computes the second
  // direction, whose decrement passes the absolute test.
  CHECK(st.iterations == 2);
  CHECK(st.lineSearchSteps == 0);
  CHECK(st.regularizations == 0);
  CHECK(st.Message().find("Newton decrement") != std::string::npos);
  CHECK((p.x - c).lpNorm<Eigen::Infinity>() <= 1e-14);
  CHECK(st.finalValue <= 1e-28);
  CHECK(st.initialGradientNorm == Approx(a.cwiseProduct(c).lpNorm<Eigen::Infinity>()));
  CHECK(st.finalGradientNorm <= 1e-13);
  CHECK(st.assemblySeconds >= 0.0);
  CHECK(st.factorizationSeconds >= 0.0);
  CHECK(st.lineSearchSeconds >= 0.0);

  // One iteration alone already lands on the minimizer (but is reported as Stopped).
  SeparableQuadratic once(a, c);
  NonlinearSolverParams params;
  params.maxIterations = 1;
  const SolverStats st1 = MinimizeNewton(once, params, 1.0);
  CHECK(st1.status == StageStatus::Stopped);
  CHECK(st1.iterations == 1);
  CHECK((once.x - c).lpNorm<Eigen::Infinity>() <= 1e-14);
}

TEST_CASE("a start hinted to be local tries the exact Hessian at the first iteration", "[optim]") {
  // Exact curvature 3, projected 4: the projected first step leaves x at 3/4 of the way, and the
  // next iteration (exact after a full step) finishes: 3 iterations. With the hint the first step
  // is exact: 2 (the step, then the passing decrement test).
  const double c = 3.0;
  ElementwiseQuadratic plain(4.0, -1.0, c), hinted(4.0, -1.0, c);
  const SolverStats st0 = MinimizeNewton(plain, NonlinearSolverParams(), 1.0);
  NewtonStart start;
  start.exactHessian = true;
  const SolverStats st1 = MinimizeNewton(hinted, NonlinearSolverParams(), 1.0, nullptr, nullptr,
                                         start);
  INFO(Describe(st0) << " / " << Describe(st1));
  REQUIRE(st0.status == StageStatus::Converged);
  REQUIRE(st1.status == StageStatus::Converged);
  CHECK(st0.iterations == 3);
  CHECK(st1.iterations == 2);
  REQUIRE(!plain.projections.empty());
  REQUIRE(!hinted.projections.empty());
  CHECK(plain.projections[0] == PsdProjection::Clamp);
  CHECK(hinted.projections[0] == PsdProjection::None);
  CHECK(hinted.x == Approx(c / 3.0).epsilon(1e-14));
  CHECK(plain.x == Approx(c / 3.0).epsilon(1e-14));

  // Where the exact Hessian is indefinite (curvature 4 − 5 < 0) the hinted first iteration is
  // re-assembled projected: None, then Clamp. (This f is unbounded below; one iteration is run.)
  ElementwiseQuadratic indefinite(4.0, -5.0, c);
  NonlinearSolverParams once;
  once.maxIterations = 1;
  MinimizeNewton(indefinite, once, 1.0, nullptr, nullptr, start);
  REQUIRE(indefinite.projections.size() >= 2);
  CHECK(indefinite.projections[0] == PsdProjection::None);
  CHECK(indefinite.projections[1] == PsdProjection::Clamp);
}

TEST_CASE("a last correction below f's round-off is committed without evaluating f", "[optim]") {
  // f = F0 + Σ ½ a_i (x_i − c_i)² with F0 = 1e6: after the exact step the second direction
  // promises a decrease far below 1e-14 |f| = 1e-8, which f cannot resolve. The last correction
  // is committed without a value evaluation: one Value call in all (the first step's trial).
  const Eigen::VectorXd a = (Eigen::VectorXd(3) << 2, 30, 0.7).finished();
  const Eigen::VectorXd c = (Eigen::VectorXd(3) << 1, -2, 0.5).finished();
  class Offset : public SeparableQuadratic {
   public:
    using SeparableQuadratic::SeparableQuadratic;
    double F(const Eigen::VectorXd& z) const override { return 1e6 + SeparableQuadratic::F(z); }
  };
  Offset p(a, c);
  const SolverStats st = MinimizeNewton(p, NonlinearSolverParams(), 1.0);
  INFO(Describe(st));
  REQUIRE(st.status == StageStatus::Converged);
  CHECK(st.iterations == 2);
  CHECK(p.valueCalls == 1);
  CHECK(p.commits == 2);
  CHECK(st.finalValue == 1e6);
  CHECK((p.x - c).lpNorm<Eigen::Infinity>() <= 1e-14);

  // Without the offset the same decrease is resolvable (|f| is tiny): the value is checked.
  SeparableQuadratic q(a, c);
  const SolverStats sq = MinimizeNewton(q, NonlinearSolverParams(), 1.0);
  REQUIRE(sq.status == StageStatus::Converged);
  CHECK(q.valueCalls == 2);
  CHECK(q.commits == 2);
}

TEST_CASE("a convex non-quadratic problem converges quadratically", "[optim]") {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  Eigen::VectorXd c(40);
  for (Eigen::Index i = 0; i < c.size(); ++i) c[i] = u(rng);
  CoshChain p(c, 2.0);
  NonlinearSolverParams params = TightParams();
  params.relativeTolerance = 1e-15;
  const SolverStats st = MinimizeNewton(p, params, 1.0);
  INFO(Describe(st));
  REQUIRE(st.status == StageStatus::Converged);
  CHECK(st.iterations <= 12);
  CHECK(p.Gradient(p.x).lpNorm<Eigen::Infinity>() <= 1e-12);

  // Local quadratic convergence: once ‖g‖∞ < 0.1, each iterate's gradient is below C ‖g‖∞²
  // (until round-off, ~1e-13 here) and the ratios ‖g_{k+1}‖/‖g_k‖ shrink toward 0.
  const std::vector<double>& g = p.gradientNorms;
  std::ostringstream sequence;
  for (double v : g) sequence << v << " ";
  INFO("gradient norms: " << sequence.str());
  int quadraticSteps = 0;
  for (size_t k = 0; k + 1 < g.size(); ++k) {
    if (g[k] >= 0.1 || g[k + 1] <= 1e-12) continue;
    CHECK(g[k + 1] <= 10.0 * g[k] * g[k]);
    ++quadraticSteps;
  }
  CHECK(quadraticSteps >= 2);
}

TEST_CASE("projected Newton reaches the Rosenbrock minimum", "[optim]") {
  for (PsdProjection projection : {PsdProjection::Clamp, PsdProjection::Abs}) {
    Rosenbrock p;
    NonlinearSolverParams params;
    params.psdProjection = projection;
    const SolverStats st = MinimizeNewton(p, params, 1.0);
    INFO(Describe(st));
    CHECK(st.status == StageStatus::Converged);
    CHECK((p.x - Eigen::Vector2d(1, 1)).norm() <= 1e-8);
    CHECK(st.iterations <= 40);
    CHECK(st.lineSearchSteps > 0);  // the valley forces backtracking from (−1.2, 1)
  }
}

TEST_CASE("Newton on SO(3) finds the polar factor", "[optim]") {
  // A = R_true S with S symmetric positive definite: the polar factor of A is R_true.
  const Eigen::Matrix3d Rtrue = Exp(2.0 * Eigen::Vector3d(1, 2, 3).normalized());
  const Eigen::Matrix3d Q = Exp(Eigen::Vector3d(0.3, -0.5, 0.8));
  const Eigen::Matrix3d S = Q * Eigen::Vector3d(3, 2, 1).asDiagonal() * Q.transpose();
  const Eigen::Matrix3d A = Rtrue * S;
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d polar = svd.matrixU() * svd.matrixV().transpose();
  REQUIRE(polar.determinant() > 0.0);
  REQUIRE((polar - Rtrue).norm() <= 1e-12);

  RotationAlignment p(A, Eigen::Matrix3d::Identity());

  // The analytic tangent gradient and Hessian agree with finite differences of Value.
  {
    Eigen::VectorXd g;
    Eigen::SparseMatrix<double> H;
    p.Evaluate(&g, &H, PsdProjection::None);
    const ScalarFunction value = [&p](const Eigen::VectorXd& d) { return p.Value(d); };
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3);
    CHECK((FiniteDifferenceGradient(value, zero, 1e-6) - g).norm() <= 1e-8);
    const VectorFunction gradientAt = [&value](const Eigen::VectorXd& d) {
      return FiniteDifferenceGradient(value, d, 1e-4);
    };
    const Eigen::MatrixXd fdHessian = FiniteDifferenceJacobian(gradientAt, zero, 1e-4);
    CHECK((fdHessian - Eigen::MatrixXd(H)).norm() <= 1e-5);
    p.gradientNorms.clear();
  }

  const SolverStats st = MinimizeNewton(p, NonlinearSolverParams(), 1.0);
  INFO(Describe(st));
  CHECK(st.status == StageStatus::Converged);
  CHECK((p.R - polar).norm() <= 1e-8);
  CHECK((p.R.transpose() * p.R - Eigen::Matrix3d::Identity()).norm() <= 1e-12);
  CHECK(st.finalValue == Approx(-svd.singularValues().sum()).epsilon(1e-12));
  CHECK(st.iterations <= 15);
}

TEST_CASE("an indefinite Hessian is regularized with a diagonal shift", "[optim]") {
  // Exact Hessian (no projection) at (0, 0.2): [[0, 1], [1, 0.48]], indefinite, with the (0, 0)
  // entry missing from the sparsity pattern.
  QuarticSaddle p;
  {
    Eigen::VectorXd g;
    Eigen::SparseMatrix<double> H;
    p.Evaluate(&g, &H, PsdProjection::None);
    p.gradientNorms.clear();
    REQUIRE(H.nonZeros() == 3);  // (0, 0) is structurally absent
    REQUIRE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(H)).eigenvalues()[0] <
            0.0);
  }
  NonlinearSolverParams params;
  params.psdProjection = PsdProjection::None;
  const SolverStats st = MinimizeNewton(p, params, 1.0);
  INFO(Describe(st));
  CHECK(st.status == StageStatus::Converged);
  CHECK(st.regularizations >= 1);
  CHECK(std::abs(std::abs(p.x[0]) - 0.5) <= 1e-8);
  CHECK(p.x[1] == Approx(-p.x[0]).margin(1e-8));
  CHECK(st.finalValue == Approx(-0.125).margin(1e-14));
}

TEST_CASE("an iteration cap is reported as Stopped, never Converged", "[optim]") {
  Rosenbrock p;
  NonlinearSolverParams params;
  params.maxIterations = 2;
  const SolverStats st = MinimizeNewton(p, params, 1.0);
  INFO(Describe(st));
  CHECK(st.status == StageStatus::Stopped);
  CHECK(st.iterations == 2);
  CHECK(p.gradientNorms.size() == 2);
  CHECK(p.commits == 2);  // both steps were taken: the state is the last accepted iterate
  CHECK(st.message.find("max_iterations") != std::string::npos);
  CHECK(std::string(ToString(st.status)) == "Stopped");
}

TEST_CASE("a value that is NaN off the start is Diverged", "[optim]") {
  for (LineSearchKind kind : {LineSearchKind::Armijo, LineSearchKind::None}) {
    NanOffStart p;
    const Eigen::VectorXd x0 = p.x;
    NonlinearSolverParams params;
    params.lineSearch = kind;
    params.maxLineSearchSteps = 25;
    const SolverStats st = MinimizeNewton(p, params, 1.0);
    INFO(Describe(st));
    CHECK(st.status == StageStatus::Diverged);
    CHECK(st.iterations == 1);
    CHECK(p.commits == 0);
    CHECK(p.x == x0);
    CHECK(std::isfinite(st.finalValue));
    if (kind == LineSearchKind::Armijo) {
      CHECK(st.lineSearchSteps == 25);
      CHECK(p.valueCalls == 25);
      CHECK(st.message.find("line search") != std::string::npos);
    } else {
      CHECK(p.valueCalls == 1);
    }
  }
}

TEST_CASE("a non-finite gradient is Diverged", "[optim]") {
  SeparableQuadratic p(Eigen::Vector2d(1, 1), Eigen::Vector2d(1, std::nan("")));
  const SolverStats st = MinimizeNewton(p, NonlinearSolverParams(), 1.0);
  CHECK(st.status == StageStatus::Diverged);
  CHECK(st.iterations == 0);
}

TEST_CASE("a stationary start converges at once; other step tests", "[optim]") {
  SeparableQuadratic p(Eigen::Vector2d(1, 2), Eigen::Vector2d(0, 0));
  const SolverStats st = MinimizeNewton(p, NonlinearSolverParams(), 1.0);
  CHECK(st.status == StageStatus::Converged);
  CHECK(st.iterations == 0);
  CHECK(st.initialGradientNorm == 0.0);

  // The step test uses StepNorm(d)/timeScale: a 1e-6 step over Δt = 1e3 is 1e-9 m/s.
  SeparableQuadratic q(Eigen::Vector2d(1, 1), Eigen::Vector2d(1e-6, 0));
  NonlinearSolverParams params = TightParams();
  params.stepTolerance = 2e-9;
  const SolverStats sq = MinimizeNewton(q, params, 1e3);
  INFO(Describe(sq));
  CHECK(sq.status == StageStatus::Converged);
  CHECK(sq.iterations == 1);
  CHECK(sq.Message().find("step") == 0);
  CHECK(q.x[0] == Approx(1e-6).epsilon(1e-12));  // the last correction was committed

  // The relative gradient test.
  SeparableQuadratic r(Eigen::Vector2d(1, 1), Eigen::Vector2d(1, 0));
  params = TightParams();
  params.relativeTolerance = 1.0;  // passes at the first iterate
  const SolverStats sr = MinimizeNewton(r, params, 1.0);
  CHECK(sr.status == StageStatus::Converged);
  CHECK(sr.Message().find("gradient norm") == 0);
  CHECK(r.x[0] == Approx(1.0));
}

TEST_CASE("invalid parameters or time scale are reported without touching the problem", "[optim]") {
  SeparableQuadratic p(Eigen::Vector2d(1, 1), Eigen::Vector2d(1, 0));
  NonlinearSolverParams params;
  params.backtrackFactor = 1.0;
  SolverStats st = MinimizeNewton(p, params, 1.0);
  CHECK(st.status == StageStatus::Diverged);
  CHECK(st.message == "invalid parameters: backtrack_factor: must be in (0, 1), got 1");
  CHECK(p.gradientNorms.empty());
  st = MinimizeNewton(p, NonlinearSolverParams(), 0.0);
  CHECK(st.status == StageStatus::Diverged);
  CHECK(p.gradientNorms.empty());
}

TEST_CASE("solver parameters are validated by name", "[optim]") {
  NonlinearSolverParams p;
  CHECK(Validate(p).empty());
  p.maxIterations = 0;
  CHECK(Validate(p) == "max_iterations: must be >= 1, got 0");
  p = NonlinearSolverParams();
  p.absoluteTolerance = -1e-3;
  CHECK(Validate(p) == "absolute_tolerance: must be >= 0, got -0.001");
  p = NonlinearSolverParams();
  p.relativeTolerance = std::nan("");
  CHECK(Validate(p) == "relative_tolerance: must be >= 0, got nan");
  p = NonlinearSolverParams();
  p.stepTolerance = -2;
  CHECK(Validate(p) == "step_tolerance: must be >= 0, got -2");
  p = NonlinearSolverParams();
  p.armijoConstant = 1.5;
  CHECK(Validate(p) == "armijo_constant: must be in (0, 1), got 1.5");
  p.armijoConstant = 0.0;
  CHECK(Validate(p) == "armijo_constant: must be in (0, 1), got 0");
  p = NonlinearSolverParams();
  p.backtrackFactor = 0.0;
  CHECK(Validate(p) == "backtrack_factor: must be in (0, 1), got 0");
  p = NonlinearSolverParams();
  p.maxLineSearchSteps = 0;
  CHECK(Validate(p) == "max_line_search_steps: must be >= 1, got 0");
  // Zero tolerances are allowed (that test is then effectively off).
  p = NonlinearSolverParams();
  p.absoluteTolerance = p.relativeTolerance = p.stepTolerance = 0.0;
  CHECK(Validate(p).empty());
}

TEST_CASE("stage statuses have names", "[optim]") {
  CHECK(std::string(ToString(StageStatus::Converged)) == "Converged");
  CHECK(std::string(ToString(StageStatus::Stopped)) == "Stopped");
  CHECK(std::string(ToString(StageStatus::Diverged)) == "Diverged");
}
