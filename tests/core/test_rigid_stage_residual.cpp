#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/model/rigid_math.h"
#include "core/dynamics/scene_stage.h"
#include "optim/residual_newton.h"
#include "derivative_check.h"
#include "kind_stage.h"

using namespace superdex;

namespace {

// A static plane and two boxes (half extents 0.1 m) pressed into the plane and each other, sliding
// along x at 0.2 m/s and spinning slowly, their stage start one step back; with `forces` and
// `torques` applied loads on the boxes.
struct Fixture {
  test::HandStage hand;
  Eigen::Vector3d force[3] = {Eigen::Vector3d::Zero(), {3, -1, 2}, {-2, 4, 1}};
  Eigen::Vector3d torque[3] = {Eigen::Vector3d::Zero(), {0.5, -0.2, 0.3}, {-0.1, 0.4, 0.2}};

  explicit Fixture(bool forces = false, bool torques = false) {
    auto build = [&](RigidShape shape, bool dynamic, Eigen::Vector3d p, Eigen::Matrix3d R) {
      const size_t i = hand.kinds.size();
      RigidActorDesc d;
      d.name = "a" + std::to_string(i);
      d.dynamic = dynamic;
      d.shape = shape;
      d.contact.penaltyCoefficient = 1e6;
      d.contact.normalViscousDampingCoefficient = 0.8;
      d.contact.viscousFrictionCoefficient = 0.1;
      if (dynamic && forces) d.appliedForce = {{0.0, force[i]}};
      if (dynamic && torques) d.appliedTorque = {{0.0, torque[i]}};
      RigidPose start = {p - hand.dt * Eigen::Vector3d(0.2, 0.05, -0.1),
                         ExpSo3(Eigen::Vector3d(0, 0, -0.02)) * R};
      if (!dynamic) start = {p, R};
      hand.AddRigid(d, {p, R}, start, {p + Eigen::Vector3d(0.001, 0, -0.001), R});
    };
    RigidShape plane;
    plane.kind = RigidShapeKind::Plane;
    build(plane, false, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
    RigidShape box;
    box.kind = RigidShapeKind::Box;
    box.halfExtents = Eigen::Vector3d(0.1, 0.1, 0.1);
    build(box, true, Eigen::Vector3d(0.0, 0.0, 0.098), ExpSo3(Eigen::Vector3d(0.02, -0.01, 0.3)));
    build(box, true, Eigen::Vector3d(0.01, 0.02, 0.296), ExpSo3(Eigen::Vector3d(-0.01, 0.02, 0.1)));
    hand.Finish();
    REQUIRE(hand.numDofs == 12);
  }
};

// The fixture's stage problem in one dissipation mode, on its own copy of the iterate.
struct Stage {
  Fixture f;
  std::vector<Eigen::VectorXd> x = f.hand.x;
  StageDissipation dissipation;
  SceneStageProblem problem;
  explicit Stage(DissipationMode mode, bool enabled = true, bool forces = false,
                 bool torques = false)
      : f(forces, torques),
        dissipation{enabled, mode, true},
        problem(12, f.hand.dt, &f.hand.pipeline, f.hand.stage, &x, dissipation) {}
  RigidPose Pose(size_t k) const { return f.hand.Pose(x, k); }
};

// Central differences (step 1e-7) of the stage's residual at its current state.
Eigen::MatrixXd ResidualJacobianFd(SceneStageProblem& problem) {
  return FiniteDifferenceJacobian(
      [&](const Eigen::VectorXd& d) {
        Eigen::VectorXd r;
        problem.Residual(d, &r);
        return r;
      },
      Eigen::VectorXd::Zero(problem.NumDofs()), 1e-7);
}

// Central differences (step 1e-7) of the stage's value at its current state.
Eigen::VectorXd ValueGradientFd(SceneStageProblem& problem) {
  return FiniteDifferenceGradient([&](const Eigen::VectorXd& d) { return problem.Value(d); },
                                  Eigen::VectorXd::Zero(problem.NumDofs()), 1e-7);
}

}  // namespace

TEST_CASE("rigid stage: residual Jacobian and potential gradient with dissipation",
          "[core][gradient][dissipation]") {
  for (DissipationMode mode : {DissipationMode::ExplicitNormals, DissipationMode::ReconstructedLoad,
                               DissipationMode::ImplicitLoad}) {
    DYNAMIC_SECTION(ToString(mode)) {
      Stage stage(mode);
      SceneStageProblem& problem = stage.problem;
      CHECK(problem.IsPotential() == (mode == DissipationMode::ExplicitNormals));
      Eigen::VectorXd r;
      Eigen::SparseMatrix<double> J;
      problem.EvaluateResidual(&r, &J);
      REQUIRE(r.size() == 12);
      const Eigen::MatrixXd Jfd = ResidualJacobianFd(problem);
      const double err = (Eigen::MatrixXd(J) - Jfd).norm() / Jfd.norm();
      INFO("residual Jacobian error " << err);
      CHECK(err < 1e-6);
      if (mode == DissipationMode::ExplicitNormals) {
        Eigen::VectorXd g;
        problem.Evaluate(&g, nullptr, PsdProjection::None);
        CHECK((g - r).norm() < 1e-12 * r.norm());
        const Eigen::VectorXd gfd = ValueGradientFd(problem);
        INFO("gradient error " << (g - gfd).norm() / gfd.norm());
        CHECK((g - gfd).norm() < 1e-6 * gfd.norm());
      }
    }
  }
}

TEST_CASE("rigid stage: the residual at a trial step equals the one after committing it, bit for "
          "bit", "[core][dissipation]") {
  for (DissipationMode mode : {DissipationMode::ExplicitNormals, DissipationMode::ReconstructedLoad,
                               DissipationMode::ImplicitLoad}) {
    DYNAMIC_SECTION(ToString(mode)) {
      Stage stage(mode);
      SceneStageProblem& problem = stage.problem;
      Eigen::VectorXd r0, rTrial, rCommitted, rOnly;
      Eigen::SparseMatrix<double> J0, JTrial, JCommitted;
      problem.EvaluateResidual(&r0, &J0);
      const ContactStats before = problem.LastContactStats();
      // A step that moves both boxes by up to 1 mm and turns them.
      Eigen::VectorXd d(12);
      d << 1e-4, -2e-4, -1e-3, 3e-3, -1e-3, 2e-3, -1e-4, 2e-4, -5e-4, 1e-3, 2e-3, -1e-3;
      REQUIRE(problem.EvaluateResidualAtStep(d, &rTrial, &JTrial));
      // Not adopted before the commit: the statistics still describe the current state.
      CHECK(problem.LastContactStats().minSignedDistance == before.minSignedDistance);
      problem.Residual(d, &rOnly);
      problem.Commit(d);
      CHECK(problem.LastContactStats().minSignedDistance != before.minSignedDistance);
      const ContactStats adopted = problem.LastContactStats();
      problem.EvaluateResidual(&rCommitted, &JCommitted);
      CHECK(problem.LastContactStats().minSignedDistance == adopted.minSignedDistance);
      CHECK(problem.LastContactStats().activeSamples == adopted.activeSamples);
      CHECK(problem.LastContactStats().energy == adopted.energy);
      REQUIRE(rTrial.size() == rCommitted.size());
      CHECK(std::memcmp(rTrial.data(), rCommitted.data(), sizeof(double) * rTrial.size()) == 0);
      REQUIRE(JTrial.nonZeros() == JCommitted.nonZeros());
      CHECK(std::memcmp(JTrial.valuePtr(), JCommitted.valuePtr(),
                        sizeof(double) * JTrial.nonZeros()) == 0);
      CHECK(std::memcmp(JTrial.innerIndexPtr(), JCommitted.innerIndexPtr(),
                        sizeof(int) * JTrial.nonZeros()) == 0);
      // And the same residual as the residual-only evaluation, up to the order of its sums.
      CHECK((rOnly - rTrial).norm() <= 1e-12 * rTrial.norm());
      CHECK((rTrial - r0).norm() > 1e-3 * r0.norm());  // the step changed something
    }
  }
}

namespace {

// The problem as a solver sees it, without EvaluateResidualAtStep and EvaluateAtStep (the solvers
// then evaluate every accepted state again).
class WithoutTrialDerivatives : public StageProblem {
 public:
  explicit WithoutTrialDerivatives(StageProblem& p) : p_(p) {}
  int NumDofs() const override { return p_.NumDofs(); }
  double Value(const Eigen::VectorXd& d) override { return p_.Value(d); }
  double Evaluate(Eigen::VectorXd* g, Eigen::SparseMatrix<double>* H,
                  PsdProjection projection) override {
    return p_.Evaluate(g, H, projection);
  }
  void Commit(const Eigen::VectorXd& d) override { p_.Commit(d); }
  bool IsPotential() const override { return p_.IsPotential(); }
  void Residual(const Eigen::VectorXd& d, Eigen::VectorXd* r) override { p_.Residual(d, r); }
  void EvaluateResidual(Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J) override {
    p_.EvaluateResidual(r, J);
  }
  bool LimitStep(Eigen::VectorXd* d) override { return p_.LimitStep(d); }
  bool TrustStep(Eigen::VectorXd* d) override { return p_.TrustStep(d); }
  double StepNorm(const Eigen::VectorXd& d) const override { return p_.StepNorm(d); }

 private:
  StageProblem& p_;
};

// The same solve with and without reusing accepted trials: same iterations, bitwise the same
// solution.
void CheckSameSolve(const SolverStats& sa, const SolverStats& sb, const Stage& a, const Stage& b) {
  INFO(sa.Message() << " / " << sb.Message());
  CHECK(sa.status == StageStatus::Converged);
  CHECK(sa.iterations >= 2);  // at least one accepted trial was reused
  CHECK(sa.iterations == sb.iterations);
  CHECK(sa.lineSearchSteps == sb.lineSearchSteps);
  for (size_t i = 0; i < a.x.size(); ++i) CHECK(a.x[i] == b.x[i]);
}

}  // namespace

TEST_CASE("residual Newton: reusing the accepted trial's Jacobian leaves the iterates unchanged",
          "[core][dissipation]") {
  for (DissipationMode mode : {DissipationMode::ReconstructedLoad, DissipationMode::ImplicitLoad}) {
    DYNAMIC_SECTION(ToString(mode)) {
      Stage a(mode), b(mode);
      NonlinearSolverParams params;
      WithoutTrialDerivatives bPlain(b.problem);
      const SolverStats sa = SolveResidualNewton(a.problem, params, a.f.hand.dt, nullptr);
      const SolverStats sb = SolveResidualNewton(bPlain, params, b.f.hand.dt, nullptr);
      CheckSameSolve(sa, sb, a, b);
      CHECK(sa.finalGradientNorm == sb.finalGradientNorm);
    }
  }
}

TEST_CASE("rigid stage: the potential's derivatives at a trial step equal those after committing "
          "it, bit for bit", "[core][dissipation]") {
  for (bool dissipation : {false, true}) {
    DYNAMIC_SECTION((dissipation ? "explicit-normals dissipation" : "conservative")) {
      Stage stage(DissipationMode::ExplicitNormals, dissipation);
      SceneStageProblem& problem = stage.problem;
      std::vector<Eigen::VectorXd>& x = stage.x;
      REQUIRE(problem.IsPotential());
      Eigen::VectorXd d(12);
      d << 1e-4, -2e-4, -1e-3, 3e-3, -1e-3, 2e-3, -1e-4, 2e-4, -5e-4, 1e-3, 2e-3, -1e-3;
      for (PsdProjection projection : {PsdProjection::None, PsdProjection::Clamp}) {
        Eigen::VectorXd gTrial, gCommitted;
        Eigen::SparseMatrix<double> HTrial, HCommitted;
        const std::vector<Eigen::VectorXd> start = x;
        double fTrial = 0.0;
        REQUIRE(problem.EvaluateAtStep(d, &fTrial, &gTrial, &HTrial, projection));
        CHECK(fTrial == problem.Value(d));
        problem.Commit(d);
        const double fCommitted = problem.Evaluate(&gCommitted, &HCommitted, projection);
        CHECK(fTrial == fCommitted);
        REQUIRE(gTrial.size() == gCommitted.size());
        CHECK(std::memcmp(gTrial.data(), gCommitted.data(), sizeof(double) * gTrial.size()) == 0);
        REQUIRE(HTrial.nonZeros() == HCommitted.nonZeros());
        CHECK(std::memcmp(HTrial.valuePtr(), HCommitted.valuePtr(),
                          sizeof(double) * HTrial.nonZeros()) == 0);
        x = start;  // back to the stage's state for the next projection
      }
    }
  }
}

TEST_CASE("projected Newton: reusing the accepted trial's derivatives leaves the iterates unchanged",
          "[core][dissipation]") {
  for (PsdProjection projection : {PsdProjection::None, PsdProjection::Clamp}) {
    DYNAMIC_SECTION("projection " << static_cast<int>(projection)) {
      Stage a(DissipationMode::ExplicitNormals), b(DissipationMode::ExplicitNormals);
      NonlinearSolverParams params;
      params.psdProjection = projection;
      WithoutTrialDerivatives bPlain(b.problem);
      const SolverStats sa = MinimizeNewton(a.problem, params, a.f.hand.dt, nullptr);
      const SolverStats sb = MinimizeNewton(bPlain, params, b.f.hand.dt, nullptr);
      CheckSameSolve(sa, sb, a, b);
      CHECK(sa.finalValue == sb.finalValue);
    }
  }
}

TEST_CASE("rigid stage: the dynamic bodies' six dofs are the Krylov preconditioner's blocks",
          "[core][optim]") {
  Stage stage(DissipationMode::ReconstructedLoad);
  DofBlockLayout layout;
  stage.problem.BlockLayout(&layout);
  CHECK(layout.sizes == std::vector<int>{6, 6});  // the static plane has no dofs
  // A kind whose free dofs do not fill its blocks (one rotation dof held) claims none.
  Fixture f;
  std::vector<Eigen::VectorXd> x = f.hand.x;
  KindStage held = f.hand.stage;
  held.stageDof[2] = {6, 7, 8, 9, 10, -1};
  SceneStageProblem problem(11, f.hand.dt, &f.hand.pipeline, held, &x);
  problem.BlockLayout(&layout);
  CHECK(layout.sizes.empty());
}

TEST_CASE("rigid stage: the trust region bounds each body's Newton correction",
          "[core][stage]") {
  Stage s(DissipationMode::ExplicitNormals);
  const RigidBodyModel& m = s.f.hand.Rigid(1).Model();  // both boxes: half extents 0.1 m
  const double rho = std::max(m.samplesRadius, RmsRadius(m));
  REQUIRE(rho >= 0.1);
  const double trust = kCorrectionTrust * rho;
  auto moved = [&](const Eigen::VectorXd& d, int o) {
    return d.segment<3>(o).norm() + d.segment<3>(o + 3).norm() * rho;
  };
  SECTION("a correction within the region is left as it is") {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(12);
    d << 0.2 * trust, 0, 0, 0, 0, 0.5 * trust / rho, 0, -0.9 * trust, 0, 0, 0, 0;
    const Eigen::VectorXd before = d;
    CHECK_FALSE(s.problem.TrustStep(&d));
    CHECK(d == before);
  }
  SECTION("a long translation and a rotation of radians are shortened, body by body") {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(12);
    d.segment<3>(0) = Eigen::Vector3d(0.5, -0.2, 0.1);   // body 1: half a metre
    d.segment<3>(9) = Eigen::Vector3d(0.0, 0.0, 3.0);    // body 2: three radians
    d[6] = 1e-3;
    const Eigen::VectorXd before = d;
    CHECK(s.problem.TrustStep(&d));
    for (int o : {0, 6}) {
      INFO("body at dof " << o);
      CHECK(moved(d, o) == Approx(trust).epsilon(1e-12));
      // The direction is kept: a positive multiple of the body's block.
      const double scale = d.segment<6>(o).norm() / before.segment<6>(o).norm();
      CHECK(scale < 1.0);
      CHECK((d.segment<6>(o) - scale * before.segment<6>(o)).norm() <= 1e-15);
    }
  }
}

TEST_CASE("rigid stage: applied forces are a potential, applied torques a residual term",
          "[core][gradient][applied_loads]") {
  for (DissipationMode mode : {DissipationMode::ExplicitNormals, DissipationMode::ReconstructedLoad,
                               DissipationMode::ImplicitLoad}) {
    for (bool torques : {false, true}) {
      DYNAMIC_SECTION(ToString(mode) << (torques ? ", forces and torques" : ", forces")) {
        Stage plain(mode), stage(mode, true, true, torques);
        SceneStageProblem& problem = stage.problem;
        CHECK(problem.IsPotential() == (mode == DissipationMode::ExplicitNormals && !torques));
        // The residual: the unloaded one minus the loads (−F on δp, −τ on δθ).
        Eigen::VectorXd r, r0;
        Eigen::SparseMatrix<double> J, J0;
        problem.EvaluateResidual(&r, &J);
        plain.problem.EvaluateResidual(&r0, &J0);
        Eigen::VectorXd loads = Eigen::VectorXd::Zero(12);
        for (int b = 1; b <= 2; ++b) {
          loads.segment<3>(6 * (b - 1)) = stage.f.force[b];
          if (torques) loads.segment<3>(6 * (b - 1) + 3) = stage.f.torque[b];
        }
        CHECK((r - (r0 - loads)).norm() < 1e-12 * r.norm());
        // Its Jacobian: finite differences of the residual (a constant world torque adds none).
        const Eigen::MatrixXd Jfd = ResidualJacobianFd(problem);
        const double err = (Eigen::MatrixXd(J) - Jfd).norm() / Jfd.norm();
        INFO("residual Jacobian error " << err);
        CHECK(err < 1e-6);
        CHECK((Eigen::MatrixXd(J) - Eigen::MatrixXd(J0)).norm() < 1e-12 * Jfd.norm());
        if (mode != DissipationMode::ExplicitNormals) continue;
        // The minimizers' value: its gradient is the residual (the torques' work is linear in the
        // rotation step from the current iterate), its Hessian finite differences of the gradient.
        Eigen::VectorXd g;
        Eigen::SparseMatrix<double> H;
        problem.Evaluate(&g, &H, PsdProjection::None);
        CHECK((g - r).norm() < 1e-12 * r.norm());
        const Eigen::VectorXd gfd = ValueGradientFd(problem);
        INFO("gradient error " << (g - gfd).norm() / gfd.norm());
        CHECK((g - gfd).norm() < 1e-6 * gfd.norm());
        Eigen::SparseMatrix<double> H0;
        Eigen::VectorXd g0;
        plain.problem.Evaluate(&g0, &H0, PsdProjection::None);
        CHECK((Eigen::MatrixXd(H) - Eigen::MatrixXd(H0)).norm() == 0.0);  // the loads are linear
        // A trial's value is the one evaluated after committing it, bit for bit.
        Eigen::VectorXd d(12);
        d << 1e-4, -2e-4, -1e-3, 3e-3, -1e-3, 2e-3, -1e-4, 2e-4, -5e-4, 1e-3, 2e-3, -1e-3;
        double fTrial = 0.0;
        Eigen::VectorXd gTrial, gCommitted;
        REQUIRE(problem.EvaluateAtStep(d, &fTrial, &gTrial, nullptr, PsdProjection::None));
        CHECK(fTrial == problem.Value(d));
        problem.Commit(d);
        CHECK(fTrial == problem.Evaluate(&gCommitted, nullptr, PsdProjection::None));
        CHECK(std::memcmp(gTrial.data(), gCommitted.data(), sizeof(double) * 12) == 0);
      }
    }
  }
}

TEST_CASE("rigid stage: with applied torques both solvers reach the residual's root",
          "[core][applied_loads]") {
  // Projected Newton on the minimizers' value (the torques' work along the committed iterates)
  // and residual Newton find the same stage solution: r = 0 with the torques in it.
  Stage a(DissipationMode::ExplicitNormals, true, true, true);
  Stage b(DissipationMode::ExplicitNormals, true, true, true);
  NonlinearSolverParams params;
  const SolverStats sa = MinimizeNewton(a.problem, params, a.f.hand.dt, nullptr);
  const SolverStats sb = SolveResidualNewton(b.problem, params, b.f.hand.dt, nullptr);
  REQUIRE(sa.status == StageStatus::Converged);
  REQUIRE(sb.status == StageStatus::Converged);
  Eigen::VectorXd ra, rb, r0;
  a.problem.EvaluateResidual(&ra, nullptr);
  b.problem.EvaluateResidual(&rb, nullptr);
  Stage start(DissipationMode::ExplicitNormals, true, true, true);
  start.problem.EvaluateResidual(&r0, nullptr);
  CHECK(ra.lpNorm<Eigen::Infinity>() < 1e-6 * r0.lpNorm<Eigen::Infinity>());
  CHECK(rb.lpNorm<Eigen::Infinity>() < 1e-6 * r0.lpNorm<Eigen::Infinity>());
  for (size_t i = 1; i < a.x.size(); ++i) {
    CHECK((a.Pose(i).p - b.Pose(i).p).norm() < 1e-9);
    CHECK((a.Pose(i).R - b.Pose(i).R).norm() < 1e-8);
  }
}
