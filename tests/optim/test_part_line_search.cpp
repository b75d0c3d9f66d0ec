// The line search by independent parts (optim/part_line_search.h) in both Newton solvers, on a
// two-unit problem whose first unit needs a cut step and whose second is a quadratic (root): with
// one step length the quadratic unit takes the first unit's cut; by parts it takes its full Newton
// step, unless a term joins the units at the base state or at the trial.
#include <catch2/catch.hpp>
#include <cmath>

#include "optim/line_search.h"
#include "optim/newton_solver.h"
#include "optim/part_line_search.h"
#include "optim/residual_newton.h"

using namespace superdex;

namespace {

/// When the problem reports a coupling term between its two units.
enum class Join { Never, Always, WhenFirstNegative };

/// Units x₁, x₂ (one dof each).
///   potential:  f = √(1 + x₁²) + ½ (x₂ − 1)²  — Newton's step on √(1 + x²) is −x(1 + x²): from
///               x₁ = 3 the full step (to −27) raises f; Armijo on f₁ accepts α = 1/8 (x₁ = −0.75),
///               and so does Armijo on f from x₂ = 0.5;
///   residual:   r = (atan x₁, x₂ − 1)          — from x₁ = 3 the full step overshoots to −9.49
///               (θ₁ rises); the merit test on θ₁ accepts α = 1/4 (x₁ = −0.12), the one on θ from
///               x₂ = 0.5 already α = 1/2 (x₂'s fall outweighs x₁'s rise there).
/// The joins are reported only (the objective has no coupling term), which LastSplit allows: a
/// join says the units may be coupled.
class TwoUnits : public StageProblem {
 public:
  TwoUnits(bool potential, Join join) : potential_(potential), join_(join) {}
  int NumDofs() const override { return 2; }
  double Value(const Eigen::VectorXd& d) override { return At(x_ + d, nullptr, nullptr); }
  double Evaluate(Eigen::VectorXd* g, Eigen::SparseMatrix<double>* H, PsdProjection) override {
    return At(x_, g, H);
  }
  bool EvaluateAtStep(const Eigen::VectorXd& d, double* value, Eigen::VectorXd* g,
                      Eigen::SparseMatrix<double>* H, PsdProjection) override {
    *value = At(x_ + d, g, H);
    return true;
  }
  void Commit(const Eigen::VectorXd& d) override { x_ += d; }
  bool IsPotential() const override { return potential_; }
  void Residual(const Eigen::VectorXd& d, Eigen::VectorXd* r) override {
    Eigen::SparseMatrix<double> J;
    ResidualAt(x_ + d, r, &J);
  }
  void EvaluateResidual(Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J) override {
    ResidualAt(x_, r, J);
  }
  bool LastSplit(StageSplit* split) override {
    split->unitOfDof = {0, 1};
    split->units = 2;
    split->share = share_;
    split->joins.clear();
    if (join_ == Join::Always || (join_ == Join::WhenFirstNegative && last_[0] < 0.0))
      split->joins.emplace_back(0, 1);
    return true;
  }
  const Eigen::Vector2d& x() const { return x_; }

 private:
  static void Diagonal(double a, double b, Eigen::SparseMatrix<double>* M) {
    M->resize(2, 2);
    M->setZero();
    M->insert(0, 0) = a;
    M->insert(1, 1) = b;
    M->makeCompressed();
  }
  double At(const Eigen::Vector2d& x, Eigen::VectorXd* g, Eigen::SparseMatrix<double>* H) {
    last_ = x;
    const double s = std::sqrt(1.0 + x[0] * x[0]);
    share_ = {s, 0.5 * (x[1] - 1.0) * (x[1] - 1.0)};
    if (g) *g = Eigen::Vector2d(x[0] / s, x[1] - 1.0);
    if (H) Diagonal(1.0 / (s * s * s), 1.0, H);
    return share_[0] + share_[1];
  }
  void ResidualAt(const Eigen::Vector2d& x, Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J) {
    last_ = x;
    share_ = {0.0, 0.0};
    *r = Eigen::Vector2d(std::atan(x[0]), x[1] - 1.0);
    Diagonal(1.0 / (1.0 + x[0] * x[0]), 1.0, J);
  }

  bool potential_;
  Join join_;
  Eigen::Vector2d x_{3.0, 0.5}, last_{3.0, 0.5};
  std::vector<double> share_{0.0, 0.0};
};

NonlinearSolverParams Params(bool parts, int maxIterations) {
  NonlinearSolverParams p;
  p.partLineSearch = parts;
  p.maxIterations = maxIterations;
  return p;
}

SolverStats Solve(TwoUnits& problem, const NonlinearSolverParams& p) {
  return problem.IsPotential() ? MinimizeNewton(problem, p, 1.0)
                               : SolveResidualNewton(problem, p, 1.0);
}

}  // namespace

TEST_CASE("Part line search: an independent quadratic unit takes its full step", "[optim][parts]") {
  for (bool potential : {true, false}) {
    INFO((potential ? "minimization" : "residual"));
    // The accepted step length with one step length and the first part's own.
    const double shared = potential ? 0.125 : 0.5;
    const double own = potential ? 0.125 : 0.25;
    {
      TwoUnits one(potential, Join::Never);
      const SolverStats st = Solve(one, Params(false, 1));
      CHECK(st.status == StageStatus::Stopped);
      CHECK(st.lineSearchSteps == (potential ? 3 : 1));
      CHECK(one.x()[1] == Approx(0.5 + 0.5 * shared).epsilon(1e-15));  // the shared cut
    }
    {
      TwoUnits parts(potential, Join::Never);
      const SolverStats st = Solve(parts, Params(true, 1));
      CHECK(st.status == StageStatus::Stopped);
      CHECK(parts.x()[1] == 1.0);  // the quadratic's Newton step, whole
      const double x1 = potential ? 3.0 - own * 30.0 : 3.0 - own * std::atan(3.0) * 10.0;
      CHECK(parts.x()[0] == Approx(x1).epsilon(1e-14));
    }
    // Both solve to the same point.
    TwoUnits a(potential, Join::Never), b(potential, Join::Never);
    const SolverStats sa = Solve(a, Params(false, 50));
    const SolverStats sb = Solve(b, Params(true, 50));
    REQUIRE(sa.status == StageStatus::Converged);
    REQUIRE(sb.status == StageStatus::Converged);
    CHECK(std::abs(a.x()[0]) < 1e-6);
    CHECK(std::abs(b.x()[0]) < 1e-6);
    CHECK(a.x()[1] == Approx(1.0).margin(1e-12));
    CHECK(b.x()[1] == Approx(1.0).margin(1e-12));
    CHECK(sb.iterations <= sa.iterations);
  }
}

TEST_CASE("Part line search: units joined at the base state or at the trial share the cut",
          "[optim][parts]") {
  for (bool potential : {true, false}) {
    INFO((potential ? "minimization" : "residual"));
    const double shared = potential ? 0.125 : 0.5;
    // Joined at the start: one part, one step length.
    TwoUnits joined(potential, Join::Always);
    Solve(joined, Params(true, 1));
    CHECK(joined.x()[1] == Approx(0.5 + 0.5 * shared).epsilon(1e-15));
    // Joined only where x₁ < 0, i.e. at every trial of this first step: the two parts are tested
    // as one group on the sum of their merits, whose first unit's rise outweighs the second's
    // fall at the same step length as with one step length.
    TwoUnits atTrial(potential, Join::WhenFirstNegative);
    Solve(atTrial, Params(true, 1));
    CHECK(atTrial.x()[1] == Approx(0.5 + 0.5 * shared).epsilon(1e-15));
  }
}

TEST_CASE("Part line search: a part whose step is no descent stays", "[optim][parts]") {
  TwoUnits problem(true, Join::Never);
  Eigen::VectorXd g, step;
  Eigen::SparseMatrix<double> H;
  problem.Evaluate(&g, &H, PsdProjection::None);
  PartLineSearch parts;
  REQUIRE(parts.Begin(problem));
  CHECK(parts.Parts() == 2);
  // g = (3/√10, −0.5): the direction (−1, −1) descends along the first unit only (g·d < 0
  // overall).
  const Eigen::Vector2d dir(-1.0, -1.0);
  parts.StartMinimization(g, dir);
  parts.Step(dir, &step);
  CHECK(step[0] == -1.0);
  CHECK(step[1] == 0.0);
  CHECK_FALSE(parts.AllFull());
  CHECK(parts.MinAlpha() == 0.0);
}

TEST_CASE("Part line search: a residual part the inexact direction does not descend stays",
          "[optim][parts]") {
  // r = (atan x₁, x₂ − 1) at (3, 0.5), J = diag(1/10, 1). The direction (−1, −0.1), as an
  // inexact linear solve may leave it: a descent for θ₁ (x₁ 3 → 2) and an ascent for θ₂
  // (r₂·(J d)₂ = 0.05 > 0), which no step length makes pass its group's test (θ₂ rises
  // linearly in α) until the round-off band does.
  const Eigen::Vector2d dir(-1.0, -0.1);
  auto search = [&](bool withJacobian, Eigen::VectorXd* step) {
    TwoUnits problem(false, Join::Never);
    Eigen::VectorXd r, rTrial;
    Eigen::SparseMatrix<double> J, JTrial;
    problem.EvaluateResidual(&r, &J);
    LineSearch ls;
    ls.SetOptions(LineSearch::Options());
    ls.ReadSplit(problem);
    REQUIRE(ls.Split());
    LineSearch::Start start =
        LineSearch::Start::Residual(0.5 * r.squaredNorm(), r, 0.5 * std::abs(r.dot(dir)));
    if (withJacobian) start.jacobian = &J;
    return ls.Search(problem, start, dir, step, &rTrial, &JTrial);
  };
  Eigen::VectorXd step;
  // With the Jacobian: the second part stays, the first takes its whole step at the first trial.
  const LineSearch::Summary stays = search(true, &step);
  CHECK(stays.accepted);
  CHECK(stays.rejectedTrials == 0);
  CHECK(step[0] == -1.0);
  CHECK(step[1] == 0.0);
  CHECK(stays.trialMerit == Approx(0.5 * std::atan(2.0) * std::atan(2.0) + 0.125).epsilon(1e-15));
  // Without it: the second part's step length is cut until the band, a trial per halving.
  const LineSearch::Summary cut = search(false, &step);
  CHECK(cut.rejectedTrials >= 30);
  CHECK(step[0] == -1.0);
  CHECK(std::abs(step[1]) < 1e-9);
}

namespace {

/// f = ½‖x‖² − b·x over three units of one dof each; units 0 and 1 are reported joined (one
/// part), unit 2 stands alone. At x = 0, g = −b.
class ThreeUnits : public StageProblem {
 public:
  /// `emptyUnits`: that many more units reported after the three, with no dof (an actor the
  /// stage holds no unknown of).
  explicit ThreeUnits(const Eigen::Vector3d& b, int emptyUnits = 0) : b_(b), empty_(emptyUnits) {}
  int NumDofs() const override { return 3; }
  double Value(const Eigen::VectorXd& d) override { return At(x_ + d, nullptr); }
  double Evaluate(Eigen::VectorXd* g, Eigen::SparseMatrix<double>* H, PsdProjection) override {
    if (H) {
      H->resize(3, 3);
      H->setIdentity();
    }
    return At(x_, g);
  }
  void Commit(const Eigen::VectorXd& d) override { x_ += d; }
  bool IsPotential() const override { return true; }
  void Residual(const Eigen::VectorXd&, Eigen::VectorXd*) override {}
  void EvaluateResidual(Eigen::VectorXd*, Eigen::SparseMatrix<double>*) override {}
  bool LastSplit(StageSplit* split) override {
    split->unitOfDof = {0, 1, 2};
    split->units = 3 + empty_;
    split->share = share_;
    split->share.resize(3 + empty_, 0.0);
    split->joins = {{0, 1}};
    return true;
  }

 private:
  double At(const Eigen::Vector3d& x, Eigen::VectorXd* g) {
    for (int k = 0; k < 3; ++k) share_[k] = 0.5 * x[k] * x[k] - b_[k] * x[k];
    if (g) *g = x - b_;
    return share_[0] + share_[1] + share_[2];
  }
  Eigen::Vector3d b_, x_ = Eigen::Vector3d::Zero();
  int empty_ = 0;
  std::vector<double> share_{0.0, 0.0, 0.0};
};

}  // namespace

TEST_CASE("Part line search: a shortened step that no longer descends is scaled uniformly",
          "[optim][parts]") {
  // g = (0.9, −0.5, −1). The direction d = (0.2, 1, 1) descends on the joined part {0, 1}
  // (g·d = −0.32) and on unit 2. A bound that shortens dof 1 to a tenth and dof 2 to a half
  // leaves l = (0.2, 0.1, 0.5): part {0, 1} now ascends (+0.13), unit 2 still descends.
  ThreeUnits problem(Eigen::Vector3d(-0.9, 0.5, 1.0));
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H;
  problem.Evaluate(&g, &H, PsdProjection::None);
  const Eigen::Vector3d d(0.2, 1.0, 1.0);
  Eigen::VectorXd limited = Eigen::Vector3d(0.2, 0.1, 0.5);
  PartLineSearch parts;
  REQUIRE(parts.Begin(problem));
  REQUIRE(parts.Parts() == 2);
  REQUIRE(g[0] * limited[0] + g[1] * limited[1] > 0.0);
  parts.ShortenByParts(g, d, &limited);
  // Part {0, 1}: d scaled by the smallest fraction its dofs were shortened to, 0.1 — a descent
  // direction within both dofs' bounds. Unit 2 keeps its shortened step.
  CHECK(limited[0] == 0.1 * d[0]);
  CHECK(limited[1] == 0.1 * d[1]);
  CHECK(g[0] * limited[0] + g[1] * limited[1] < 0.0);
  CHECK(limited[2] == 0.5);
  // The residual solver's form: every part starts at the smallest fraction of its dofs.
  const Eigen::Vector3d x(1.0, 2.0, 4.0);
  Eigen::VectorXd r = Eigen::Vector3d(-1.0, -1.0, -1.0), step;
  parts.StartResidual(r, x);
  parts.CapSteps(x, Eigen::Vector3d(1.0, 0.2, 1.0));
  parts.Step(x, &step);
  CHECK(step[0] == 0.1 * x[0]);
  CHECK(step[1] == 0.1 * x[1]);
  CHECK(step[2] == 0.25 * x[2]);
  CHECK(parts.MinAlpha() == 0.1);
}

TEST_CASE("Part line search: a unit without a dof neither holds back the step nor makes a part",
          "[optim][parts]") {
  // f = ½‖x‖² − b·x: Newton's step −g is exact, so every part passes at its full step.
  for (bool residual : {false, true}) {
    INFO((residual ? "residual" : "minimization"));
    ThreeUnits problem(Eigen::Vector3d(-0.9, 0.5, 1.0), 1);
    Eigen::VectorXd g, step, trial;
    Eigen::SparseMatrix<double> H, trialH;
    problem.Evaluate(&g, &H, PsdProjection::None);
    const Eigen::VectorXd d = -g;
    PartLineSearch parts;
    REQUIRE(parts.Begin(problem));
    CHECK(parts.Parts() == 3);  // {0, 1}, {2} and the empty unit's
    if (residual) {
      parts.StartResidual(g, d, &d);  // r = g, J = I: J d = d, r·(J d) < 0 on both parts
    } else {
      parts.StartMinimization(g, d);
    }
    parts.Step(d, &step);
    CHECK(step == d);
    CHECK(parts.AllFull());  // the empty part's α (0: no descent) is not a step length
    CHECK(parts.MinAlpha() == 1.0);
    // Through the line search: a full step is reported as one (the residual solver's quadratic
    // regime and its stagnation test read it).
    LineSearch ls;
    ls.SetOptions(LineSearch::Options());
    ls.ReadSplit(problem);
    REQUIRE(ls.Split());
    const double slope = g.dot(d);
    const LineSearch::Summary sum = ls.Search(
        problem,
        LineSearch::Start::Potential(problem.Value(Eigen::Vector3d::Zero()), g, slope, slope), d,
        &step, &trial, &trialH);
    CHECK(sum.accepted);
    CHECK(sum.alpha == 1.0);
  }
  // Two dof-owning units joined, and one without: a single part with dofs, no split.
  class Joined : public ThreeUnits {
   public:
    Joined() : ThreeUnits(Eigen::Vector3d(1.0, 1.0, 1.0), 0) {}
    bool LastSplit(StageSplit* split) override {
      ThreeUnits::LastSplit(split);
      split->unitOfDof = {0, 0, 0};
      return true;
    }
  } joined;
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H;
  joined.Evaluate(&g, &H, PsdProjection::None);
  PartLineSearch parts;
  CHECK_FALSE(parts.Begin(joined));
}
