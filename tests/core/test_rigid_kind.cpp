// The rigid kind (core/model/rigid_kind.h): a rigid body carried by the generic actor layer's
// manifold hooks (tangent steps, the exponential retraction, the residual Jacobian's
// trivialization, the DIRK rotation rules) and by the one contact assembler (rotating samples and
// rotating collider frames).
//
// Expectations:
//   - its stage energy's gradient and Hessian in the tangent step δ = [δp, δθ] equal central
//     differences of Φ(q ⊕ δ);
//   - scenes of rigid kinds added by AddActor(RigidKind::Build(desc)) follow the same scenes of
//     rigid actors added by AddRigidActor(desc) (which builds a RigidKind too, with the scene's
//     own bookkeeping: the description, shared sample sets, held static bodies, the snapshot
//     layout) to within the stage solver's tolerance. Both scenes solve every stage by Newton
//     from the same start (no warm start, no closed-form free stages), and converge to a gradient
//     of at most 1e-10 of the first one. (These twins were written against the former built-in
//     rigid implementation, per-body arrays and regrouped closed-form pair sums; the recordings of
//     tests/regression, made with it, carry that comparison now);
//   - with the stage policy's shortcuts on (the motion's warm start with its trust bound and
//     contact step limit, the closed-form free stage), through the kind's hooks (PredictStage,
//     TangentBetween, ForceChange, FreeStageMinimizer, the assembler's step limit), a rigid kind
//     takes the built-in body's path: the same closed-form stages and Newton iterations, and the
//     same states to the tolerances above.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>

#include "core/model/rigid_kind.h"
#include "core/model/rigid_math.h"
#include "core/scene.h"
#include "core/sensitivity/adjoint.h"
#include "core/sensitivity/sensitivity.h"
#include "derivative_check.h"
#include "scene_builders.h"
#include "sensitivity_scenes.h"

using namespace superdex;

namespace {

SceneSettings SameNewtonPath(IntegrationMethod method, int mode) {
  SceneSettings s;
  s.integrator = method;
  s.eval = test::EvalParamsForMode(mode);
  s.warmStart = false;
  s.closedFormFreeStages = false;
  return s;
}

// A scene of built-in rigid actors and the same scene with every actor of `asKind` added as a
// rigid kind.
struct Twin {
  Scene builtIn, kinds;
  std::vector<ActorHandle> a, b;
  Twin(const SceneSettings& s) : builtIn(s), kinds(s) {}
  void Add(const RigidActorDesc& d, bool asKind) {
    Error error;
    a.push_back(builtIn.AddRigidActor(d, &error));
    REQUIRE(a.back().IsValid());
    if (asKind) {
      std::unique_ptr<RigidKind> k = RigidKind::Build(d, &error);
      REQUIRE(k);
      b.push_back(kinds.AddActor(std::move(k), &error, d.contactLayer));
    } else {
      b.push_back(kinds.AddRigidActor(d, &error));
    }
    REQUIRE(b.back().IsValid());
  }
  // A soft actor added to both scenes: its handles in the built-in and in the kinds' scene.
  std::pair<ActorHandle, ActorHandle> AddSoft(const SoftActorDesc& d) {
    Error error;
    const ActorHandle s0 = builtIn.AddSoftActor(d, &error);
    const ActorHandle s1 = kinds.AddSoftActor(d, &error);
    REQUIRE(s0.IsValid());
    REQUIRE(s1.IsValid());
    return {s0, s1};
  }
  // The largest difference of the soft actor's node positions [m] and velocities [m/s].
  Eigen::Vector2d SoftDifference(const std::pair<ActorHandle, ActorHandle>& s) const {
    const SoftBodyState& x = builtIn.SoftState(s.first);
    const SoftBodyState& y = kinds.SoftState(s.second);
    return {(x.x - y.x).lpNorm<Eigen::Infinity>(), (x.v - y.v).lpNorm<Eigen::Infinity>()};
  }
  RigidBodyState KindsState(size_t i) const {
    return kinds.IsKind(b[i]) ? RigidKind::Unpack(kinds.KindStateOf(b[i])) : kinds.State(b[i]);
  }
  // Steps both; returns the largest differences over the dynamic actors of position [m], of
  // rotation (‖ΔR‖_F), of velocity [m/s] and of Ṙ [1/s].
  // Summed over the steps run: Newton iterations and closed-form free stages of each scene.
  int iterations[2] = {0, 0}, freeStages[2] = {0, 0}, krylov[2] = {0, 0};
  Eigen::Vector4d Run(int steps, double dt) {
    Eigen::Vector4d worst = Eigen::Vector4d::Zero();
    for (int n = 0; n < steps; ++n) {
      StepReport ra, rb;
      Error error;
      REQUIRE(builtIn.Step(dt, &ra, &error));
      REQUIRE(kinds.Step(dt, &rb, &error));
      REQUIRE(ra.status == StageStatus::Converged);
      REQUIRE(rb.status == StageStatus::Converged);
      iterations[0] += ra.newtonIterations;
      iterations[1] += rb.newtonIterations;
      freeStages[0] += ra.freeStages;
      freeStages[1] += rb.freeStages;
      krylov[0] += ra.krylovIterations;
      krylov[1] += rb.krylovIterations;
      for (size_t i = 0; i < a.size(); ++i) {
        if (!builtIn.Model(a[i]).dynamic) continue;
        const RigidBodyState& x = builtIn.State(a[i]);
        const RigidBodyState y = KindsState(i);
        worst[0] = std::max(worst[0], (x.p - y.p).norm());
        worst[1] = std::max(worst[1], (x.R - y.R).norm());
        worst[2] = std::max(worst[2], (x.v - y.v).norm());
        worst[3] = std::max(worst[3], (x.Rdot - y.Rdot).norm());
      }
    }
    return worst;
  }
};

// The tolerances of a contact scene's twins: |Δp| [m], ‖ΔR‖_F, |Δv| [m/s], |ΔṘ| [1/s].
void CheckFollowsInContact(const Eigen::Vector4d& worst) {
  CHECK(worst[0] < 1e-8);
  CHECK(worst[1] < 1e-7);
  CHECK(worst[2] < 1e-6);
  CHECK(worst[3] < 1e-5);
}

// Twins whose pairs are all of one layer sum the same terms in the same order (the kinds' pairs
// come from the broad phase's overlaps as the rigid pairs do, scatter as the same 6 × 6 blocks,
// and their frames and sample bodies are formed from the same poses): the same bits.
void CheckBitIdentical(const Eigen::Vector4d& worst) { CHECK(worst == Eigen::Vector4d::Zero()); }

RigidActorDesc TumblingBox() {
  RigidActorDesc d;
  d.name = "box";
  d.shape.kind = RigidShapeKind::Box;
  d.shape.halfExtents = Eigen::Vector3d(0.3, 0.2, 0.1);
  d.mass = 2.0;
  d.position = Eigen::Vector3d(0.1, -0.2, 1.0);
  d.linearVelocity = Eigen::Vector3d(0.3, 0.0, 1.0);
  // About the intermediate axis, slightly off: the Dzhanibekov flip.
  d.angularVelocity = Eigen::Vector3d(0.05, 6.0, 0.02);
  return d;
}

}  // namespace

TEST_CASE("the rigid kind's stage energy: gradient and Hessian in δ = [δp, δθ] by differences",
          "[core][kind][rigid][derivatives]") {
  // With an applied force ramp (its potential −F(t_i)·p at a stage time between the keyframes).
  RigidActorDesc d = TumblingBox();
  d.appliedForce = {{0.0, Eigen::Vector3d(1.0, -2.0, 0.5)}, {1.0, Eigen::Vector3d(3.0, 0.0, -1.0)}};
  Error error;
  const std::unique_ptr<RigidKind> body = RigidKind::Build(d, &error);
  REQUIRE(body);
  Eigen::VectorXd q = RigidKind::Pack(RigidBodyState()).x;
  q.head<3>() = Eigen::Vector3d(0.2, -0.1, 0.7);
  const Eigen::Matrix3d R = ExpSo3(Eigen::Vector3d(0.4, -0.9, 0.3));
  q.tail<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(R.data());
  KindStageData stage;
  stage.dt = 0.01;
  stage.time = 0.3;
  stage.gravity = Eigen::Vector3d(0.3, -0.2, -9.81);
  // An inertial target whose R̂ is an affine combination of rotations, not a rotation.
  const Eigen::Matrix3d Rhat = 1.5 * ExpSo3(Eigen::Vector3d(0.41, -0.88, 0.33)) -
                               0.5 * ExpSo3(Eigen::Vector3d(0.38, -0.93, 0.29));
  stage.qHat = q;
  stage.qHat.head<3>() += Eigen::Vector3d(0.01, 0.02, -0.005);
  stage.qHat.tail<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(Rhat.data());
  Eigen::VectorXd g = Eigen::VectorXd::Zero(6);
  std::vector<Eigen::Triplet<double>> triplets;
  body->StageEnergy(stage, q, 2, PsdProjection::None, &g, &triplets);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(6, 6);
  for (const auto& t : triplets) H(t.row(), t.col()) += t.value();
  auto f = [&](const Eigen::VectorXd& delta) {
    Eigen::VectorXd moved;
    body->Retract(q, delta, &moved);
    return body->StageEnergy(stage, moved, 0, PsdProjection::None, nullptr, nullptr);
  };
  const test::DerivativeCheck c = test::CheckDerivatives(f, g, H, 1e-5);
  CHECK(c.gradientError < 1e-7);
  CHECK(c.hessianError < 1e-5);
  // The retraction stays on SO(3) and is the identity at δ = 0.
  Eigen::VectorXd moved;
  body->Retract(q, Eigen::VectorXd::Zero(6), &moved);
  CHECK(moved == q);
  Eigen::VectorXd delta(6);
  delta << 0.1, 0.2, 0.3, 0.5, -0.4, 0.2;
  body->Retract(q, delta, &moved);
  const Eigen::Matrix3d Rm = RigidKind::PoseOf(moved).R;
  CHECK((Rm.transpose() * Rm - Eigen::Matrix3d::Identity()).norm() < 1e-14);
}

TEST_CASE("a tumbling rigid kind follows the built-in rigid actor under BDF and DIRK",
          "[core][kind][rigid]") {
  // Torque-free flight through the Dzhanibekov flip (1 s at Δt = 1e-2, no contact).
  for (IntegrationMethod method :
       {IntegrationMethod::BDF2, IntegrationMethod::BDF3, IntegrationMethod::DIRK22,
        IntegrationMethod::DIRK33, IntegrationMethod::SymplecticDIRK22}) {
    SceneSettings s = SameNewtonPath(method, 1);
    s.gravity = Eigen::Vector3d(0, 0, -9.81);
    Twin twin(s);
    twin.Add(TumblingBox(), true);
    const Eigen::Vector4d worst = twin.Run(100, 1e-2);
    INFO("method " << static_cast<int>(method) << ": |Δp| " << worst[0] << " |ΔR| " << worst[1]
                   << " |Δv| " << worst[2] << " |ΔṘ| " << worst[3]);
    CheckBitIdentical(worst);
  }
}

TEST_CASE("a rigid kind cube lands and slides on a plane as the built-in cube does",
          "[core][kind][rigid][contact]") {
  // A cube released 10 µm above a plane tilted by 0.3 rad with μ = 0.2 (it slides) and normal
  // damping, 0.4 s at Δt = 5e-3, in every dissipation mode; the ground is a static rigid kind in
  // one twin and a built-in static plane in another.
  const double theta = 0.3;
  const Eigen::Vector3d n(std::sin(theta), 0, std::cos(theta));
  for (int mode = 0; mode < 3; ++mode)
    for (bool groundAsKind : {false, true}) {
      Twin twin(SameNewtonPath(IntegrationMethod::BDF2, mode));
      twin.Add(test::Ground(n, 1e8, 0.2, 20.0), groundAsKind);
      RigidActorDesc cube = test::CubeOnIncline(theta, 1e8, 0.2, 20.0);
      cube.linearVelocity = Eigen::Vector3d(0.0, 0.3, 0.0);  // sideways: a curved path
      twin.Add(cube, true);
      const Eigen::Vector4d worst = twin.Run(80, 5e-3);
      INFO(test::kModeNames[mode] << (groundAsKind ? ", kind ground" : ", built-in ground")
                                  << ": |Δp| " << worst[0] << " |ΔR| " << worst[1] << " |Δv| "
                                  << worst[2] << " |ΔṘ| " << worst[3]);
      CheckBitIdentical(worst);
      // It slides: friction opposes the whole slip velocity, of which the downhill part is one
      // component, so the downhill acceleration lies between g (sin θ − μ cos θ) (pure downhill
      // slip) and g sin θ (no friction); 0.95 allows for the landing's first steps.
      const RigidBodyState end = twin.KindsState(1);
      const double down = end.v.dot(Eigen::Vector3d(std::cos(theta), 0, -std::sin(theta)));
      CHECK(down > 0.95 * 9.81 * (std::sin(theta) - 0.2 * std::cos(theta)) * 0.4);
      CHECK(down < 9.81 * std::sin(theta) * 0.4);
    }
}

TEST_CASE("a cube driven flat into a plane kind keeps the built-in contact set",
          "[core][kind][rigid][contact]") {
  // A 0.2 m, 1 kg cube (surface resolution 2, k = 1e6 Pa/m, frictionless, undamped: no
  // dissipation) dropped flat from 0.4 m onto a plane under BDF2 with the stage policy's defaults.
  // At the deepest point (17 mm, t ≈ 0.293 s) the side faces' lowest samples, 16.7 mm above the
  // bottom, enter the penalty band with normals perpendicular to the plane: their alignment s is
  // the round-off of the cube's rotation (about 1e-9, the size of the test's allowance). The test
  // reads the normals at x_n for every collider frame, so a stage's contact set does not change
  // with the iterate; read at the iterate, the set flipped inside a line search and the stage at
  // 0.2929 s did not converge.
  for (bool groundAsKind : {false, true}) {
    SceneSettings settings;
    settings.integrator = IntegrationMethod::BDF2;
    Twin twin(settings);
    twin.Add(test::Ground(Eigen::Vector3d::UnitZ(), 1e6, 0.0, 0.0), groundAsKind);
    RigidActorDesc cube = test::Cube(1e6, 0.0, 0.0);
    cube.position = Eigen::Vector3d(0.0, 0.0, 0.5);
    twin.Add(cube, true);
    const Eigen::Vector4d worst = twin.Run(3000, 1e-4);  // Run requires every stage converged
    INFO((groundAsKind ? "kind ground" : "built-in ground") << ": |Δp| " << worst[0]);
    CheckBitIdentical(worst);
    CHECK(twin.KindsState(1).v.z() > 0.0);  // past the deepest point, on the rebound
  }
}

TEST_CASE("a stack of rigid kinds and built-in boxes follows the all-built-in stack",
          "[core][kind][rigid][contact]") {
  // Three boxes on a ground, alternately kinds and built-in actors, so that every ordered pair
  // type meets: kind on built-in field, built-in on kind field, kind on kind field.
  for (int mode = 0; mode < 3; ++mode) {
    Twin twin(SameNewtonPath(IntegrationMethod::BDF2, mode));
    twin.Add(test::StaticGround(1e8, 0.4), true);
    for (int k = 0; k < 3; ++k) {
      RigidActorDesc box = test::Cube(1e8, 0.4, 10.0);
      box.name = "box" + std::to_string(k);
      box.position = Eigen::Vector3d(0.01 * k, -0.005 * k, 0.1 + 0.2 * k + 1e-4 * (k + 1));
      box.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.05 * k, Eigen::Vector3d::UnitZ()));
      twin.Add(box, k != 1);
    }
    const Eigen::Vector4d worst = twin.Run(60, 5e-3);
    INFO(test::kModeNames[mode] << ": |Δp| " << worst[0] << " |ΔR| " << worst[1] << " |Δv| "
                                << worst[2] << " |ΔṘ| " << worst[3]);
    // Not the same bits: the built-in pairs are summed before the kinds' pairs.
    CheckFollowsInContact(worst);
  }
}

TEST_CASE("with warm start and closed-form free stages a rigid kind takes the built-in path",
          "[core][kind][rigid][contact]") {
  // A tumbling box dropped 0.3 m onto a static ground (free flight in closed form, then the
  // landing's warm-started, step-limited stages), and a cube sliding sideways on a 0.3 rad incline
  // (warm start exact for the steady slide), and three boxes landing side by side (the line
  // search by parts), under BDF2 and DIRK22, with the default settings.
  const double theta = 0.3;
  const Eigen::Vector3d n(std::sin(theta), 0, std::cos(theta));
  for (IntegrationMethod method : {IntegrationMethod::BDF2, IntegrationMethod::DIRK22})
    for (int scene = 0; scene < 4; ++scene) {
      SceneSettings s;
      s.integrator = method;
      // Scene 3: nine such boxes (54 dofs: above the dense solves' size) with Krylov linear
      // solves, whose block preconditioner inverts each body's 6 × 6 block
      // (StageProblem::BlockLayout; ActorKind::DofBlockSize).
      if (scene == 3) s.solver.linear.kind = LinearSolverKind::Iterative;
      Twin twin(s);
      if (scene == 0) {
        twin.Add(test::StaticGround(1e8, 0.4), true);
        RigidActorDesc box = TumblingBox();
        box.position = Eigen::Vector3d(0.0, 0.0, 0.6);
        box.linearVelocity = Eigen::Vector3d(0.2, 0.0, 0.0);
        box.angularVelocity = Eigen::Vector3d(0.3, 2.0, 0.1);
        box.contact.normalViscousDampingCoefficient = 20.0;
        twin.Add(box, true);
      } else if (scene == 1) {
        twin.Add(test::Ground(n, 1e8, 0.2, 20.0), true);
        RigidActorDesc cube = test::CubeOnIncline(theta, 1e8, 0.2, 20.0);
        cube.linearVelocity = Eigen::Vector3d(0.0, 0.3, 0.0);
        twin.Add(cube, true);
      } else {  // three boxes side by side landing at different speeds: each its own part of
                // the stage's line search (StageProblem::LastSplit; one step length for all
                // took 393 instead of 378 Newton iterations under BDF2)
        twin.Add(test::StaticGround(1e8, 0.4), true);
        for (int k = 0; k < (scene == 3 ? 9 : 3); ++k) {
          RigidActorDesc box = test::Cube(1e8, 0.4, 10.0);
          box.name = "box" + std::to_string(k);
          box.position = Eigen::Vector3d(0.5 * k, -0.005 * k, 0.102 + 0.004 * (k % 3));
          box.linearVelocity = Eigen::Vector3d(0.1 * (k % 3), 0.0, -0.3 * (k % 3));
          box.orientation =
              Eigen::Quaterniond(Eigen::AngleAxisd(0.05 * k, Eigen::Vector3d::UnitZ()));
          twin.Add(box, true);
        }
      }
      const Eigen::Vector4d worst = twin.Run(100, 5e-3);
      INFO("method " << static_cast<int>(method) << ", scene " << scene
                     << ": |Δp| " << worst[0] << " |ΔR| " << worst[1] << " |Δv| " << worst[2]
                     << " |ΔṘ| " << worst[3] << "; iterations " << twin.iterations[0] << " / "
                     << twin.iterations[1] << ", free stages " << twin.freeStages[0] << " / "
                     << twin.freeStages[1]);
      CHECK(twin.iterations[1] == twin.iterations[0]);
      CHECK(twin.freeStages[1] == twin.freeStages[0]);
      CHECK(twin.krylov[1] == twin.krylov[0]);
      if (scene == 3) CHECK(twin.krylov[0] > 0);
      if (scene == 0) CHECK(twin.freeStages[0] > 10);  // the drop's free flight
      CheckBitIdentical(worst);
    }
}

TEST_CASE("applied loads and kinematic motion of rigid kinds follow the built-in actor's",
          "[core][kind][rigid][contact]") {
  // Scene 0: a cube on a static ground pushed by a force ramp along x (0 to 8 N over 0.3 s:
  // above μ m g = 3.92 N, so it starts to slide) and turned by a torque about z that reverses
  // (an exact potential for the force, the residual's −τ for the torque, with the torque's work
  // along the committed iterates in the minimizing solves). Scene 1: a kinematic plate (its path
  // of pose keyframes, turning by 0.1 rad) pushing a cube across a static ground: all of the
  // plate's dofs prescribed, its pairs combined as a dynamic collider's, its exact path state at
  // each step's end. Under BDF2 and DIRK22 with the default stage policy (warm start, closed-form
  // free stages), in every dissipation mode: the same Newton iterations and free stages, the
  // same states to the contact tolerances, and the kinematic plate exactly on its path.
  for (IntegrationMethod method : {IntegrationMethod::BDF2, IntegrationMethod::DIRK22})
    for (int mode = 0; mode < 3; ++mode)
      for (int scene = 0; scene < 2; ++scene) {
        SceneSettings s;
        s.integrator = method;
        s.eval = test::EvalParamsForMode(mode);
        Twin twin(s);
        twin.Add(test::StaticGround(1e8, 0.4), true);
        RigidActorDesc cube = test::Cube(1e8, 0.4, 10.0);
        cube.position = Eigen::Vector3d(0.0, 0.0, 0.1 - 1e-4);
        if (scene == 0) {
          cube.appliedForce = {{0.0, Eigen::Vector3d::Zero()}, {0.3, Eigen::Vector3d(8, 0, 0)}};
          cube.appliedTorque = {{0.0, Eigen::Vector3d(0, 0, 0.5)},
                                {0.3, Eigen::Vector3d(0, 0, -0.5)}};
          twin.Add(cube, true);
        } else {
          twin.Add(cube, true);
          RigidActorDesc plate;
          plate.name = "plate";
          plate.dynamic = false;
          plate.kinematic = true;
          plate.shape.kind = RigidShapeKind::Box;
          plate.shape.halfExtents = Eigen::Vector3d(0.01, 0.15, 0.02);
          plate.shape.surfaceResolution = 2;
          plate.contact.coulombFrictionCoefficient = 0.0;
          PoseKeyframe k0, k1;
          k0.t = 0.0;
          k0.position = Eigen::Vector3d(-0.112, 0.0, 0.05);
          k1.t = 0.3;
          k1.position = Eigen::Vector3d(0.0, 0.0, 0.05);
          k1.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()));
          plate.path = {k0, k1};
          twin.Add(plate, true);
        }
        const Eigen::Vector4d worst = twin.Run(60, 5e-3);
        INFO("method " << static_cast<int>(method) << ", " << test::kModeNames[mode]
                       << ", scene " << scene << ": |Δp| " << worst[0] << " |ΔR| " << worst[1]
                       << " |Δv| " << worst[2] << " |ΔṘ| " << worst[3] << "; iterations "
                       << twin.iterations[0] << " / " << twin.iterations[1]
                       << ", free stages " << twin.freeStages[0] << " / "
                       << twin.freeStages[1]);
        CheckBitIdentical(worst);
        CHECK(twin.iterations[1] == twin.iterations[0]);
        CHECK(twin.freeStages[1] == twin.freeStages[0]);
        const RigidBodyState cubeEnd = twin.KindsState(1);
        if (scene == 0) {
          // Pushed past the friction limit: it slides along +x and turns.
          CHECK(cubeEnd.p.x() > 1e-3);
          CHECK(cubeEnd.Rdot.norm() > 1e-3);
        } else {
          // The plate on its path to the bit, and the cube pushed ahead of it.
          const RigidBodyState plateEnd = twin.KindsState(2);
          const RigidBodyState& builtInPlate = twin.builtIn.State(twin.a[2]);
          CHECK((plateEnd.p - builtInPlate.p).norm() == 0.0);
          CHECK((plateEnd.R - builtInPlate.R).norm() == 0.0);
          CHECK((plateEnd.v - builtInPlate.v).norm() == 0.0);
          CHECK(cubeEnd.p.x() > 0.05);
        }
      }
}

TEST_CASE("the slips of a rigid kind's pairs are recorded and evaluated about the record",
          "[core][kind][rigid][sensitivity]") {
  // A cube kind pressed 0.1 mm into a static ground kind and sliding at 1 m/s over the stage
  // (Δt_i = 1e-2, the default mode): recording its pair's slips (core/contact/slip_tape.h) and
  // evaluating about them at the same configuration gives the same dissipative residual.
  Error error;
  std::unique_ptr<RigidKind> ground = RigidKind::Build(test::StaticGround(1e8, 0.4), &error);
  std::unique_ptr<RigidKind> cube = RigidKind::Build(test::Cube(1e8, 0.4, 10.0), &error);
  REQUIRE(ground);
  REQUIRE(cube);
  const std::vector<const ActorKind*> kinds = {ground.get(), cube.get()};
  ContactPipeline pipeline;
  pipeline.Configure(nullptr, &kinds, {0, 1});
  std::vector<Eigen::VectorXd> q = {ground->InitialState().x, cube->InitialState().x};
  q[1].head<3>() = Eigen::Vector3d(0, 0, 0.1 - 1e-4);
  std::vector<Eigen::VectorXd> qLast = q;
  qLast[1][0] -= 1e-2;
  const std::vector<Eigen::VectorXd> q0 = qLast;
  const std::vector<std::vector<int>> stageDof = {std::vector<int>(6, -1), {0, 1, 2, 3, 4, 5}};
  KindView view;
  view.q = &q;
  view.qLast = &qLast;
  view.q0 = &q0;
  view.stageDof = &stageDof;
  StageSlips slips;
  DissipationContext context;
  context.dt = 1e-2;
  context.slips = &slips;
  context.recordSlips = true;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(6), recorded = Eigen::VectorXd::Zero(6);
  ContactStats stats;
  pipeline.Evaluate(1, PsdProjection::None, &g, nullptr, nullptr, &stats, &context, &recorded,
                    &view);
  slips.Seal();
  REQUIRE(stats.dissipativeSamples > 0);
  const PairSlips* pair = slips.Find(1, 0);  // the cube on the ground
  REQUIRE(pair);
  CHECK(static_cast<int>(pair->samples.size()) == stats.dissipativeSamples);
  context.recordSlips = false;
  Eigen::VectorXd about = Eigen::VectorXd::Zero(6);
  g.setZero();
  pipeline.Evaluate(1, PsdProjection::None, &g, nullptr, nullptr, &stats, &context, &about,
                    &view);
  INFO("recorded " << recorded.transpose() << ", about the record " << about.transpose());
  CHECK(recorded[0] > 0.1);  // friction against the +x slip (the residual is −force) [N]
  CHECK((about - recorded).norm() <= 1e-12 * recorded.norm());
}

namespace {

// The sensitivity suite's boxes (tests/sensitivity_scenes.h) as twins: the cube as a rigid kind,
// and the ground as one too where `groundAsKind`. Sliding: 0.5 mm into the ground at 0.5 m/s
// along x; bouncing: dropped tilted from 2 cm, moving sideways.
Twin SensitivityTwin(IntegrationMethod method, DissipationMode mode, bool bouncing,
                     bool groundAsKind) {
  Twin twin(test::TightSettings(method, mode));
  RigidActorDesc ground = test::Ground(Eigen::Vector3d::UnitZ(), 1e7, 0.5, 1.0);
  ground.contact.viscousFrictionCoefficient = 0.2;
  twin.Add(ground, groundAsKind);
  RigidActorDesc box = test::Cube(1e7, 0.5, 1.0);
  box.contact.viscousFrictionCoefficient = 0.2;
  box.position = Eigen::Vector3d(0, 0, 0.1 - 5e-4);
  box.linearVelocity = Eigen::Vector3d(0.5, 0, 0);
  if (bouncing) {
    box.position = Eigen::Vector3d(0, 0, 0.13);
    box.orientation =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 1, 0).normalized()));
    box.linearVelocity = Eigen::Vector3d(0.3, 0, -0.5);
  }
  twin.Add(box, true);
  return twin;
}

}  // namespace

TEST_CASE("sensitivities through a rigid kind equal the built-in rigid actor's",
          "[core][kind][sensitivity]") {
  // The cube's packed block has the same layout in both scenes (p, R, v, Ṙ), so the forward
  // sensitivities dS/dθ of the twins compare entry by entry, and the adjoint gradients of
  // L = w · c_cube(S_N) compare directly. Both differentiate the same discrete map by the same
  // differences (the kind's DifferenceGroups are the built-in body's directions and steps); they
  // differ by the round-off of two assemblies (the ground's pairs take the built-in rigid path in
  // one scene and the kind pair path in the other), which the differences divide by their steps
  // (η ≈ 1e-7 m, 1e-4 of a parameter). They agree to the accuracy the differences are checked to
  // against trajectory differences (1e-5 relative, tests/core/test_sensitivity.cpp).
  const std::vector<std::string> names = {
      "cube.coulomb_friction_coefficient", "cube.penalty_coefficient", "cube.velocity.x",
      "cube.angular_velocity.y",           "cube.position.z",          "ground.coulomb_friction_coefficient"};
  const Eigen::Vector3d w(1.0, -0.5, 2.0);
  struct Case {
    IntegrationMethod method;
    DissipationMode mode;
    bool bouncing, groundAsKind;
  };
  for (const Case c : {Case{IntegrationMethod::BDF2, DissipationMode::ReconstructedLoad, false, false},
                       Case{IntegrationMethod::DIRK22, DissipationMode::ImplicitLoad, false, true},
                       Case{IntegrationMethod::BackwardEuler, DissipationMode::ExplicitNormals, true,
                            true}}) {
    INFO(ToString(c.method) << (c.bouncing ? ", bouncing" : ", sliding")
                            << (c.groundAsKind ? ", ground a kind too" : ""));
    const int steps = 60;
    const double dt = 2e-3;
    Twin twin = SensitivityTwin(c.method, c.mode, c.bouncing, c.groundAsKind);
    Scene* scenes[2] = {&twin.builtIn, &twin.kinds};
    Eigen::MatrixXd block[2], com[2];
    Eigen::VectorXd gradient[2];
    for (int k = 0; k < 2; ++k) {
      Scene& scene = *scenes[k];
      const ActorHandle cube = scene.FindActor("cube");
      const std::vector<SceneParameter> params = test::ParseParameters(scene, names);
      Error error;
      ForwardSensitivity forward;
      REQUIRE(forward.Begin(&scene, params, &error));
      for (int n = 0; n < steps; ++n) {
        INFO(error.message);
        REQUIRE(forward.Step(dt, nullptr, &error));
      }
      block[k] = forward.StateJacobian().middleRows(scene.StateOffset(cube), 24);
      com[k] = forward.CenterOfMassJacobian(cube);
      Twin fresh = SensitivityTwin(c.method, c.mode, c.bouncing, c.groundAsKind);
      Scene& again = k == 0 ? fresh.builtIn : fresh.kinds;
      AdjointSensitivity adjoint;
      REQUIRE(adjoint.Run(&again, std::vector<double>(steps, dt), nullptr, &error));
      const bool ok = adjoint.Gradient(
          test::ParseParameters(again, names),
          [&](int n, Scene& s, Eigen::VectorXd* dL) {
            if (n == steps) *dL += CenterOfMassMap(s, cube).transpose() * w;
          },
          &gradient[k], &error);
      INFO(error.message);
      REQUIRE(ok);
    }
    for (size_t j = 0; j < names.size(); ++j) {
      const double scale = block[0].col(j).lpNorm<Eigen::Infinity>();
      const double err = (block[1].col(j) - block[0].col(j)).lpNorm<Eigen::Infinity>();
      INFO(names[j] << ": dS/dθ of the cube, largest " << scale << ", twins differ by " << err
                    << "; d(com)/dθ " << com[0].col(j).transpose() << " and "
                    << com[1].col(j).transpose() << "; adjoint " << gradient[0][j] << " and "
                    << gradient[1][j]);
      CHECK(err <= 1e-5 * scale);
      CHECK(std::abs(gradient[1][j] - gradient[0][j]) <= 1e-5 * std::abs(gradient[0][j]));
    }
  }
}

TEST_CASE("a soft cube lands on rigid kinds as on the built-in rigid actors",
          "[core][kind][soft][physics]") {
  // Soft actors collide on a kind's field through the same assembler as on a rigid body's (their
  // face samples, culled face by face): a soft cube (2 × 2 × 2 cells, 0.1 m, E = 1e5 Pa) dropped
  // 1 cm onto a dynamic box resting on the ground, both rigid kinds (the ground static), follows
  // the same scene of built-in rigid actors to the twins' contact tolerances, with the same Newton
  // iterations, in the three dissipation modes.
  for (int mode : {0, 1, 2}) {
    INFO(test::kModeNames[mode]);
    Twin twin(SameNewtonPath(IntegrationMethod::BDF2, mode));
    twin.Add(test::StaticGround(1e7, 0.5), true);
    RigidActorDesc box = test::Cube(1e7, 0.5, 1.0);
    box.shape.halfExtents = Eigen::Vector3d(0.2, 0.2, 0.05);
    box.position = Eigen::Vector3d(0, 0, 0.05 - 2e-4);
    twin.Add(box, true);
    SoftActorDesc d;
    d.name = "soft";
    d.mesh = std::make_shared<TetMesh>(
        MakeTetBox(Eigen::Vector3d::Constant(0.05), Eigen::Vector3i::Constant(2)));
    d.position = Eigen::Vector3d(0.02, -0.01, 0.1 + 0.05 + 0.01);
    d.linearVelocity = Eigen::Vector3d(0.2, 0, 0);
    d.material.youngsModulus = 1e5;
    d.material.density = 1000.0;
    d.contact.penaltyCoefficient = 1e7;
    d.contact.normalViscousDampingCoefficient = 1.0;
    const auto soft = twin.AddSoft(d);
    CheckFollowsInContact(twin.Run(150, 2e-3));
    CHECK(twin.iterations[0] == twin.iterations[1]);
    const Eigen::Vector2d diff = twin.SoftDifference(soft);
    const double dx = diff[0], dv = diff[1];
    INFO("soft nodes differ by " << dx << " m, " << dv << " m/s; Newton iterations "
                                 << twin.iterations[0] << " and " << twin.iterations[1]);
    CHECK(dx < 1e-8);
    CHECK(dv < 1e-6);
    // The box stopped it: in free fall its centre would be at 0.16 − g (0.3 s)²/2 = −0.28 m; it
    // bounces on the box's top face (z = 0.1) with its centre near 0.15 m.
    const double z = twin.kinds.CenterOfMass(soft.second).z();
    INFO("centre height " << z << " m");
    CHECK(z > 0.14);
    CHECK(z < 0.17);
  }
}

TEST_CASE("a rigid kind lands on a soft Sdf collider as the built-in rigid actor does",
          "[core][kind][rigid][soft][contact]") {
  // A kind's sample body on a soft actor's grid field (core/contact/tet_field.h, the tet
  // pullback): a soft slab (0.4 × 0.4 × 0.1 m, E = 1e6 Pa, its bottom resting 0.1 mm in a static
  // ground) with colliderType Sdf, and a 0.1 m cube dropped 1 cm onto it, sliding at 0.2 m/s,
  // as a rigid kind in one scene and a built-in actor in the other: the same states to the
  // twins' contact tolerances, the same Newton iterations, in the three dissipation modes. The
  // ground a built-in actor in both, or a kind in the kinds' scene (which then has no built-in
  // rigid actor: the kind's stage start x⁰ must not depend on one).
  for (int mode : {0, 1, 2})
   for (bool groundAsKind : {false, true}) {
    INFO(test::kModeNames[mode] << (groundAsKind ? ", kind ground" : ", built-in ground"));
    Twin twin(SameNewtonPath(IntegrationMethod::BDF2, mode));
    twin.Add(test::StaticGround(1e7, 0.5), groundAsKind);
    SoftActorDesc d;
    d.name = "slab";
    d.mesh = std::make_shared<TetMesh>(
        MakeTetBox(Eigen::Vector3d(0.2, 0.2, 0.05), Eigen::Vector3i(3, 3, 1)));
    d.position = Eigen::Vector3d(0, 0, 0.05 - 1e-4);
    d.material.youngsModulus = 1e6;
    d.material.density = 500.0;
    d.colliderType = ColliderType::Sdf;
    d.gridSdf.minGridResolution = 16;
    d.contact.penaltyCoefficient = 1e7;
    d.contact.coulombFrictionCoefficient = 0.3;
    d.contact.normalViscousDampingCoefficient = 1.0;
    const auto slab = twin.AddSoft(d);
    RigidActorDesc cube = test::Cube(1e7, 0.3, 1.0);
    cube.shape.halfExtents = Eigen::Vector3d::Constant(0.05);
    cube.mass = 0.5;
    cube.position = Eigen::Vector3d(0.013, -0.007, 0.1 + 0.05 + 0.01);
    cube.linearVelocity = Eigen::Vector3d(0.2, 0, 0);
    twin.Add(cube, true);
    // The same bits: the kind's dofs lead the slab's nodes as the built-in cube's do, its
    // frame and sample body are formed from the same poses. (Where they were not, with explicit
    // normals a round-off difference grew tenfold per step once the sliding cube's samples
    // crossed the slab's tet faces: each sample's terms use the tet that contains y_n at x_n,
    // and round-off chooses between two tets' maps on a face.)
    const Eigen::Vector4d worst = twin.Run(100, 2e-3);
    const double dx = twin.SoftDifference(slab)[0];
    INFO("|Δp| " << worst[0] << " |ΔR| " << worst[1] << " |Δv| " << worst[2] << " |ΔṘ| "
                 << worst[3] << "; soft nodes differ by " << dx << " m; Newton iterations "
                 << twin.iterations[0] << " and " << twin.iterations[1]);
    CheckBitIdentical(worst);
    CHECK(dx == 0.0);
    CHECK(twin.iterations[0] == twin.iterations[1]);
    // The slab's field stopped it (it lands after 0.045 s): in free fall its centre would be at
    // 0.16 − g (0.09 s)²/2 = 0.12 m; it rests on the slab's top face (z = 0.1) with its centre
    // near 0.15 m.
    const double z = twin.KindsState(1).p.z();
    INFO("cube centre height " << z << " m");
    CHECK(z > 0.14);
    CHECK(z < 0.16);
  }
}
