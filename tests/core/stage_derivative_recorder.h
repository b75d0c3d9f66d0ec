// A stage recorder for derivative tests: takes the first stage a step solves and checks, at a
// point 1e-4 off its solution, the stage's gradient and exact Hessian against central differences
// of its value (a potential), or its residual Jacobian against differences of the residual (the
// residual modes), and the projected Hessian's smallest eigenvalue.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>

#include "core/dynamics/stage_recorder.h"
#include "derivative_check.h"
#include "optim/finite_difference.h"

namespace superdex {
namespace test {

class StageDerivativeRecorder : public StageRecorder {
 public:
  void BeginStep() override {}
  bool Supplies() const override { return false; }
  void Supply(const StageInputs&, const StageDissipation&, std::vector<Eigen::VectorXd>*) override {}
  bool Records() const override { return true; }
  void Record(const StageInputs& inputs, const StageDissipation& dissipation,
              const std::vector<Eigen::VectorXd>& solution) override {
    if (checked) return;
    checked = true;
    std::vector<Eigen::VectorXd> x = solution;
    SceneStageProblem problem = inputs.Problem(dissipation, &x);
    potential = problem.IsPotential();
    const int n = problem.NumDofs();
    Eigen::VectorXd away(n);
    for (int i = 0; i < n; ++i) away[i] = 1e-4 * std::sin(1.0 + 2.0 * i);
    problem.Commit(away);
    dofs = n;
    if (!potential) {  // the residual modes: J against differences of the residual
      Eigen::VectorXd r;
      Eigen::SparseMatrix<double> J;
      problem.EvaluateResidual(&r, &J);
      active = problem.LastContactStats().activeSamples;
      const Eigen::MatrixXd Jfd = FiniteDifferenceJacobian(
          [&](const Eigen::VectorXd& d) {
            Eigen::VectorXd rd;
            problem.Residual(d, &rd);
            return rd;
          },
          Eigen::VectorXd::Zero(n), residualStep);
      residualError = (Eigen::MatrixXd(J) - Jfd).norm() / Jfd.norm();
      return;
    }
    Eigen::VectorXd g;
    Eigen::SparseMatrix<double> H, Hp;
    problem.Evaluate(&g, &H, PsdProjection::None);
    active = problem.LastContactStats().activeSamples;
    result = CheckDerivatives([&](const Eigen::VectorXd& d) { return problem.Value(d); }, g,
                                    Eigen::MatrixXd(H), 1e-6);
    Eigen::VectorXd gp;
    problem.Evaluate(&gp, &Hp, PsdProjection::Clamp);
    minProjected =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(Hp)).eigenvalues().minCoeff();
  }
  /// The checks of a stage with active contact: a potential (explicit normals) or not, its
  /// gradient and exact Hessian within 1e-6 and 1e-5 relative and its projected Hessian PSD
  /// (-1e-8), or its residual Jacobian within 5e-9 relative.
  void CheckAccuracy(bool explicitNormals) const {
    CHECK(potential == explicitNormals);
    CHECK(active > 0);
    if (explicitNormals) {
      INFO("gradient " << result.gradientError << ", Hessian " << result.hessianError);
      CHECK(result.gradientError < 1e-6);
      CHECK(result.hessianError < 1e-5);
      CHECK(minProjected > -1e-8);
    } else {
      INFO("residual Jacobian " << residualError);
      CHECK(residualError < 5e-9);
    }
  }
  double residualStep = 1e-7;  ///< the residual's central differences' step
  bool checked = false, potential = false;
  int active = 0, dofs = 0;
  double minProjected = 0.0, residualError = 0.0;
  DerivativeCheck result;
};

}  // namespace test
}  // namespace superdex
