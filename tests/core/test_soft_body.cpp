// Soft actors: the stage's derivatives with soft contact (every dissipation mode), the patch test,
// a cube at rest carrying its weight, momentum balance against a dynamic rigid body, node
// constraints, and the input errors.
#include <catch2/catch.hpp>
#include <Eigen/Eigenvalues>
#include <random>

#include "core/model/rigid_math.h"
#include "core/scene.h"
#include "core/dynamics/scene_stage.h"
#include "derivative_check.h"
#include "kind_stage.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

std::shared_ptr<const TetMesh> TetCube(double half, int cells) {
  return std::make_shared<TetMesh>(
      MakeTetBox(Eigen::Vector3d::Constant(half), Eigen::Vector3i::Constant(cells)));
}

SoftActorDesc SoftCube(double half, int cells, const Eigen::Vector3d& position) {
  SoftActorDesc d;
  d.name = "soft";
  d.mesh = TetCube(half, cells);
  d.position = position;
  d.material.youngsModulus = 1e5;
  d.material.poissonRatio = 0.3;
  d.material.density = 1000.0;
  return d;
}

// The sliding tests' cube: 0.1 m, 3 × 3 × 3 cells, E = 1e6 Pa, β = 0.01 s, penalty 1e8 Pa/m,
// Coulomb coefficient mu.
SoftActorDesc SlidingSoftCube(const Eigen::Vector3d& position, double mu) {
  SoftActorDesc d = SoftCube(0.05, 3, position);
  d.material.youngsModulus = 1e6;
  d.material.stiffnessDamping = 0.01;
  d.contact.penaltyCoefficient = 1e8;
  d.contact.coulombFrictionCoefficient = mu;
  return d;
}

// A soft cube (2 × 2 × 2 cells, one node pinned) pressed 2 mm into a static plane with a dynamic
// rigid box pressed 2 mm into its top; everything sliding; stiffness damping on.
struct SoftStageFixture {
  test::HandStage hand;

  SoftStageFixture() {
    Error e;
    RigidActorDesc ground = test::StaticGround(1e5, 0.5);
    ground.contact.normalViscousDampingCoefficient = 0.5;
    ground.contact.viscousFrictionCoefficient = 0.2;
    hand.AddRigid(ground, {}, {}, {});
    RigidActorDesc box = test::Cube(1e5, 0.4, 0.5);
    box.contact.viscousFrictionCoefficient = 0.2;
    const RigidPose pose = {Eigen::Vector3d(0.01, 0.0, 0.298),
                            ExpSo3(Eigen::Vector3d(0.01, -0.02, 0.2))};
    hand.AddRigid(box, pose,
                  {pose.p - hand.dt * Eigen::Vector3d(0.2, 0.05, -0.1),
                   ExpSo3(Eigen::Vector3d(0, 0, -0.02)) * pose.R},
                  {pose.p + Eigen::Vector3d(0.001, 0, -0.001), pose.R});

    SoftActorDesc d = SoftCube(0.1, 2, Eigen::Vector3d(0, 0, 0.1));
    d.contact.penaltyCoefficient = 1e5;
    d.contact.normalViscousDampingCoefficient = 0.5;
    d.contact.viscousFrictionCoefficient = 0.2;
    d.material.stiffnessDamping = 0.01;
    d.constraints.push_back({{13}, {}});  // the centre node, pinned
    SoftBodyModel m;
    SoftBodyState s;
    REQUIRE(BuildSoftBody(d, "", &m, &s, &e));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1e-3, 1e-3);
    Eigen::VectorXd xc = s.x;
    for (Eigen::Index i = 0; i < xc.size(); ++i) xc[i] += u(rng);
    for (int a = 0; a < m.NumNodes(); ++a) xc[3 * a + 2] -= 0.002;
    SoftStageTarget t;
    t.x0 = xc;
    for (int a = 0; a < m.NumNodes(); ++a)
      t.x0.segment<3>(3 * a) -= hand.dt * Eigen::Vector3d(0.15, -0.05, -0.1);
    t.xLast = t.x0;
    t.xHat = xc + Eigen::VectorXd::Constant(xc.size(), 2e-4);
    hand.AddSoft(m, s, t, xc);
    hand.Finish();
    REQUIRE(hand.numDofs == 6 + 3 * m.numFree);
  }
};

// The stage's residual Jacobian against central differences of its residual (every mode) and,
// for a potential stage, its gradient against differences of its value; both fixtures press
// more than 20 samples into contact. Returns the residual at the current state.
Eigen::VectorXd CheckStageDerivatives(SceneStageProblem& problem, int numDofs) {
  Eigen::VectorXd r;
  Eigen::SparseMatrix<double> J;
  problem.EvaluateResidual(&r, &J);
  const ContactStats& st = problem.LastContactStats();
  INFO("active samples " << st.activeSamples << ", dissipative " << st.dissipativeSamples);
  REQUIRE(st.activeSamples > 20);
  REQUIRE(st.dissipativeSamples > 20);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(numDofs);
  const Eigen::MatrixXd Jfd = FiniteDifferenceJacobian(
      [&](const Eigen::VectorXd& d) {
        Eigen::VectorXd rr;
        problem.Residual(d, &rr);
        return rr;
      },
      zero, 1e-7);
  const double err = (Eigen::MatrixXd(J) - Jfd).norm() / Jfd.norm();
  INFO("residual Jacobian error " << err);
  CHECK(err < 1e-6);
  if (problem.IsPotential()) {
    Eigen::VectorXd g;
    problem.Evaluate(&g, nullptr, PsdProjection::None);
    const Eigen::VectorXd gfd = FiniteDifferenceGradient(
        [&](const Eigen::VectorXd& d) { return problem.Value(d); }, zero, 1e-7);
    INFO("gradient error " << (g - gfd).norm() / gfd.norm());
    CHECK((g - gfd).norm() < 1e-6 * gfd.norm());
  }
  return r;
}

}  // namespace

TEST_CASE("soft stage: gradient, Hessian and residual Jacobian with soft contact",
          "[core][soft][gradient][dissipation]") {
  for (DissipationMode mode : {DissipationMode::ExplicitNormals, DissipationMode::ReconstructedLoad,
                               DissipationMode::ImplicitLoad}) {
    DYNAMIC_SECTION(ToString(mode)) {
      SoftStageFixture f;
      StageDissipation diss;
      diss.enabled = true;
      diss.mode = mode;
      std::vector<Eigen::VectorXd> x = f.hand.x;
      SceneStageProblem problem(f.hand.numDofs, f.hand.dt, &f.hand.pipeline,
                                f.hand.stage, &x, diss);
      const int numDofs = f.hand.numDofs;
      const Eigen::VectorXd r = CheckStageDerivatives(problem, numDofs);
      if (mode == DissipationMode::ExplicitNormals) {
        Eigen::VectorXd g;
        Eigen::SparseMatrix<double> H;
        problem.Evaluate(&g, &H, PsdProjection::None);
        CHECK((g - r).norm() < 1e-12 * r.norm());
        // The soft block of the Hessian is symmetric (the rigid rotation blocks carry the
        // non-symmetric trivialization only in the residual Jacobian).
        const Eigen::MatrixXd Hd(H);
        const Eigen::MatrixXd Hs = Hd.bottomRightCorner(numDofs - 6, numDofs - 6);
        CHECK((Hs - Hs.transpose()).norm() < 1e-10 * Hs.norm());
        // Projected: positive semi-definite.
        problem.Evaluate(&g, &H, PsdProjection::Clamp);
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig{Eigen::MatrixXd(H)};
        CHECK(eig.eigenvalues().minCoeff() > -1e-8 * eig.eigenvalues().cwiseAbs().maxCoeff());
      }
    }
  }
}

TEST_CASE("soft: patch test, uniform stretch reproduces the analytic stress", "[core][soft]") {
  // A 3 × 3 × 3-cell block whose boundary nodes are held at x = F X: the free interior nodes must
  // settle at F X too, every tet carries F, and the force holding the x = +a face is P(F) e_x A.
  const double a = 0.1;
  SceneSettings settings;
  settings.gravity.setZero();
  settings.integrator = IntegrationMethod::BackwardEuler;
  Scene scene(settings);
  SoftActorDesc d = SoftCube(a, 3, Eigen::Vector3d::Zero());
  Eigen::Matrix3d F;
  F << 1.1, 0.05, 0.0, 0.0, 0.95, 0.02, 0.0, 0.0, 1.03;
  const TetMesh& mesh = *d.mesh;
  std::vector<int> interior;
  for (int i = 0; i < mesh.NumVertices(); ++i) {
    const Eigen::Vector3d& X = mesh.vertices[i];
    if (X.cwiseAbs().maxCoeff() > a - 1e-9) {
      d.constraints.push_back({{i}, {{0.0, (F - Eigen::Matrix3d::Identity()) * X}}});
    } else {
      interior.push_back(i);
    }
  }
  REQUIRE(interior.size() == 8);
  Error e;
  const ActorHandle h = scene.AddSoftActor(d, &e);
  REQUIRE(e.ok());
  for (int k = 0; k < 6; ++k) {  // quasi-static: Δt = 10 s makes the inertia negligible
    StepReport rep;
    REQUIRE(scene.Step(10.0, &rep, &e));
    REQUIRE(rep.status == StageStatus::Converged);
  }
  const SoftBodyModel& m = scene.SoftModel(h);
  const Eigen::VectorXd& x = scene.SoftState(h).x;
  double posErr = 0.0;
  for (int i : interior)
    posErr = std::max(posErr, (x.segment<3>(3 * i) - F * mesh.vertices[i]).norm());
  INFO("interior position error " << posErr << " m");
  CHECK(posErr < 1e-9);
  // The nodal forces that hold the boundary, f_a = ∂E/∂x_a, must be those of the uniform stress
  // P(F): by the virial identity Σ_a f_a X_aᵀ = ∮ P N Xᵀ dA = P Vol.
  Eigen::VectorXd grad = Eigen::VectorXd::Zero(x.size());
  for (int t = 0; t < mesh.NumTets(); ++t) {
    const Eigen::Vector4i& T = m.rest.tets[t];
    const Eigen::Vector3d xs[4] = {x.segment<3>(3 * T[0]), x.segment<3>(3 * T[1]),
                                   x.segment<3>(3 * T[2]), x.segment<3>(3 * T[3])};
    TetElasticTerm term;
    EvaluateStableNeoHookean(m.elements[t], m.lame, xs, 1, false, &term);
    const Eigen::Matrix3d Ds = (Eigen::Matrix3d() << xs[1] - xs[0], xs[2] - xs[0], xs[3] - xs[0])
                                   .finished();
    CHECK((Ds * m.elements[t].DmInv - F).norm() < 1e-9);
    for (int k = 0; k < 4; ++k) grad.segment<3>(3 * T[k]) += term.gradient.segment<3>(3 * k);
  }
  Eigen::Matrix3d virial = Eigen::Matrix3d::Zero();
  for (int i = 0; i < mesh.NumVertices(); ++i)
    virial += grad.segment<3>(3 * i) * mesh.vertices[i].transpose();
  const double volume = std::pow(2 * a, 3);
  const Eigen::Matrix3d P = StableNeoHookeanStress(F, m.lame);
  INFO("virial/V:\n" << virial / volume << "\nP:\n" << P);
  CHECK((virial / volume - P).norm() < 1e-9 * P.norm());
}

TEST_CASE("soft: a cube at rest on a plane carries its weight", "[core][soft][physics]") {
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BackwardEuler;
  Scene scene(settings);
  Error e;
  scene.AddRigidActor(test::StaticGround(1e6, 0.5), &e);
  SoftActorDesc d = SoftCube(0.1, 4, Eigen::Vector3d(0, 0, 0.1005));
  d.material.stiffnessDamping = 0.02;
  d.contact.penaltyCoefficient = 1e6;
  const ActorHandle h = scene.AddSoftActor(d, &e);
  REQUIRE(e.ok());
  double minDet = INFINITY;
  for (int k = 0; k < 200; ++k) {
    StepReport rep;
    REQUIRE(scene.Step(0.01, &rep, &e));
    REQUIRE(rep.status == StageStatus::Converged);
    minDet = std::min(minDet, rep.minDetF);
  }
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  for (const ContactSampleRecord& r : scene.ContactSamples()) {
    CHECK(r.colliding == h.index);
    CHECK(r.face >= 0);
    force += r.weight * (r.traction + r.friction + r.damping);
  }
  const double weight = scene.SoftModel(h).mass * 9.81;
  INFO("contact force " << force.transpose() << " N, weight " << weight << " N, speed "
                        << scene.CenterOfMassVelocity(h).transpose() << " m/s");
  CHECK(std::abs(force.z() - weight) < 1e-3 * weight);
  CHECK(force.head<2>().norm() < 1e-6 * weight);
  CHECK(minDet > 0.9);
  // The per-face traction field integrates to the same resultant.
  std::vector<Eigen::Vector3d> tractions;
  REQUIRE(scene.SoftFaceTractions(h, &tractions, &e));
  Eigen::Vector3d fromFaces = Eigen::Vector3d::Zero();
  for (size_t f = 0; f < tractions.size(); ++f)
    fromFaces += tractions[f] * scene.SoftModel(h).faceArea[f];
  CHECK((fromFaces - force).norm() < 1e-9 * weight);
}

// A soft cube (0.1 m, 3 × 3 × 3 cells, E = 1e6 Pa, β = 0.01 s) set on a plane and thrown at 1 m/s
// with μ = 0.3 slides to rest after v0²/(2 μ g) = 0.1699 m, like a rigid block: friction on its
// surface samples decelerates its centre of mass at μ g while it slides. Measured (Δt = 1e-3):
// BDF2 +0.74 % (reconstructed load), −0.06 % (current load); BackwardEuler with explicit normals
// +0.29 %; BDF2 with the current load at Δt = 1e-2: −0.11 % (the last two not asserted).
TEST_CASE("soft: a cube thrown along a plane slides v0^2 / (2 mu g)", "[core][soft][physics]") {
  const double mu = 0.3, v0 = 1.0;
  const double expected = v0 * v0 / (2 * mu * 9.81);
  for (int mode : {1, 2}) {
    DYNAMIC_SECTION(test::kModeNames[mode]) {
      SceneSettings settings;
      settings.integrator = IntegrationMethod::BDF2;
      settings.eval = test::EvalParamsForMode(mode);
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::StaticGround(1e8, mu), &e).IsValid());
      SoftActorDesc d = SlidingSoftCube(Eigen::Vector3d(0, 0, 0.05), mu);
      d.linearVelocity = Eigen::Vector3d(v0, 0, 0);
      const ActorHandle h = scene.AddSoftActor(d, &e);
      REQUIRE(e.ok());
      const double x0 = scene.CenterOfMass(h).x();
      for (int k = 0; k < 800; ++k) {
        StepReport rep;
        REQUIRE(scene.Step(1e-3, &rep, &e));
        REQUIRE(rep.status == StageStatus::Converged);
      }
      const double travelled = scene.CenterOfMass(h).x() - x0;
      INFO("slid " << travelled << " m (expected " << expected << "), velocity "
                   << scene.CenterOfMassVelocity(h).transpose() << " m/s");
      CHECK(std::abs(travelled - expected) < 0.015 * expected);
      // Stopped (it stops at about 0.34 s; what remains is its elastic rocking: measured
      // 9.2e-3 and 2.7e-3 m/s horizontally at 0.8 s).
      CHECK(scene.CenterOfMassVelocity(h).head<2>().norm() < 0.02);
    }
  }
}

// The same cube released on a 30° incline with μ = 0.3 (< tan 30°) slides down at
// g (sin θ − μ cos θ) = 2.3563 m/s². Measured (fit over 0.3–1 s): BDF2 at Δt = 1e-2 +7.3e-5
// (reconstructed load), +3.1e-5 (current load); at Δt = 1e-3 −4.2e-5, +7.5e-5.
TEST_CASE("soft: a cube slides down a 30 degree incline at g (sin - mu cos)", "[core][soft][physics]") {
  const double mu = 0.3, theta = M_PI / 6;
  const Eigen::Vector3d n(std::sin(theta), 0, std::cos(theta));
  const Eigen::Vector3d down(std::cos(theta), 0, -std::sin(theta));
  const double expected = 9.81 * (std::sin(theta) - mu * std::cos(theta));
  for (int mode : {1, 2}) {
    DYNAMIC_SECTION(test::kModeNames[mode]) {
      SceneSettings settings;
      settings.integrator = IntegrationMethod::BDF2;
      settings.eval = test::EvalParamsForMode(mode);
      Scene scene(settings);
      Error e;
      REQUIRE(scene.AddRigidActor(test::Ground(n, 1e8, mu, 0.0), &e).IsValid());
      SoftActorDesc d = SlidingSoftCube(0.05 * n, mu);
      d.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()));
      const ActorHandle h = scene.AddSoftActor(d, &e);
      REQUIRE(e.ok());
      const Eigen::Vector3d c0 = scene.CenterOfMass(h);
      Eigen::MatrixXd A(0, 3);
      std::vector<double> ts, ss;
      for (int k = 1; k <= 100; ++k) {
        StepReport rep;
        REQUIRE(scene.Step(1e-2, &rep, &e));
        REQUIRE(rep.status == StageStatus::Converged);
        if (scene.Time() >= 0.3 - 1e-9) {
          ts.push_back(scene.Time());
          ss.push_back((scene.CenterOfMass(h) - c0).dot(down));
        }
      }
      A.resize(ts.size(), 3);
      Eigen::VectorXd y(ts.size());
      for (size_t i = 0; i < ts.size(); ++i) {
        A.row(i) << 1.0, ts[i], ts[i] * ts[i];
        y[i] = ss[i];
      }
      const double a = 2 * A.colPivHouseholderQr().solve(y)[2];
      INFO("a = " << a << " m/s^2, expected " << expected);
      CHECK(std::abs(a - expected) < 0.005 * expected);
    }
  }
}

TEST_CASE("soft: momentum is balanced against a dynamic rigid body", "[core][soft][physics]") {
  // Gravity off: a soft cube thrown at a spinning rigid box. Contact forces are equal and
  // opposite, so every method keeps the linear momentum (up to the stage tolerance); angular
  // momentum is a quadratic invariant that the implicit midpoint rule keeps and Backward Euler
  // and BDF2 change by O(h²) per step (L_{n+1} − L_n = h Σ x_n × f_{n+1} for BE).
  for (IntegrationMethod method : {IntegrationMethod::BackwardEuler, IntegrationMethod::BDF2,
                                   IntegrationMethod::SymplecticDIRK12}) {
    DYNAMIC_SECTION(ToString(method)) {
      SceneSettings settings;
      settings.gravity.setZero();
      settings.integrator = method;
      settings.solver.absoluteTolerance = 1e-12;
      Scene scene(settings);
      Error e;
      RigidActorDesc box = test::Cube(1e5, 0.3, 0.0);
      box.position = Eigen::Vector3d(0.25, 0.03, 0.02);
      box.angularVelocity = Eigen::Vector3d(0.5, 1.0, -2.0);
      scene.AddRigidActor(box, &e);
      SoftActorDesc d = SoftCube(0.1, 2, Eigen::Vector3d::Zero());
      d.contact.penaltyCoefficient = 1e5;
      d.contact.coulombFrictionCoefficient = 0.3;
      d.linearVelocity = Eigen::Vector3d(1.0, 0.0, 0.0);
      scene.AddSoftActor(d, &e);
      REQUIRE(e.ok());
      const Eigen::Vector3d P0 = scene.TotalLinearMomentum();
      const Eigen::Vector3d L0 = scene.TotalAngularMomentum();
      int contactSteps = 0;
      for (int k = 0; k < 60; ++k) {
        StepReport rep;
        REQUIRE(scene.Step(2e-3, &rep, &e));
        REQUIRE(rep.status == StageStatus::Converged);
        contactSteps += rep.contact.activeSamples > 0;
      }
      CHECK(contactSteps > 5);
      const double dP = (scene.TotalLinearMomentum() - P0).norm() / P0.norm();
      const double dL = (scene.TotalAngularMomentum() - L0).norm() / L0.norm();
      INFO("relative momentum changes " << dP << ", " << dL << " over " << contactSteps
                                        << " steps in contact");
      CHECK(dP < 1e-9);
      if (method == IntegrationMethod::SymplecticDIRK12) CHECK(dL < 1e-9);
    }
  }
}

TEST_CASE("soft: pinned and driven nodes follow their paths", "[core][soft]") {
  SceneSettings settings;
  Scene scene(settings);
  SoftActorDesc d = SoftCube(0.1, 2, Eigen::Vector3d(0, 0, 0.5));
  std::vector<int> top, bottom;
  for (int i = 0; i < d.mesh->NumVertices(); ++i) {
    if (d.mesh->vertices[i].z() > 0.099) top.push_back(i);
    if (d.mesh->vertices[i].z() < -0.099) bottom.push_back(i);
  }
  d.constraints.push_back({top, {}});
  d.constraints.push_back({bottom, {{0.0, Eigen::Vector3d::Zero()},
                                    {0.1, Eigen::Vector3d(0, 0, -0.02)}}});
  Error e;
  const ActorHandle h = scene.AddSoftActor(d, &e);
  REQUIRE(e.ok());
  for (int k = 0; k < 20; ++k) {
    StepReport rep;
    REQUIRE(scene.Step(0.01, &rep, &e));
    REQUIRE(rep.status == StageStatus::Converged);
  }
  const SoftBodyModel& m = scene.SoftModel(h);
  const Eigen::VectorXd& x = scene.SoftState(h).x;
  for (int i : top) CHECK((x.segment<3>(3 * i) - m.rest.vertices[i]).norm() < 1e-14);
  for (int i : bottom)
    CHECK((x.segment<3>(3 * i) - m.rest.vertices[i] - Eigen::Vector3d(0, 0, -0.02)).norm() < 1e-14);
  // The stretched block hangs between them: its free nodes moved, none inverted.
  double minDet = INFINITY;
  ElasticEnergy(m, x, &minDet);
  CHECK(minDet > 0.5);
}

TEST_CASE("soft: bad input names the field and the rule", "[core][soft]") {
  Scene scene;
  Error e;
  SoftActorDesc d = SoftCube(0.1, 1, Eigen::Vector3d::Zero());
  d.material.poissonRatio = 0.5;
  CHECK(!scene.AddSoftActor(d, &e).IsValid());
  CHECK_THAT(e.message, Catch::Contains("poisson_ratio"));
  d = SoftCube(0.1, 1, Eigen::Vector3d::Zero());
  d.material.youngsModulus = -1;
  CHECK(!scene.AddSoftActor(d, &e).IsValid());
  CHECK_THAT(e.message, Catch::Contains("youngs_modulus"));
  d = SoftCube(0.1, 1, Eigen::Vector3d::Zero());
  d.constraints.push_back({{1000}, {}});
  CHECK(!scene.AddSoftActor(d, &e).IsValid());
  CHECK_THAT(e.message, Catch::Contains("constraints[0].nodes"));
  d = SoftCube(0.1, 1, Eigen::Vector3d::Zero());
  for (ColliderType t : {ColliderType::Sphere, ColliderType::Mesh, ColliderType::PointCloud}) {
    d.colliderType = t;  // the Mesh collider is for rigid actors and links only (spec)
    CHECK(!scene.AddSoftActor(d, &e).IsValid());
    CHECK_THAT(e.message, Catch::Contains("collider_type") && Catch::Contains(ToString(t)));
  }
  d = SoftCube(0.1, 1, Eigen::Vector3d::Zero());
  auto inverted = std::make_shared<TetMesh>(*d.mesh);
  std::swap(inverted->tets[0][0], inverted->tets[0][1]);
  d.mesh = inverted;
  CHECK(!scene.AddSoftActor(d, &e).IsValid());
  CHECK_THAT(e.message, Catch::Contains("inverted"));
  CHECK(scene.NumActors() == 0);
}

namespace {

// A soft cube B with an Sdf collider (experimental role); a rigid box pressed 2 mm into its top
// and a soft cube A pressed 2 mm into its +x side; everything moving. Stiffness damping off.
struct SoftColliderFixture {
  test::HandStage hand;

  SoftColliderFixture() {
    Error e;
    hand.gravity.setZero();
    RigidActorDesc box = test::Cube(1e5, 0.4, 0.5);
    box.contact.viscousFrictionCoefficient = 0.2;
    const RigidPose pose = {Eigen::Vector3d(0.013, 0.004, 0.198),
                            ExpSo3(Eigen::Vector3d(0.01, -0.02, 0.2))};
    hand.AddRigid(box, pose,
                  {pose.p - hand.dt * Eigen::Vector3d(0.2, 0.05, -0.1),
                   ExpSo3(Eigen::Vector3d(0, 0, -0.02)) * pose.R},
                  pose);

    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1e-3, 1e-3);
    const Eigen::Vector3d centers[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d(0.198, 0.03, 0.01)};
    const Eigen::Vector3d velocity[2] = {Eigen::Vector3d(0.05, 0.0, 0.02),
                                         Eigen::Vector3d(-0.1, 0.1, 0.05)};
    for (int k = 0; k < 2; ++k) {
      SoftActorDesc d = SoftCube(0.1, 2, centers[k]);
      d.contact.penaltyCoefficient = 1e5;
      d.contact.normalViscousDampingCoefficient = 0.5;
      d.contact.viscousFrictionCoefficient = 0.2;
      if (k == 0) d.colliderType = ColliderType::Sdf;
      d.gridSdf.minGridResolution = 24;
      SoftBodyModel m;
      SoftBodyState s;
      REQUIRE(BuildSoftBody(d, "", &m, &s, &e));
      Eigen::VectorXd xc = s.x;
      for (Eigen::Index i = 0; i < xc.size(); ++i) xc[i] += u(rng);
      SoftStageTarget t;
      t.x0 = xc;
      for (int a = 0; a < m.NumNodes(); ++a) t.x0.segment<3>(3 * a) -= hand.dt * velocity[k];
      t.xLast = t.x0;
      t.xHat = xc;
      hand.AddSoft(m, s, t, xc);
    }
    hand.Finish();
  }
};

}  // namespace

TEST_CASE("soft collider: gradient, Hessian and residual Jacobian of rigid and soft samples on a "
          "deformed grid SDF", "[core][soft][gradient][dissipation]") {
  for (DissipationMode mode : {DissipationMode::ExplicitNormals, DissipationMode::ReconstructedLoad,
                               DissipationMode::ImplicitLoad}) {
    DYNAMIC_SECTION(ToString(mode)) {
      SoftColliderFixture f;
      StageDissipation diss;
      diss.enabled = true;
      diss.mode = mode;
      std::vector<Eigen::VectorXd> x = f.hand.x;
      SceneStageProblem problem(f.hand.numDofs, f.hand.dt, &f.hand.pipeline,
                                f.hand.stage, &x, diss);
      const Eigen::VectorXd r = CheckStageDerivatives(problem, f.hand.numDofs);
      // Balanced: the contact forces sum to zero over all actors (no gravity, no inertia offset:
      // x̂ = x for the soft actors; the rigid box's inertia is removed by p̂ = p, R̂ = R).
      Eigen::Vector3d net = r.head<3>();
      for (Eigen::Index i = 6; i < r.size(); i += 3) net += r.segment<3>(i);
      INFO("net force " << net.transpose());
      CHECK(net.norm() < 1e-9 * r.norm());
    }
  }
}

TEST_CASE("soft collider: soft on soft keeps the momentum balance", "[core][soft][physics]") {
  // Gravity off: a soft cube thrown at a soft cube with an Sdf collider (and a rigid box thrown
  // at it from above). Forces through the deformed-SDF pullback are balanced on every stencil.
  for (bool explicitNormals : {false, true}) {
    DYNAMIC_SECTION((explicitNormals ? "explicit normals" : "reconstructed load")) {
      SceneSettings settings;
      settings.gravity.setZero();
      settings.integrator = IntegrationMethod::SymplecticDIRK12;
      settings.eval.explicitNormals = explicitNormals;
      // Conservation to 1e-9 needs stages solved well below it.
      settings.solver.absoluteTolerance = 1e-16;
      settings.solver.relativeTolerance = 1e-13;
      settings.solver.stepTolerance = 1e-12;
      Scene scene(settings);
      Error e;
      SoftActorDesc target = SoftCube(0.1, 3, Eigen::Vector3d::Zero());
      target.colliderType = ColliderType::Sdf;
      target.contact.penaltyCoefficient = 1e5;
      target.contact.coulombFrictionCoefficient = 0.3;
      const ActorHandle b = scene.AddSoftActor(target, &e);
      REQUIRE(e.ok());
      SoftActorDesc thrown = SoftCube(0.1, 2, Eigen::Vector3d(-0.21, 0.05, 0.03));
      thrown.contact.penaltyCoefficient = 1e5;
      thrown.contact.coulombFrictionCoefficient = 0.3;
      thrown.linearVelocity = Eigen::Vector3d(1.0, 0.0, 0.0);
      thrown.name = "thrown";
      scene.AddSoftActor(thrown, &e);
      RigidActorDesc box = test::Cube(1e5, 0.3, 0.0);
      box.position = Eigen::Vector3d(0.02, -0.03, 0.21);
      box.linearVelocity = Eigen::Vector3d(0.0, 0.0, -1.0);
      box.angularVelocity = Eigen::Vector3d(0.0, 0.0, 3.0);
      scene.AddRigidActor(box, &e);
      REQUIRE(e.ok());
      const Eigen::Vector3d P0 = scene.TotalLinearMomentum();
      const Eigen::Vector3d L0 = scene.TotalAngularMomentum();
      int contactSteps = 0;
      double minDet = INFINITY;
      for (int k = 0; k < 50; ++k) {
        StepReport rep;
        REQUIRE(scene.Step(2e-3, &rep, &e));
        REQUIRE(rep.status == StageStatus::Converged);
        contactSteps += rep.contact.activeSamples > 0;
        minDet = std::min(minDet, rep.minDetF);
      }
      CHECK(contactSteps > 20);
      CHECK(minDet > 0.5);
      // Both the soft and the rigid samples found the deformed collider.
      int fromSoft = 0, fromRigid = 0;
      for (const ContactSampleRecord& r : scene.ContactSamples())
        if (r.collider == b.index) (r.face >= 0 ? fromSoft : fromRigid) += 1;
      const double dP = (scene.TotalLinearMomentum() - P0).norm() / P0.norm();
      const double dL = (scene.TotalAngularMomentum() - L0).norm() / L0.norm();
      INFO("relative momentum changes " << dP << ", " << dL << "; samples on the soft collider: "
                                        << fromSoft << " soft, " << fromRigid << " rigid");
      CHECK(dP < 1e-9);
      CHECK(dL < 1e-9);
    }
  }
}
