// The scene writer (scenes/scene_writer.h): a scene built in C++ (or loaded), written as a scene
// file and loaded again, runs the same trajectory bit for bit; what has no scene-file form is
// refused with the actor and the rule.
#include <catch2/catch.hpp>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/model/rigid_kind.h"
#include "core/model/rigid_math.h"
#include "geometry/tet_mesh.h"
#include "scenes/scene_file.h"
#include "scenes/scene_writer.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

std::string TempDir(const std::string& name) {
  const std::string dir = std::string(SUPERDEX_BINARY_DIR) + "/scene_writer_" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

bool Same(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

// Steps both scenes `steps` times by dt and requires every state to agree bit for bit.
void RequireSameRun(Scene& a, Scene& b, double dt, int steps) {
  REQUIRE(a.NumActors() == b.NumActors());
  Error e;
  for (int k = 0; k <= steps; ++k) {
    for (int i = 0; i < a.NumActors(); ++i) {
      const ActorHandle h{i};
      INFO("step " << k << ", actor " << a.ActorName(h));
      REQUIRE(a.ActorName(h) == b.ActorName(h));
      if (a.IsSoft(h)) {
        REQUIRE(Same(a.SoftState(h).x, b.SoftState(h).x));
        REQUIRE(Same(a.SoftState(h).v, b.SoftState(h).v));
        continue;
      }
      REQUIRE(Same(a.State(h).p, b.State(h).p));
      REQUIRE(Same(a.State(h).R, b.State(h).R));
      REQUIRE(Same(a.State(h).v, b.State(h).v));
      REQUIRE(Same(a.State(h).Rdot, b.State(h).Rdot));
    }
    if (k == steps) break;
    StepReport ra, rb;
    REQUIRE(a.Step(dt, &ra, &e));
    REQUIRE(b.Step(dt, &rb, &e));
  }
}

// A scene that uses what a scene file can say: settings, static, dynamic and kinematic rigid
// actors (sphere, box, mesh, plane), applied loads, a soft actor with driven nodes, nesting, layers
// and actor-pair filtering, and parameters changed after creation.
// `massChanged`: the ball's mass is changed after creation too (the writer keeps it, the second
// moment then follows to round-off only).
std::unique_ptr<Scene> BuiltScene(bool massChanged = false) {
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BDF2;
  settings.gravity = Eigen::Vector3d(0.3, 0, -9.81);
  settings.solver.maxIterations = 60;
  settings.eval.explicitNormals = true;
  auto scene = std::make_unique<Scene>(settings);
  Error e;
  // Its normal is normalized by the actor.
  const RigidActorDesc ground = test::Ground(Eigen::Vector3d(0.01, 0, 1), 1e9, 0.5, 2.0);
  REQUIRE(scene->AddRigidActor(ground, &e).IsValid());
  RigidActorDesc ball;
  ball.name = "ball";
  ball.shape.radius = 0.1;
  ball.shape.surfaceResolution = 2;
  ball.mass = 1.3;
  ball.position = Eigen::Vector3d(0.1, 0.2, 0.1005);
  ball.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  ball.linearVelocity = Eigen::Vector3d(0.3, -0.1, 0);
  ball.angularVelocity = Eigen::Vector3d(1, 0, 2);
  ball.appliedForce = {{0.0, Eigen::Vector3d(0, 1, 0)}, {0.01, Eigen::Vector3d(1, 0, 0)}};
  ball.appliedTorque = {{0.0, Eigen::Vector3d(0, 0, 0.01)}};
  ball.contact.normalViscousDampingCoefficient = 2.0;
  ball.surfaceIntegral = SurfaceIntegral::ExactSphere;
  const ActorHandle b = scene->AddRigidActor(ball, &e);
  REQUIRE(b.IsValid());
  RigidActorDesc box;
  box.name = "box";
  box.shape.kind = RigidShapeKind::Box;
  box.shape.halfExtents = Eigen::Vector3d(0.1, 0.05, 0.04);
  box.density = 700;
  box.position = Eigen::Vector3d(0.6, 0, 0.0405);
  box.contactLayer = "boxes";
  REQUIRE(scene->AddRigidActor(box, &e, b).IsValid());  // nested under the ball
  RigidActorDesc rock;
  rock.name = "rock";
  rock.shape.kind = RigidShapeKind::Mesh;
  rock.shape.mesh = std::make_shared<TriangleMesh>(MakeIcosphere(0.07, 1));
  rock.mass = 0.4;
  rock.position = Eigen::Vector3d(-0.5, 0, 0.0705);
  rock.colliderType = ColliderType::Mesh;
  const ActorHandle r = scene->AddRigidActor(rock, &e);
  REQUIRE(r.IsValid());
  RigidActorDesc paddle;
  paddle.name = "paddle";
  paddle.dynamic = false;
  paddle.kinematic = true;
  paddle.shape.kind = RigidShapeKind::Box;
  paddle.shape.halfExtents = Eigen::Vector3d(0.01, 0.2, 0.05);
  PoseKeyframe k0, k1;
  k0.position = Eigen::Vector3d(0.45, 0, 0.06);
  k1.t = 0.05;
  k1.position = Eigen::Vector3d(0.5, 0, 0.06);
  k1.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  paddle.path = {k0, k1};
  REQUIRE(scene->AddRigidActor(paddle, &e).IsValid());
  SoftActorDesc jelly;
  jelly.name = "jelly";
  jelly.mesh = std::make_shared<TetMesh>(MakeTetBox(Eigen::Vector3d(0.05, 0.05, 0.05),
                                                    Eigen::Vector3i(2, 2, 2)));
  jelly.position = Eigen::Vector3d(0, -0.6, 0.0505);
  jelly.material.youngsModulus = 2e5;
  jelly.material.stiffnessDamping = 0.01;
  jelly.constraints.push_back({{0, 1}, {{0.0, Eigen::Vector3d::Zero()},
                                         {0.05, Eigen::Vector3d(0, 0, 0.01)}}});
  const ActorHandle j = scene->AddSoftActor(jelly, &e);
  REQUIRE(j.IsValid());
  // Changed after creation: kept by the writer.
  ContactParams c = scene->GetContactParams(r);
  c.coulombFrictionCoefficient = 0.3;
  REQUIRE(scene->SetContactParams(r, c, &e));
  if (massChanged) REQUIRE(scene->SetRigidMass(b, 1.1, &e));
  REQUIRE(scene->SetSoftMaterial(j, 3e5, jelly.material.density, &e));  // E alone: exact
  REQUIRE(scene->SetContactLayer(j, "soft", &e));
  REQUIRE(scene->EnableLayerContactAsymmetric("soft", "boxes", false, &e));
  REQUIRE(scene->EnableActorContactSymmetric(r, b, false, IncludeNestedActors::Yes, &e));
  return scene;
}

}  // namespace

TEST_CASE("scene writer: a built scene written and loaded runs the same trajectory bit for bit",
          "[scenes][writer]") {
  std::unique_ptr<Scene> scene = BuiltScene();
  const std::string dir = TempDir("built");
  SceneWriteOptions options;
  options.dt = 2e-3;
  options.duration = 0.1;
  options.description = "written by the test";
  Error e;
  REQUIRE(WriteSceneFile(*scene, dir + "/built.json", options, &e));
  CHECK(std::filesystem::exists(dir + "/built.rock.obj"));
  CHECK(std::filesystem::exists(dir + "/built.jelly.msh"));
  SceneFile f;
  INFO(e.message);
  REQUIRE(LoadSceneFile(dir + "/built.json", &f, &e));
  CHECK(f.dt == 2e-3);
  CHECK(f.duration == 0.1);
  CHECK(f.description == "written by the test");
  Scene& loaded = *f.scene;
  CHECK(loaded.GetContactParams(loaded.FindActor("rock")).coulombFrictionCoefficient == 0.3);
  CHECK(loaded.SoftModel(loaded.FindActor("jelly")).material.youngsModulus == 3e5);
  CHECK(loaded.ContactLayer(loaded.FindActor("jelly")) == "soft");
  CHECK(loaded.RigidDesc(loaded.FindActor("ball")).surfaceIntegral == SurfaceIntegral::ExactSphere);
  CHECK(loaded.Parent(loaded.FindActor("box")).index == loaded.FindActor("ball").index);
  CHECK_FALSE(loaded.ContactAllowed(loaded.FindActor("jelly"), loaded.FindActor("box")));
  CHECK(loaded.ContactAllowed(loaded.FindActor("box"), loaded.FindActor("jelly")));
  CHECK_FALSE(loaded.ContactAllowed(loaded.FindActor("box"), loaded.FindActor("rock")));
  CHECK_FALSE(loaded.ContactAllowed(loaded.FindActor("rock"), loaded.FindActor("ball")));
  CHECK(loaded.ContactAllowed(loaded.FindActor("box"), loaded.FindActor("ground")));
  RequireSameRun(*scene, loaded, options.dt, 25);
}

TEST_CASE("scene writer: a mass changed after creation is written", "[scenes][writer]") {
  std::unique_ptr<Scene> scene = BuiltScene(true);
  const std::string dir = TempDir("mass");
  Error e;
  REQUIRE(WriteSceneFile(*scene, dir + "/mass.json", SceneWriteOptions(), &e));
  SceneFile f;
  REQUIRE(LoadSceneFile(dir + "/mass.json", &f, &e));
  const RigidBodyModel& a = scene->Model(scene->FindActor("ball"));
  const RigidBodyModel& b = f.scene->Model(f.scene->FindActor("ball"));
  CHECK(b.mass == 1.1);
  CHECK((b.secondMoment - a.secondMoment).norm() < 1e-15 * a.secondMoment.norm());
}

TEST_CASE("scene writer: the shipped scenes written and loaded run bit for bit",
          "[scenes][writer][shipped]") {
  for (const char* name : {"drop", "box_rest", "stack", "incline", "tumble", "push", "pyramid",
                           "soft_cube_press", "soft_cylinder_on_blocks", "damping_sweep"}) {
    DYNAMIC_SECTION(name) {
      SceneFile original, written;
      Error e;
      REQUIRE(LoadSceneFile(std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/" + name + ".json",
                            &original, &e));
      const std::string dir = TempDir(name);
      SceneWriteOptions options;
      options.dt = original.dt;
      options.duration = original.duration;
      REQUIRE(WriteSceneFile(*original.scene, dir + "/" + name + ".json", options, &e));
      INFO(e.message);
      REQUIRE(LoadSceneFile(dir + "/" + name + ".json", &written, &e));
      RequireSameRun(*original.scene, *written.scene, original.dt, 20);
    }
  }
}

TEST_CASE("scene writer: what has no scene-file form is refused, naming the actor and the rule",
          "[scenes][writer][bad_input]") {
  const std::string dir = TempDir("refused");
  SceneWriteOptions options;
  Error e;
  {
    std::unique_ptr<Scene> scene = BuiltScene();
    StepReport r;
    REQUIRE(scene->Step(1e-3, &r, &e));
    CHECK_FALSE(WriteSceneFile(*scene, dir + "/stepped.json", options, &e));
    CHECK_THAT(e.message, Catch::Contains("scene: it has stepped to t = 0.001"));
  }
  {
    std::unique_ptr<Scene> scene = BuiltScene();
    const ActorHandle j = scene->FindActor("jelly");
    SoftBodyState s = scene->SoftState(j);
    s.v.setConstant(0.1);  // a uniform velocity change: written
    REQUIRE(scene->SetSoftState(j, s, &e));
    REQUIRE(WriteSceneFile(*scene, dir + "/soft.json", options, &e));
    SceneFile f;
    REQUIRE(LoadSceneFile(dir + "/soft.json", &f, &e));
    // The free nodes move at the new velocity (the driven ones start on their path's, as built).
    const ActorHandle k = f.scene->FindActor("jelly");
    const SoftBodyModel& m = f.scene->SoftModel(k);
    for (int n = 0; n < m.NumNodes(); ++n)
      if (m.freeIndex[n] >= 0)
        CHECK((f.scene->SoftState(k).v.segment<3>(3 * n) - s.v.segment<3>(3 * n)).norm() < 1e-14);
    s.x[0] += 1e-3;  // one node moved: no scene-file form
    REQUIRE(scene->SetSoftState(j, s, &e));
    CHECK_FALSE(WriteSceneFile(*scene, dir + "/soft.json", options, &e));
    CHECK_THAT(e.message, Catch::Contains("jelly: a soft actor's state set after its creation, "
                                          "other than a uniform shift"));
  }
  {
    Scene scene;
    RigidActorDesc d;
    d.name = "odd";
    d.inertia = Eigen::Matrix3d::Identity() * 0.01;
    (*d.inertia)(0, 1) = (*d.inertia)(1, 0) = 0.001;
    REQUIRE(scene.AddRigidActor(d, &e).IsValid());
    CHECK_FALSE(WriteSceneFile(scene, dir + "/inertia.json", options, &e));
    CHECK_THAT(e.message, Catch::Contains("odd.inertia: a full inertia tensor has no scene-file form"));
    RigidActorDesc k;
    k.name = "kind";
    k.position.z() = 3;
    REQUIRE(scene.AddActor(RigidKind::Build(k, &e), &e).IsValid());
    CHECK_FALSE(WriteSceneFile(scene, dir + "/kind.json", options, &e));
  }
  // A set rigid state is written (its orientation to round-off) and loads to the same pose.
  std::unique_ptr<Scene> scene = BuiltScene();
  const ActorHandle b = scene->FindActor("ball");
  RigidBodyState s = scene->State(b);
  s.p += Eigen::Vector3d(0, 0, 0.5);
  s.R = ExpSo3(Eigen::Vector3d(0.1, 0.2, 0.3)) * s.R;
  s.Rdot = Skew(Eigen::Vector3d(0, 3, 0)) * s.R;
  REQUIRE(scene->SetState(b, s, &e));
  REQUIRE(WriteSceneFile(*scene, dir + "/set.json", options, &e));
  SceneFile f;
  REQUIRE(LoadSceneFile(dir + "/set.json", &f, &e));
  const RigidBodyState& t = f.scene->State(f.scene->FindActor("ball"));
  CHECK((t.p - s.p).norm() < 1e-15);
  CHECK((t.R - s.R).norm() < 1e-15);
  CHECK((t.AngularVelocity() - s.AngularVelocity()).norm() < 1e-13);
}
