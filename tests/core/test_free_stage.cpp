// The closed-form free stage (SceneSettings::closedFormFreeStages): where no contact sample is
// active at the minimizer of inertia and gravity, a stage is solved without Newton iterations.
// Its poses must be Newton's to Newton's tolerance, in every integrator and dissipation mode, and
// a stage where contact (penalty or retained dissipation) acts must still go to Newton.
#include <catch2/catch.hpp>

#include "core/dynamics/integrators.h"
#include "core/model/rigid_math.h"
#include "core/scene.h"
#include "scene_builders.h"

using namespace superdex;

namespace {

struct Run {
  std::vector<RigidBodyState> end;
  long newton = 0;
  int notConverged = 0;
  int stages = 0;
  int freeStages = 0;  // stages solved in closed form (StepReport::freeStages)
  double maxDifference = 0.0;
};

// Steps `scene` and `reference` (the same scene with Newton on every stage) side by side; the
// largest difference of a dynamic body's position [m] or orientation (‖R − R_ref‖_F) over the run.
Run RunBoth(Scene& scene, Scene& reference, double dt, int steps, long* referenceNewton) {
  Run run;
  Error e;
  for (int i = 0; i < steps; ++i) {
    StepReport r, rr;
    REQUIRE(scene.Step(dt, &r, &e));
    REQUIRE(reference.Step(dt, &rr, &e));
    run.newton += r.newtonIterations;
    *referenceNewton += rr.newtonIterations;
    run.stages += r.stages;
    run.freeStages += r.freeStages;
    if (r.status != StageStatus::Converged) ++run.notConverged;
    for (int a = 0; a < scene.NumActors(); ++a) {
      const RigidBodyState s = scene.State(ActorHandle{a});
      const RigidBodyState t = reference.State(ActorHandle{a});
      run.maxDifference = std::max({run.maxDifference, (s.p - t.p).norm(), (s.R - t.R).norm()});
    }
  }
  for (int a = 0; a < scene.NumActors(); ++a) run.end.push_back(scene.State(ActorHandle{a}));
  return run;
}

// An asymmetric box (0.2 × 0.4 × 0.6 m, 2 kg) tumbling high above a ground plane: a candidate
// pair exists (a plane's box is unbounded) but no sample is near it.
RigidActorDesc TumblingBox() {
  RigidActorDesc box = test::Cube(1e9, 0.5, 1.0);
  box.shape.halfExtents = Eigen::Vector3d(0.1, 0.2, 0.3);
  box.mass = 2.0;
  box.position = Eigen::Vector3d(0, 0, 50);
  box.linearVelocity = Eigen::Vector3d(1.0, -0.5, 2.0);
  box.angularVelocity = Eigen::Vector3d(3.0, 0.2, -1.0);  // near the middle axis: unstable
  return box;
}

}  // namespace

TEST_CASE("Free-flight stages are solved in closed form and agree with Newton's", "[free_stage]") {
  for (IntegrationMethod method :
       {IntegrationMethod::BackwardEuler, IntegrationMethod::BDF2, IntegrationMethod::BDF3,
        IntegrationMethod::DIRK22, IntegrationMethod::DIRK23, IntegrationMethod::DIRK33,
        IntegrationMethod::SymplecticDIRK12, IntegrationMethod::SymplecticDIRK22}) {
    DYNAMIC_SECTION(ToString(method)) {
      SceneSettings settings;
      settings.integrator = method;
      SceneSettings newton = settings;
      newton.closedFormFreeStages = false;
      Scene scene(settings), reference(newton);
      Error e;
      for (Scene* s : {&scene, &reference}) {
        REQUIRE(s->AddRigidActor(test::StaticGround(), &e).IsValid());
        REQUIRE(s->AddRigidActor(TumblingBox(), &e).IsValid());
      }
      long referenceNewton = 0;
      const Run run = RunBoth(scene, reference, 1e-2, 50, &referenceNewton);
      INFO("largest pose difference " << run.maxDifference << "; Newton iterations "
                                       << referenceNewton << " with Newton on every stage");
      CHECK(run.notConverged == 0);
      CHECK(run.newton == 0);
      CHECK(run.freeStages == run.stages);
      // (BDF3 starts with extra stages.)
      CHECK(run.stages >= 50 * (IsMultistep(method) ? 1 : TableauOf(method).stages));
      CHECK(referenceNewton >= 50);
      // Newton stops at a Newton decrement of 1e-12 J after a full step (quadratic phase): its
      // poses are the minimizer's to far below that.
      CHECK(run.maxDifference < 1e-10);
    }
  }
}

TEST_CASE("A body leaving and meeting contact goes to Newton where contact acts",
          "[free_stage]") {
  // A cube thrown up and sideways off the ground with friction and normal damping: it leaves the
  // contact (where explicit normals retain the stage-start load for one more stage), flies and
  // lands again. Where it is taken right the closed form agrees with Newton to Newton's tolerance,
  // amplified through the landing (3e-12 m measured); taken at a stage where only dissipation
  // acts (a retained or reconstructed load, no penalty sample active) the runs part by 0.86 m.
  for (int mode : {0, 1, 2}) {
    DYNAMIC_SECTION(test::kModeNames[mode]) {
      SceneSettings settings;
      settings.eval = test::EvalParamsForMode(mode);
      SceneSettings newton = settings;
      newton.closedFormFreeStages = false;
      Scene scene(settings), reference(newton);
      Error e;
      RigidActorDesc cube = test::Cube(1e9, 0.5, 1.0);
      cube.position = Eigen::Vector3d(0, 0, 0.1 - 2e-4);  // resting in the penalty band
      cube.linearVelocity = Eigen::Vector3d(1.0, 0.0, 1.0);
      cube.angularVelocity = Eigen::Vector3d(0.0, 2.0, 0.0);
      for (Scene* s : {&scene, &reference}) {
        REQUIRE(s->AddRigidActor(test::StaticGround(1e9, 0.5), &e).IsValid());
        REQUIRE(s->AddRigidActor(cube, &e).IsValid());
      }
      long referenceNewton = 0;
      const Run run = RunBoth(scene, reference, 5e-3, 100, &referenceNewton);  // 0.5 s
      INFO("largest pose difference " << run.maxDifference << "; free stages " << run.freeStages
                                       << "; Newton iterations " << run.newton << " against "
                                       << referenceNewton);
      CHECK(run.notConverged == 0);
      // Airborne for about 0.3 s of the 0.5 (v_z = 1 m/s: 2 v_z / g = 0.2 s, plus the tumble).
      CHECK(run.freeStages >= 20);
      CHECK(run.freeStages < run.stages);
      CHECK(run.newton < referenceNewton);
      CHECK(run.maxDifference < 1e-9);
      // It landed: the end is in contact, below 10 cm plus the box's half diagonal.
      CHECK(run.end[1].p.z() < 0.1 * std::sqrt(3.0));
    }
  }
}

TEST_CASE("Two bodies that meet each other leave the closed form while they touch",
          "[free_stage]") {
  // Two spheres in zero gravity flying head-on into each other (both dynamic: each is the other's
  // collider), spinning, with friction: free, in contact, free again.
  SceneSettings settings;
  settings.gravity.setZero();
  SceneSettings newton = settings;
  newton.closedFormFreeStages = false;
  Scene scene(settings), reference(newton);
  Error e;
  RigidActorDesc a = test::Ball(0.1, 0.5), b = test::Ball(0.1, 0.5);
  a.name = "a";
  b.name = "b";
  a.position = Eigen::Vector3d(-0.2, 0.0, 0.0);
  b.position = Eigen::Vector3d(0.2, 0.03, 0.0);  // off centre: a glancing impact
  a.linearVelocity = Eigen::Vector3d(1.0, 0.0, 0.0);
  b.linearVelocity = Eigen::Vector3d(-1.0, 0.0, 0.0);
  a.angularVelocity = Eigen::Vector3d(0.0, 0.0, 5.0);
  for (Scene* s : {&scene, &reference}) {
    REQUIRE(s->AddRigidActor(a, &e).IsValid());
    REQUIRE(s->AddRigidActor(b, &e).IsValid());
  }
  long referenceNewton = 0;
  const Run run = RunBoth(scene, reference, 2e-3, 150, &referenceNewton);  // 0.3 s
  INFO("largest pose difference " << run.maxDifference << "; free stages " << run.freeStages
                                   << " of " << run.stages);
  CHECK(run.notConverged == 0);
  CHECK(run.freeStages >= 60);             // about 0.1 s of approach, then the separation
  CHECK(run.freeStages < run.stages - 5);  // the impact went to Newton
  CHECK(run.maxDifference < 1e-9);
  // They met and parted: a moves back (or sideways) after the impact.
  CHECK(run.end[0].v.x() < 0.9);
}
