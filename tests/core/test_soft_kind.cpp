// The soft kind (core/model/soft_kind.h): a tet FEM actor carried by the generic actor layer, its
// stage terms those of core/model/soft_terms.h on its free nodes, its face samples handed to the
// one contact assembler as Nodes maps with a face normal that moves with the nodes; with an Sdf
// collider its reference grid SDF pulled back through its deformed tets.
//
// Expectations:
//   - its stage energy's gradient and Hessian on the free nodes equal central differences of Φ;
//     prescribed nodes are prescribed tangent dofs;
//   - the scene's front door for soft actors is this kind: a scene with a soft body added by
//     AddSoftActor and the same scene with SoftKind::Build(desc) added by AddActor step bit for
//     bit alike, in each of its roles (colliding on a rigid box and on a tet field, pinned and
//     driven nodes, a tet-field collider). The soft actors' own path, which these scenes once
//     followed to within the solver's tolerance (1e-14 m), is gone; the regression recordings
//     (tests/regression) of the shipped and sensitivity soft scenes, made on it, guard the
//     physics;
//   - in those scenes the physics holds: the cube lands on the box, the driven corner returns,
//     the momentum of the free soft-on-soft scenes is balanced.
#include <catch2/catch.hpp>
#include <memory>
#include <random>

#include "core/model/soft_kind.h"
#include "core/scene.h"
#include "derivative_check.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

SoftActorDesc Cube(double half, int cells, const Eigen::Vector3d& position) {
  SoftActorDesc d;
  d.name = "soft";
  d.mesh = std::make_shared<TetMesh>(
      MakeTetBox(Eigen::Vector3d::Constant(half), Eigen::Vector3i::Constant(cells)));
  d.position = position;
  d.material.youngsModulus = 1e5;
  d.material.density = 1000.0;
  d.contact.penaltyCoefficient = 1e7;
  return d;
}

}  // namespace

TEST_CASE("the soft kind's stage energy: gradient and Hessian on the free nodes by differences",
          "[core][kind][soft][derivatives]") {
  SoftActorDesc d = Cube(0.1, 2, Eigen::Vector3d(0, 0, 0.3));
  d.material.stiffnessDamping = 0.01;
  d.constraints.push_back({{13}, {}});  // the centre node, pinned
  Error error;
  const std::unique_ptr<SoftKind> soft = SoftKind::Build(d, &error);
  REQUIRE(soft);
  const int n = soft->NumTangentDofs();
  CHECK(soft->IsPrescribed(3 * 13 + 1));
  CHECK_FALSE(soft->IsPrescribed(0));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2e-3, 2e-3);
  const Eigen::VectorXd x0 = soft->InitialState().x;
  Eigen::VectorXd q = x0;
  for (int i = 0; i < n; ++i)
    if (!soft->IsPrescribed(i)) q[i] += 10 * u(rng);  // a deformed configuration
  KindStageData stage;
  stage.dt = 0.01;
  stage.gravity = Eigen::Vector3d(0.3, -0.2, -9.81);
  stage.q0 = x0;
  stage.qLast = x0;
  stage.qHat = x0;
  for (int i = 0; i < n; ++i) stage.qHat[i] += u(rng);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
  std::vector<Eigen::Triplet<double>> triplets;
  soft->StageEnergy(stage, q, 2, PsdProjection::None, &g, &triplets);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  for (const auto& t : triplets) H(t.row(), t.col()) += t.value();
  // Over the free dofs only (prescribed ones are no unknowns: no entries there).
  std::vector<int> free;
  for (int i = 0; i < n; ++i)
    if (!soft->IsPrescribed(i)) free.push_back(i);
  REQUIRE(static_cast<int>(free.size()) == n - 3);
  for (int i = 0; i < n; ++i)
    if (soft->IsPrescribed(i)) CHECK(g[i] == 0.0);
  const int m = static_cast<int>(free.size());
  Eigen::VectorXd gFree(m);
  Eigen::MatrixXd HFree(m, m);
  for (int i = 0; i < m; ++i) {
    gFree[i] = g[free[i]];
    for (int j = 0; j < m; ++j) HFree(i, j) = H(free[i], free[j]);
  }
  auto f = [&](const Eigen::VectorXd& delta) {
    Eigen::VectorXd moved = q;
    for (int i = 0; i < m; ++i) moved[free[i]] += delta[i];
    return soft->StageEnergy(stage, moved, 0, PsdProjection::None, nullptr, nullptr);
  };
  const test::DerivativeCheck c = test::CheckDerivatives(f, gFree, HFree, 1e-6);
  INFO("gradient error " << c.gradientError << ", Hessian error " << c.hessianError);
  CHECK(c.gradientError < 1e-7);
  CHECK(c.hessianError < 1e-5);
}

TEST_CASE("a soft kind is a collider with an Sdf grid only, and refuses other colliders",
          "[core][kind][soft]") {
  SoftActorDesc d = Cube(0.1, 1, Eigen::Vector3d::Zero());
  Error error;
  std::unique_ptr<SoftKind> plain = SoftKind::Build(d, &error);
  REQUIRE(plain);
  CHECK(plain->TetCollider() == nullptr);
  CHECK(plain->Collider() == nullptr);
  d.colliderType = ColliderType::Sdf;
  std::unique_ptr<SoftKind> field = SoftKind::Build(d, &error);
  REQUIRE(field);
  REQUIRE(field->TetCollider() != nullptr);
  CHECK(field->TetCollider()->colliderGrid != nullptr);
  d.colliderType = ColliderType::Sphere;  // as AddSoftActor: the Sphere collider is for rigid actors
  CHECK_FALSE(SoftKind::Build(d, &error));
  CHECK_THAT(error.message, Catch::Contains("collider_type"));
}

TEST_CASE("a soft cube added as a soft actor is the soft kind: it lands on a box",
          "[core][kind][soft][physics]") {
  // A soft cube (2 × 2 × 2 cells, 0.1 m, E = 1e5 Pa) dropped 1 cm onto a dynamic box resting on
  // the ground, moving sideways, in the three dissipation modes: once added as a soft actor, once
  // as a SoftKind: the same actor, bit for bit.
  for (int mode : {0, 1, 2}) {
    INFO(test::kModeNames[mode]);
    SceneSettings s;
    s.integrator = IntegrationMethod::BDF2;
    s.eval = test::EvalParamsForMode(mode);
    s.warmStart = false;
    s.closedFormFreeStages = false;
    Scene actor(s), kind(s);
    Error error;
    RigidActorDesc box = test::Cube(1e7, 0.5, 1.0);
    box.shape.halfExtents = Eigen::Vector3d(0.2, 0.2, 0.05);
    box.position = Eigen::Vector3d(0, 0, 0.05 - 2e-4);
    SoftActorDesc d = Cube(0.05, 2, Eigen::Vector3d(0.02, -0.01, 0.1 + 0.05 + 0.01));
    d.linearVelocity = Eigen::Vector3d(0.2, 0, 0);
    d.contact.normalViscousDampingCoefficient = 1.0;
    d.constraints.clear();
    ActorHandle boxes[2], softs[2];
    Scene* scenes[2] = {&actor, &kind};
    for (int k = 0; k < 2; ++k) {
      REQUIRE(scenes[k]->AddRigidActor(test::StaticGround(1e7, 0.5), &error).IsValid());
      boxes[k] = scenes[k]->AddRigidActor(box, &error);
      REQUIRE(boxes[k].IsValid());
    }
    softs[0] = actor.AddSoftActor(d, &error);
    std::unique_ptr<SoftKind> sk = SoftKind::Build(d, &error);
    REQUIRE(sk);
    softs[1] = kind.AddActor(std::move(sk), &error, d.contactLayer);
    REQUIRE(softs[0].IsValid());
    REQUIRE(softs[1].IsValid());
    double dx = 0.0, dv = 0.0, dp = 0.0;
    int iterations[2] = {0, 0};
    for (int step = 0; step < 150; ++step) {
      StepReport r[2];
      for (int k = 0; k < 2; ++k) {
        REQUIRE(scenes[k]->Step(2e-3, &r[k], &error));
        REQUIRE(r[k].status == StageStatus::Converged);
        iterations[k] += r[k].newtonIterations;
      }
      const SoftBodyState& a = actor.SoftState(softs[0]);
      const KindState& b = kind.KindStateOf(softs[1]);
      dx = std::max(dx, (a.x - b.x).lpNorm<Eigen::Infinity>());
      dv = std::max(dv, (a.v - b.v).lpNorm<Eigen::Infinity>());
      dp = std::max(dp, (actor.State(boxes[0]).p - kind.State(boxes[1]).p).norm());
    }
    INFO("soft nodes differ by " << dx << " m, " << dv << " m/s; the box by " << dp
                                 << " m; Newton iterations " << iterations[0] << " and "
                                 << iterations[1]);
    CHECK(dx == 0.0);
    CHECK(dv == 0.0);
    CHECK(dp == 0.0);
    CHECK(iterations[0] == iterations[1]);
    // It landed: in free fall its centre would be at 0.16 − g (0.3 s)²/2 = −0.28 m; it bounces
    // on the box's top face (z = 0.1) with its centre near 0.15 m.
    const double z = kind.CenterOfMass(softs[1]).z();
    INFO("centre height " << z << " m");
    CHECK(z > 0.14);
    CHECK(z < 0.17);
    // The reports agree: energies and momenta of the same state.
    CHECK(kind.Energies().kinetic == actor.Energies().kinetic);
    CHECK(kind.Energies().elastic == actor.Energies().elastic);
    CHECK(kind.TotalLinearMomentum() == actor.TotalLinearMomentum());
  }
}

TEST_CASE("a soft kind's pinned and driven nodes: the soft actor's, bit for bit",
          "[core][kind][soft]") {
  // A hanging soft cube (stiffness damping on): its top nodes pinned, one bottom corner driven
  // sideways and back; no contact. The vector kind's prescribed dofs (Prescribe, the integrator's
  // differences for their velocities) against the soft actor's node constraints, under a
  // multistep and two DIRK methods.
  for (IntegrationMethod method : {IntegrationMethod::BDF2, IntegrationMethod::DIRK22,
                                   IntegrationMethod::SymplecticDIRK12}) {
    DYNAMIC_SECTION(ToString(method)) {
      SceneSettings s;
      s.integrator = method;
      s.warmStart = false;
      s.closedFormFreeStages = false;
      SoftActorDesc d = Cube(0.05, 2, Eigen::Vector3d(0, 0, 1));
      d.material.stiffnessDamping = 0.005;
      NodeConstraint top, corner;
      for (int a = 0; a < d.mesh->NumVertices(); ++a) {
        const Eigen::Vector3d& X = d.mesh->vertices[a];
        if (X.z() > 0.049) top.nodes.push_back(a);
        if (X.x() < -0.049 && X.y() < -0.049 && X.z() < -0.049) corner.nodes.push_back(a);
      }
      REQUIRE(top.nodes.size() == 9);
      REQUIRE(corner.nodes.size() == 1);
      corner.path = {{0.0, Eigen::Vector3d::Zero()},
                     {0.05, Eigen::Vector3d(0.01, 0, 0)},
                     {0.1, Eigen::Vector3d::Zero()}};
      d.constraints = {top, corner};
      Scene actor(s), kind(s);
      Error error;
      const ActorHandle a = actor.AddSoftActor(d, &error);
      std::unique_ptr<SoftKind> sk = SoftKind::Build(d, &error);
      REQUIRE(sk);
      const ActorHandle k = kind.AddActor(std::move(sk), &error);
      REQUIRE(a.IsValid());
      REQUIRE(k.IsValid());
      double dx = 0.0, dv = 0.0;
      for (int step = 0; step < 60; ++step) {
        StepReport ra, rk;
        REQUIRE(actor.Step(2.5e-3, &ra, &error));
        REQUIRE(kind.Step(2.5e-3, &rk, &error));
        REQUIRE(ra.status == StageStatus::Converged);
        REQUIRE(rk.status == StageStatus::Converged);
        dx = std::max(dx, (actor.SoftState(a).x - kind.KindStateOf(k).x).lpNorm<Eigen::Infinity>());
        dv = std::max(dv, (actor.SoftState(a).v - kind.KindStateOf(k).v).lpNorm<Eigen::Infinity>());
      }
      INFO("nodes differ by " << dx << " m, " << dv << " m/s");
      CHECK(dx == 0.0);
      CHECK(dv == 0.0);
      // The driven corner is back at its start at t = 0.1 s (within the last step's motion).
      const int c = corner.nodes[0];
      const Eigen::Vector3d x0 = kind.Kind(k).InitialState().x.segment<3>(3 * c);
      CHECK((kind.KindStateOf(k).x.segment<3>(3 * c) - x0).norm() < 1e-12);
    }
  }
}

TEST_CASE("a soft kind collides on a soft actor's Sdf field: the soft actor's, bit for bit",
          "[core][kind][soft][contact]") {
  // Gravity off: a soft cube thrown at a soft cube with an Sdf collider (the reference grid SDF
  // pulled back through its deformed tets), once as a soft actor, once as a SoftKind (its own face
  // samples through the kind's path on the soft field). Both cubes' nodes agree bit for bit in
  // the three dissipation modes, and the momentum is balanced.
  for (int mode : {0, 1, 2}) {
    INFO(test::kModeNames[mode]);
    SceneSettings s;
    s.gravity.setZero();
    s.integrator = IntegrationMethod::BDF2;
    s.eval = test::EvalParamsForMode(mode);
    s.warmStart = false;
    s.closedFormFreeStages = false;
    SoftActorDesc target = Cube(0.1, 3, Eigen::Vector3d::Zero());
    target.name = "target";
    target.colliderType = ColliderType::Sdf;
    target.contact.penaltyCoefficient = 1e5;
    target.contact.coulombFrictionCoefficient = 0.3;
    SoftActorDesc thrown = Cube(0.1, 2, Eigen::Vector3d(-0.21, 0.05, 0.03));
    thrown.name = "thrown";
    thrown.contact.penaltyCoefficient = 1e5;
    thrown.contact.coulombFrictionCoefficient = 0.3;
    thrown.linearVelocity = Eigen::Vector3d(1.0, 0.0, 0.0);
    Scene actor(s), kind(s);
    Error error;
    const ActorHandle ta = actor.AddSoftActor(target, &error);
    const ActorHandle tk = kind.AddSoftActor(target, &error);
    const ActorHandle a = actor.AddSoftActor(thrown, &error);
    std::unique_ptr<SoftKind> sk = SoftKind::Build(thrown, &error);
    REQUIRE(sk);
    const ActorHandle k = kind.AddActor(std::move(sk), &error);
    REQUIRE(ta.IsValid());
    REQUIRE(tk.IsValid());
    REQUIRE(a.IsValid());
    REQUIRE(k.IsValid());
    const Eigen::Vector3d p0 = kind.TotalLinearMomentum();
    double dx = 0.0, dv = 0.0;
    int active = 0;
    for (int step = 0; step < 60; ++step) {
      StepReport ra, rk;
      REQUIRE(actor.Step(2e-3, &ra, &error));
      REQUIRE(kind.Step(2e-3, &rk, &error));
      REQUIRE(ra.status == StageStatus::Converged);
      REQUIRE(rk.status == StageStatus::Converged);
      active = std::max(active, rk.contact.activeSamples);
      dx = std::max({dx, (actor.SoftState(a).x - kind.KindStateOf(k).x).lpNorm<Eigen::Infinity>(),
                     (actor.SoftState(ta).x - kind.SoftState(tk).x).lpNorm<Eigen::Infinity>()});
      dv = std::max({dv, (actor.SoftState(a).v - kind.KindStateOf(k).v).lpNorm<Eigen::Infinity>(),
                     (actor.SoftState(ta).v - kind.SoftState(tk).v).lpNorm<Eigen::Infinity>()});
    }
    INFO("nodes differ by " << dx << " m, " << dv << " m/s; at most " << active
                            << " active samples");
    CHECK(active > 10);  // they met
    CHECK(dx == 0.0);
    CHECK(dv == 0.0);
    CHECK((kind.TotalLinearMomentum() - p0).norm() < 1e-8 * p0.norm());
  }
}

TEST_CASE("a soft kind's Sdf collider field: the soft actor's, bit for bit", "[core][kind][soft][contact]") {
  // Gravity off: a soft cube with an Sdf collider hit by a thrown soft cube and by a thrown rigid
  // box. The target (and the thrown soft cube) as soft actors, then as SoftKinds: the target's
  // field pulled back through its deformed tets (ActorKind::TetCollider) on the kind's stage dofs.
  // Every configuration follows the all-soft-actor scene bit for bit.
  struct Combo {
    const char* name;
    bool targetKind, thrownKind;
  };
  for (const Combo c : {Combo{"target kind", true, false}, Combo{"both kinds", true, true}}) {
    for (int mode : {0, 1, 2}) {
      INFO(c.name << ", " << test::kModeNames[mode]);
      SceneSettings s;
      s.gravity.setZero();
      s.integrator = IntegrationMethod::BDF2;
      s.eval = test::EvalParamsForMode(mode);
      s.warmStart = false;
      s.closedFormFreeStages = false;
      SoftActorDesc target = Cube(0.1, 3, Eigen::Vector3d::Zero());
      target.name = "target";
      target.colliderType = ColliderType::Sdf;
      target.contact.penaltyCoefficient = 1e5;
      target.contact.coulombFrictionCoefficient = 0.3;
      SoftActorDesc thrown = Cube(0.1, 2, Eigen::Vector3d(-0.21, 0.05, 0.03));
      thrown.name = "thrown";
      thrown.contact.penaltyCoefficient = 1e5;
      thrown.contact.coulombFrictionCoefficient = 0.3;
      thrown.linearVelocity = Eigen::Vector3d(1.0, 0.0, 0.0);
      RigidActorDesc box = test::Cube(1e5, 0.3, 1.0);
      box.shape.halfExtents = Eigen::Vector3d::Constant(0.03);
      box.position = Eigen::Vector3d(0.02, -0.03, 0.135);
      box.linearVelocity = Eigen::Vector3d(0, 0, -0.5);
      Scene actor(s), kind(s);
      Error error;
      auto addSoft = [&](Scene& scene, const SoftActorDesc& d, bool asKind) {
        if (!asKind) return scene.AddSoftActor(d, &error);
        std::unique_ptr<SoftKind> k = SoftKind::Build(d, &error);
        REQUIRE(k);
        return scene.AddActor(std::move(k), &error);
      };
      const ActorHandle t[2] = {addSoft(actor, target, false), addSoft(kind, target, c.targetKind)};
      const ActorHandle h[2] = {addSoft(actor, thrown, false), addSoft(kind, thrown, c.thrownKind)};
      const ActorHandle b[2] = {actor.AddRigidActor(box, &error), kind.AddRigidActor(box, &error)};
      for (int k = 0; k < 2; ++k) {
        REQUIRE(t[k].IsValid());
        REQUIRE(h[k].IsValid());
        REQUIRE(b[k].IsValid());
      }
      auto x = [](const Scene& scene, ActorHandle a) -> const VectorState& {
        return scene.IsSoft(a) ? scene.SoftState(a) : scene.KindStateOf(a);
      };
      const Eigen::Vector3d p0 = kind.TotalLinearMomentum();
      double dx = 0.0, dv = 0.0, dp = 0.0;
      int active = 0;
      for (int step = 0; step < 60; ++step) {
        StepReport ra, rk;
        REQUIRE(actor.Step(2e-3, &ra, &error));
        REQUIRE(kind.Step(2e-3, &rk, &error));
        REQUIRE(ra.status == StageStatus::Converged);
        REQUIRE(rk.status == StageStatus::Converged);
        active = std::max(active, rk.contact.activeSamples);
        for (const ActorHandle* a : {t, h}) {
          dx = std::max(dx, (x(actor, a[0]).x - x(kind, a[1]).x).lpNorm<Eigen::Infinity>());
          dv = std::max(dv, (x(actor, a[0]).v - x(kind, a[1]).v).lpNorm<Eigen::Infinity>());
        }
        dp = std::max(dp, (actor.State(b[0]).p - kind.State(b[1]).p).norm());
      }
      INFO("nodes differ by " << dx << " m, " << dv << " m/s, the box by " << dp
                              << " m; at most " << active << " active samples");
      CHECK(active > 10);
      CHECK(dx == 0.0);
      CHECK(dv == 0.0);
      CHECK(dp == 0.0);
      CHECK((kind.TotalLinearMomentum() - p0).norm() < 1e-8 * p0.norm());
    }
  }
}
