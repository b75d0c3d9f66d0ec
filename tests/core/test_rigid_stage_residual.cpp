#include <catch2/catch.hpp>

#include "core/rigid_math.h"
#include "core/scene_stage.h"
#include "derivative_check.h"

using namespace superdex;

namespace {

struct Fixture {
  std::vector<RigidBodyModel> models;
  std::vector<int> dofOffset;
  StageTargets targets;
  std::vector<RigidPose> poses;
  ContactPipeline pipeline;

  Fixture() {
    auto build = [&](RigidShape shape, bool dynamic, Eigen::Vector3d p, Eigen::Matrix3d R) {
      RigidActorDesc d;
      d.name = "a" + std::to_string(models.size());
      d.dynamic = dynamic;
      d.shape = shape;
      d.contact.penaltyCoefficient = 1e6;
      d.contact.normalViscousDampingCoefficient = 0.8;
      d.contact.viscousFrictionCoefficient = 0.1;
      RigidBodyModel m;
      RigidBodyState s;
      Error e;
      REQUIRE(BuildRigidBody(d, "", &m, &s, &e));
      models.push_back(m);
      poses.push_back({p, R});
    };
    RigidShape plane;
    plane.kind = RigidShapeKind::Plane;
    build(plane, false, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
    RigidShape box;
    box.kind = RigidShapeKind::Box;
    box.halfExtents = Eigen::Vector3d(0.1, 0.1, 0.1);
    build(box, true, Eigen::Vector3d(0.0, 0.0, 0.098), ExpSo3(Eigen::Vector3d(0.02, -0.01, 0.3)));
    build(box, true, Eigen::Vector3d(0.01, 0.02, 0.296), ExpSo3(Eigen::Vector3d(-0.01, 0.02, 0.1)));
    dofOffset = {-1, 0, 6};
    targets.dt = 0.01;
    for (const RigidPose& p : poses) {
      // Sliding along x at 0.2 m/s, spinning slowly; the stage start one step back.
      RigidStageStart s;
      s.p = p.p - targets.dt * Eigen::Vector3d(0.2, 0.05, -0.1);
      s.R = ExpSo3(Eigen::Vector3d(0, 0, -0.02)) * p.R;
      s.Rinv = s.R.inverse();
      if (&p == &poses[0]) { s.p = p.p; s.R = p.R; s.Rinv = p.R.transpose(); }
      s.last = {s.p, s.R};
      targets.start.push_back(s);
      targets.pHat.push_back(p.p + Eigen::Vector3d(0.001, 0, -0.001));
      targets.RHat.push_back(p.R);
    }
    pipeline.Configure(&models);
  }
};

}  // namespace

TEST_CASE("rigid stage: residual Jacobian and potential gradient with dissipation",
          "[core][gradient][dissipation]") {
  for (DissipationMode mode : {DissipationMode::ExplicitNormals, DissipationMode::ReconstructedLoad,
                               DissipationMode::ImplicitLoad}) {
    DYNAMIC_SECTION(ToString(mode)) {
      Fixture f;
      StageDissipation diss;
      diss.enabled = true;
      diss.mode = mode;
      std::vector<RigidPose> poses = f.poses;
      SceneStageProblem problem(f.models, f.dofOffset, 12, f.targets, Eigen::Vector3d(0, 0, -9.81),
                                &f.pipeline, &poses, diss);
      CHECK(problem.IsPotential() == (mode == DissipationMode::ExplicitNormals));
      Eigen::VectorXd r;
      Eigen::SparseMatrix<double> J;
      problem.EvaluateResidual(&r, &J);
      REQUIRE(r.size() == 12);
      const Eigen::MatrixXd Jfd = FiniteDifferenceJacobian(
          [&](const Eigen::VectorXd& d) {
            Eigen::VectorXd rr;
            problem.Residual(d, &rr);
            return rr;
          },
          Eigen::VectorXd::Zero(12), 1e-7);
      const double err = (Eigen::MatrixXd(J) - Jfd).norm() / Jfd.norm();
      INFO("residual Jacobian error " << err);
      CHECK(err < 1e-6);
      if (mode == DissipationMode::ExplicitNormals) {
        Eigen::VectorXd g;
        problem.Evaluate(&g, nullptr, PsdProjection::None);
        CHECK((g - r).norm() < 1e-12 * r.norm());
        const Eigen::VectorXd gfd = FiniteDifferenceGradient(
            [&](const Eigen::VectorXd& d) { return problem.Value(d); }, Eigen::VectorXd::Zero(12),
            1e-7);
        INFO("gradient error " << (g - gfd).norm() / gfd.norm());
        CHECK((g - gfd).norm() < 1e-6 * gfd.norm());
      }
    }
  }
}
