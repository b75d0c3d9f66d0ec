// Cloth (shell actors with the hinge bending and the PointCloud collider with self-contact, a
// 16 cm square of 648 triangles, 0.1 kg/m², E h = 500 N/m) in contact-rich scenes, Backward
// Euler steps of 4 ms, current-load dissipation (the spec's advice for point clouds):
//   - dropped from 12 cm onto a rigid sphere (r = 5 cm) and onto a box (8 cm cube) on the
//     ground: it comes to rest draped over the obstacle's top (within 5 mm);
//   - thrown edge first onto the ground from hanging: it folds onto itself (self-contact in more
//     than 10 frames);
//   - held at its far edge on the ground and pushed at the other by a kinematic paddle sweeping
//     12 cm: it buckles up (over 2 cm) and folds onto itself (self-contact in more than 10
//     frames).
//
// The penalty ramp h_ε,δ is active for φ < δ and smooth down to φ = δ − 2ε, linear below
// (spec: "Frictionless Normal Penalty"): the band a contact may use. Bounds asserted in every
// frame (after every step):
//   - every cloth sample on a rigid field: φ >= δ − 2ε (no sample beyond the ramp's band);
//   - every admissible pair of the cloth's own point cloud (a sample X_A and a node X_B with
//     ‖X_B − X_A‖ >= r L_B at rest): ‖y − x_B‖ >= L_B + δ − 2ε > 0, i.e. no sample comes
//     closer to a node's sphere centre than the band allows. The meshes are fine enough that
//     the spheres cover the sheet through that band (the farthest point of a right triangle of
//     legs h from its corners is h/√2 <= L_B + δ − 2ε), so a sheet passing through itself would
//     bring a sample that close;
//   - every stage converged;
//   - energy only dissipated: the total (kinetic, gravity, elastic, penalty) never grows by more
//     than 1e-6 of the initial drop's energy over a step (Backward Euler; a kinematic plunger
//     does work, so there the check is not made).
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/model/rigid_kind.h"
#include "core/model/shell_kind.h"
#include "core/scene.h"

namespace superdex {
namespace {

constexpr double kEps = 0.002, kDelta = 0.001, kL = 0.01;

ShellActorDesc Cloth(double size, int cells, const Eigen::Vector3d& position,
                     const Eigen::Quaterniond& orientation = Eigen::Quaterniond::Identity()) {
  ShellActorDesc d;
  d.name = "cloth";
  d.mesh = std::make_shared<TriangleMesh>(
      MakeRectangleMesh(Eigen::Vector2d(-size / 2, -size / 2), Eigen::Vector2d(size / 2, size / 2),
                        Eigen::Vector2i(cells, cells)));
  d.meshSource = "rectangle";
  d.position = position;
  d.orientation = orientation;
  d.bending = ShellBendingModel::Hinge;
  d.material.youngsModulus = 1e6;
  d.material.density = 200.0;
  d.material.thickness = 5e-4;
  d.contact.penaltyCoefficient = 1e7;
  d.contact.penaltySmoothingHalfDistance = kEps;
  d.contact.penaltyThresholdDefault = kDelta;
  d.contact.coulombFrictionCoefficient = 0.3;
  d.pointCloud.radius = kL;
  d.pointCloud.selfContact = true;
  return d;
}

RigidActorDesc Obstacle(const std::string& name, RigidShapeKind kind, const Eigen::Vector3d& size,
                        const Eigen::Vector3d& position) {
  RigidActorDesc d;
  d.name = name;
  d.dynamic = false;
  d.shape.kind = kind;
  d.shape.radius = size.x();
  d.shape.halfExtents = size;
  d.position = position;
  d.contact.penaltySmoothingHalfDistance = kEps;
  d.contact.penaltyThresholdDefault = kDelta;
  return d;
}

// The smallest ‖y − x_B‖ over the admissible pairs of a shell's own samples and nodes [m].
double MinAdmissibleDistance(const ShellKind& k, const Eigen::VectorXd& x) {
  const Eigen::VectorXd& X = *k.ReferenceConfiguration();
  const double rL = k.PointCloud()->selfContactExclusionRatio * k.PointCloud()->radius;
  double d = INFINITY;
  for (int i = 0; i < k.NumSamples(); ++i) {
    const Eigen::Vector3d y = k.Sample(i, x).y, Y = k.Sample(i, X).y;
    for (int j = 0; 3 * j < x.size(); ++j)
      if ((X.segment<3>(3 * j) - Y).norm() >= rL) d = std::min(d, (x.segment<3>(3 * j) - y).norm());
  }
  return d;
}

// The smallest φ of a shell's samples on a static rigid actor's field.
double MinPhiOn(const ShellKind& k, const Eigen::VectorXd& x, const RigidKind& body) {
  const RigidCollider& field = *body.Collider();
  const KindFrame f = body.ColliderFrame(body.InitialState().x);
  double phi = INFINITY;
  for (int i = 0; i < k.NumSamples(); ++i)
    phi = std::min(phi, field.Value(f.pose.R.transpose() * (k.Sample(i, x).y - f.pose.p)));
  return phi;
}

// Backward Euler with the current load (the spec's advice for point clouds).
SceneSettings ClothSettings() {
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BackwardEuler;
  settings.eval.implicitNormalForceForDissipation = true;
  return settings;
}

// The static ground plane.
ActorHandle AddGround(Scene* scene) {
  Error e;
  const ActorHandle g = scene->AddRigidActor(
      Obstacle("ground", RigidShapeKind::Plane, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()), &e);
  REQUIRE(g.IsValid());
  return g;
}

struct Watch {
  double minPhi = INFINITY, minSelf = INFINITY, maxEnergyRise = -INFINITY;
  int steps = 0, converged = 0, activeSelf = 0;
};

// The bounds of every frame: the ramp's band on rigid fields and for admissible self pairs.
void CheckBounds(const Watch& w) {
  CHECK(w.minPhi >= kDelta - 2 * kEps);
  CHECK(w.minSelf >= kL + kDelta - 2 * kEps);
}

// Runs `steps` steps of dt, watching the bounds after every step (the rigid obstacles `fields`).
Watch Run(Scene* scene, ActorHandle cloth, const std::vector<ActorHandle>& fields, int steps,
          double dt) {
  Watch w;
  Error e;
  const auto& k = static_cast<const ShellKind&>(scene->Kind(cloth));
  double energy = scene->Energies().Total();
  for (int s = 0; s < steps; ++s) {
    StepReport r;
    REQUIRE(scene->Step(dt, &r, &e));
    ++w.steps;
    w.converged += r.status == StageStatus::Converged;
    const Eigen::VectorXd& x = scene->KindStateOf(cloth).x;
    for (ActorHandle f : fields)
      w.minPhi = std::min(w.minPhi, MinPhiOn(k, x, static_cast<const RigidKind&>(scene->Kind(f))));
    const double self = MinAdmissibleDistance(k, x);
    w.minSelf = std::min(w.minSelf, self);
    w.activeSelf += self < kL + kDelta;
    const double now = scene->Energies().Total();
    w.maxEnergyRise = std::max(w.maxEnergyRise, now - energy);
    energy = now;
  }
  return w;
}

}  // namespace

TEST_CASE("cloth: dropped on a rigid sphere and on a box, it drapes within the band",
          "[core][shell][point_cloud][cloth]") {
  const bool box = GENERATE(false, true);
  Scene scene(ClothSettings());
  Error e;
  const ActorHandle ground = AddGround(&scene);
  const ActorHandle obstacle =
      box ? scene.AddRigidActor(Obstacle("box", RigidShapeKind::Box, Eigen::Vector3d(0.04, 0.04, 0.04),
                                         Eigen::Vector3d(0, 0, 0.04)), &e)
          : scene.AddRigidActor(Obstacle("ball", RigidShapeKind::Sphere, Eigen::Vector3d(0.05, 0, 0),
                                         Eigen::Vector3d(0, 0, 0.05)), &e);
  REQUIRE(obstacle.IsValid());
  std::unique_ptr<ShellKind> kind = ShellKind::Build(Cloth(0.16, 18, Eigen::Vector3d(0, 0, 0.12)), &e);
  REQUIRE(kind);
  const ActorHandle cloth = scene.AddActor(std::move(kind), &e);
  REQUIRE(cloth.IsValid());
  const double drop = scene.Energies().Total();
  const Watch w = Run(&scene, cloth, {ground, obstacle}, 100, 4e-3);
  const Eigen::VectorXd& x = scene.KindStateOf(cloth).x;
  double top = -INFINITY, low = INFINITY;
  for (int j = 0; 3 * j < x.size(); ++j) {
    top = std::max(top, x[3 * j + 2]);
    low = std::min(low, x[3 * j + 2]);
  }
  INFO((box ? "box" : "sphere") << ": min φ " << w.minPhi << " m, min admissible distance "
                                << w.minSelf << " m (" << w.activeSelf
                                << " frames with self-contact), largest energy rise "
                                << w.maxEnergyRise << " J of " << drop << " J, cloth z in [" << low
                                << ", " << top << "]");
  CHECK(w.converged == w.steps);
  CheckBounds(w);
  CHECK(w.maxEnergyRise <= 1e-6 * std::abs(drop));
  CHECK(top == Approx(box ? 0.08 : 0.10).margin(0.005));  // resting on the obstacle's top
}

TEST_CASE("cloth: falling edge first, it folds onto itself on the ground without passing through",
          "[core][shell][point_cloud][cloth]") {
  Scene scene(ClothSettings());
  Error e;
  const ActorHandle ground = AddGround(&scene);
  // Hanging in the x = 0 plane, tilted 0.15 rad off the vertical, its lower edge 5 mm up,
  // thrown down onto its edge.
  const Eigen::Quaterniond hang(Eigen::AngleAxisd(M_PI / 2 - 0.15, Eigen::Vector3d::UnitX()));
  ShellActorDesc d = Cloth(0.16, 18, Eigen::Vector3d(0, 0, 0.005 + 0.08 * std::cos(0.15)), hang);
  d.linearVelocity = Eigen::Vector3d(0, -0.1, -0.3);
  std::unique_ptr<ShellKind> kind = ShellKind::Build(d, &e);
  REQUIRE(kind);
  const ActorHandle cloth = scene.AddActor(std::move(kind), &e);
  REQUIRE(cloth.IsValid());
  const double drop = scene.Energies().Total();
  const Watch w = Run(&scene, cloth, {ground}, 150, 4e-3);
  INFO("min φ " << w.minPhi << " m, min admissible distance " << w.minSelf << " m ("
                << w.activeSelf << " frames with self-contact), largest energy rise "
                << w.maxEnergyRise << " J of " << drop << " J");
  CHECK(w.converged == w.steps);
  CHECK(w.activeSelf > 10);  // it did fold onto itself
  CheckBounds(w);
  CHECK(w.maxEnergyRise <= 1e-6 * std::abs(drop));
}

TEST_CASE("cloth: a sheet crumpled by a rigid plunger does not pass through itself",
          "[core][shell][point_cloud][cloth]") {
  Scene scene(ClothSettings());
  Error e;
  const ActorHandle ground = AddGround(&scene);
  // A kinematic paddle (its lower part below the ground, so that the sheet meets its side face)
  // sweeps along the ground from beyond the sheet's edge to its middle.
  RigidActorDesc paddle = Obstacle("paddle", RigidShapeKind::Box, Eigen::Vector3d(0.01, 0.12, 0.03),
                                   Eigen::Vector3d(-0.1, 0, 0.02));
  paddle.kinematic = true;
  paddle.path = {{0.0, Eigen::Vector3d(-0.1, 0, 0.02), Eigen::Quaterniond::Identity()},
                 {0.5, Eigen::Vector3d(0.02, 0, 0.02), Eigen::Quaterniond::Identity()}};
  const ActorHandle plunger = scene.AddRigidActor(paddle, &e);
  INFO(e.message);
  REQUIRE(plunger.IsValid());
  // The sheet's far edge is held: pushed at the other, it buckles up and folds.
  ShellActorDesc d = Cloth(0.16, 18, Eigen::Vector3d(0, 0, 0.0006));
  NodeConstraint held;
  for (int j = 0; j < d.mesh->NumVertices(); ++j)
    if (d.mesh->vertices[j].x() > 0.079) held.nodes.push_back(j);
  d.constraints.push_back(held);
  d.contact.coulombFrictionCoefficient = 0.6;
  std::unique_ptr<ShellKind> kind = ShellKind::Build(d, &e);
  REQUIRE(kind);
  const ActorHandle cloth = scene.AddActor(std::move(kind), &e);
  REQUIRE(cloth.IsValid());
  const Watch w = Run(&scene, cloth, {ground}, 150, 4e-3);
  const Eigen::VectorXd& x = scene.KindStateOf(cloth).x;
  double top = 0.0, left = INFINITY;
  for (int j = 0; 3 * j < x.size(); ++j) {
    top = std::max(top, x[3 * j + 2]);
    left = std::min(left, x[3 * j]);
  }
  INFO("paddle at x = " << scene.KindStateOf(plunger).x[0] << ", sheet from x = " << left);
  INFO("min φ " << w.minPhi << " m, min admissible distance " << w.minSelf << " m ("
                << w.activeSelf << " frames with self-contact), crumple height " << top << " m");
  CHECK(w.converged == w.steps);
  CHECK(w.activeSelf > 10);
  CHECK(top > 0.02);  // crumpled up, not slid away flat
  CheckBounds(w);
}

}  // namespace superdex
