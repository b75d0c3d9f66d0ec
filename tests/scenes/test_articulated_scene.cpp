// Articulated actors in scene files (scenes/articulated_spec.h, docs/scene-format.md).
//
// Expectations:
//   - a pendulum written as a scene file follows the same trajectory, bit for bit, as the same
//     pendulum built in C++ (ArticulatedKind::Build): the reader sets the joint type, origin, axis,
//     mass properties, initial angle and velocity and the joint parameters as given;
//   - every joint type reads its initial state (a free root's position, orientation and
//     velocities; a spherical joint's orientation) into the tree's layout;
//   - the shipped swinging arm runs with every stage converged, its trajectory carrying the link
//     frames, joint positions, velocities and drive forces;
//   - bad fields are refused with the JSON path and the rule (eleven cases);
//   - links' "shapes" become attached actors named after the articulation and the link (or their
//     own name), nested under it, at their pose in the link frame, with their contact role; their
//     bad fields are named (four cases);
//   - a soft actor's "skin" binds the nodes its selectors pick (a region of the link frame, a
//     distance to the link's shapes) to its parent's links, the scene runs converged, and bad
//     bindings are named (eight cases).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>

#include "core/model/articulated_kind.h"
#include "scene_text.h"
#include "scenes/runner.h"
#include "scenes/scene_file.h"

using namespace superdex;

namespace {

const char* kPendulum = R"({
  "settings": {"dt": 0.005, "duration": 0.5, "integrator": "BDF2"},
  "actors": [
    {"name": "pendulum", "type": "articulated", "links": [
      {"name": "bob", "joint": "Revolute", "axis": [0, 2, 0],
       "origin": {"position": [0, 0, 1], "euler_deg": [0, 0, 30]},
       "mass": 2.0, "center_of_mass": [0, 0, -0.8], "inertia": [0.01, 0.02, 0.03],
       "position": 0.4, "velocity": -0.5,
       "joint_params": {"damping": 0.1, "upper_limit": 0.9, "limit_stiffness": 5000,
                        "drive_stiffness": 3, "drive_target_position": [[0, 0.1], [1, 0.3]]}}
    ]}
  ]
})";

using test::Replace;

using test::LoadError;

}  // namespace

TEST_CASE("an articulated actor read from a scene file is the one built in C++",
          "[scenes][articulated]") {
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneText(kPendulum, ".", &f, &e));
  ArticulatedActorDesc d;
  ArticulatedLinkDesc link;
  link.name = "bob";
  link.joint.type = JointType::Revolute;
  link.joint.axis = Eigen::Vector3d::UnitY();
  link.joint.origin.p = Eigen::Vector3d(0, 0, 1);
  link.joint.origin.R = Eigen::AngleAxisd(30.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  link.mass = 2.0;
  link.centerOfMass = Eigen::Vector3d(0, 0, -0.8);
  link.inertia = Eigen::Vector3d(0.01, 0.02, 0.03).asDiagonal();
  link.jointParams.damping = 0.1;
  link.jointParams.upperLimit = 0.9;
  link.jointParams.limitStiffness = 5000;
  link.jointParams.driveStiffness = 3;
  link.jointParams.driveTargetPosition = {{0, 0.1}, {1, 0.3}};
  d.name = "pendulum";
  d.links.push_back(link);
  d.jointPositions = Eigen::VectorXd::Constant(1, 0.4);
  d.jointVelocities = Eigen::VectorXd::Constant(1, -0.5);
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BDF2;
  Scene built(settings);
  const ActorHandle h = built.AddActor(ArticulatedKind::Build(d, &e), &e);
  REQUIRE(e.ok());
  for (int i = 0; i < 100; ++i) {
    StepReport r1, r2;
    REQUIRE(f.scene->Step(0.005, &r1, &e));
    REQUIRE(built.Step(0.005, &r2, &e));
    REQUIRE(r1.status == StageStatus::Converged);
  }
  CHECK(f.scene->KindStateOf({0}).x == built.KindStateOf(h).x);
  CHECK(f.scene->KindStateOf({0}).v == built.KindStateOf(h).v);
}

TEST_CASE("a scene file sets every joint type's initial state", "[scenes][articulated]") {
  const char* text = R"({
    "settings": {"dt": 0.01, "duration": 0.01, "gravity": [0, 0, 0]},
    "actors": [{"name": "chain", "type": "articulated", "links": [
      {"name": "base", "joint": "Free", "mass": 1, "inertia": [0.1, 0.1, 0.1],
       "position": [1, 2, 3], "euler_deg": [0, 0, 90], "velocity": [0.5, 0, 0],
       "angular_velocity": [0, 0, 2]},
      {"name": "ball", "parent": "base", "joint": "Spherical", "origin": {"position": [0, 0, -1]},
       "mass": 1, "inertia": [0.1, 0.1, 0.1], "euler_deg": [90, 0, 0]},
      {"name": "slide", "parent": "ball", "joint": "Prismatic", "axis": [1, 0, 0],
       "mass": 1, "inertia": [0.1, 0.1, 0.1], "position": 0.25},
      {"name": "weld", "parent": "slide", "joint": "Fixed", "mass": 0, "inertia": [0, 0, 0]}
    ]}]
  })";
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneText(text, ".", &f, &e));
  const auto& kind = dynamic_cast<const ArticulatedKind&>(f.scene->Kind({0}));
  const KindState& s = f.scene->KindStateOf({0});
  const std::vector<RigidPose> poses = kind.LinkPoses(s.x);
  const RigidPose& base = poses[0];
  CHECK((base.p - Eigen::Vector3d(1, 2, 3)).norm() <= 1e-15);
  CHECK((base.R * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm() <= 1e-15);
  const RigidPose& ball = poses[1];
  CHECK((ball.R * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm() <= 1e-15);
  const RigidPose& slide = poses[2];
  CHECK((slide.p - (ball.p + 0.25 * ball.R * Eigen::Vector3d::UnitX())).norm() <= 1e-15);
  const Eigen::VectorXd u = kind.JointVelocities(s);
  CHECK((u.head<6>() - (Eigen::VectorXd(6) << 0.5, 0, 0, 0, 0, 2).finished()).norm() <= 1e-12);
  CHECK(u.tail<4>().norm() <= 1e-12);
}

TEST_CASE("the shipped swinging arm runs converged and reports its joints",
          "[scenes][articulated][shipped]") {
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneFile(std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/swinging_arm.json", &f, &e));
  const std::string out = std::string(SUPERDEX_BINARY_DIR) + "/swinging_arm_test.jsonl";
  RunOptions o;
  o.out = out;
  o.vtk = "";
  RunSummary s;
  REQUIRE(RunScene(&f, o, &s, &e));
  CHECK(s.stopped + s.diverged == 0);
  std::ifstream in(out);
  std::string header, frame;
  std::getline(in, header);
  std::getline(in, frame);
  CHECK(header.find(R"("type":"articulated")") != std::string::npos);
  for (const char* key : {"\"links\"", "\"joint_positions\"", "\"joint_velocities\"", "\"drive_forces\""})
    CHECK(frame.find(key) != std::string::npos);
}

TEST_CASE("bad articulated fields name the JSON path and the rule",
          "[scenes][articulated][bad_input]") {
  CHECK(LoadError(Replace(kPendulum, R"("joint": "Revolute")", R"("joint": "Hinge")")) ==
        "actors[0].links[0].joint: unknown value \"Hinge\" (expected one of: Fixed, Revolute, "
        "Prismatic, Spherical, Free)");
  CHECK(LoadError(Replace(kPendulum, R"("axis": [0, 2, 0])", R"("axis": [0, 0, 0])")) ==
        "actors[0].links[0].axis: must be a non-zero vector");
  CHECK(LoadError(Replace(kPendulum, R"("axis": [0, 2, 0],)", "")) ==
        "actors[0].links[0].axis: missing required field");
  CHECK(LoadError(Replace(kPendulum, R"("mass": 2.0)", R"("mass": -2.0)")) ==
        "actors[0]: articulation 'pendulum': link 0 ('bob'): mass must be finite and >= 0");
  CHECK(LoadError(Replace(kPendulum, "[0.01, 0.02, 0.03]", "[0.01, 0.02, 0.5]")).find(
            "link 0 ('bob'): inertia must be a physical inertia tensor") != std::string::npos);
  CHECK(LoadError(Replace(kPendulum, R"("damping": 0.1)", R"("damping": -0.1)")) ==
        "actors[0]: articulation 'pendulum': link 0 ('bob'): joint_params.damping: must be >= 0, "
        "got -0.1");
  CHECK(LoadError(Replace(kPendulum, R"("upper_limit": 0.9)", R"("upper_limit": 0.9, "lower_limit": 1.0)")) ==
        "actors[0]: articulation 'pendulum': link 0 ('bob'): joint_params.upper_limit: must be >= "
        "lower_limit (1), got 0.9");
  CHECK(LoadError(Replace(kPendulum, "[[0, 0.1], [1, 0.3]]", "[[1, 0.1], [0, 0.3]]")) ==
        "actors[0]: articulation 'pendulum': link 0 ('bob'): joint_params.drive_target_position: "
        "keyframe times must increase");
  CHECK(LoadError(Replace(kPendulum, R"("velocity": -0.5)", R"("angular_velocity": [0, 0, 1])")) ==
        "actors[0].links[0].angular_velocity: a Revolute joint has no rotation");
  CHECK(LoadError(Replace(kPendulum, R"("joint": "Revolute")", R"("joint": "Revolute", "parent": "arm")")) ==
        "actors[0].links[0].parent: no earlier link named \"arm\"");
  CHECK(LoadError(Replace(kPendulum, R"("mass": 2.0)", R"("mass": 2.0, "colour": "red")")) ==
        "actors[0].links[0].colour: unknown field");
}

TEST_CASE("a scene file gives links collision shapes as attached actors",
          "[scenes][articulated][attached]") {
  const std::string withShape = Replace(
      kPendulum, R"("position": 0.4, "velocity": -0.5,)",
      R"("position": 0.4, "velocity": -0.5,
       "shapes": [{"shape": {"type": "sphere", "radius": 0.1}, "position": [0, 0, -0.8],
                   "contact": {"coulomb_friction_coefficient": 0.2}, "collider_type": "Sphere"},
                  {"name": "rod", "shape": {"type": "box", "half_extents": [0.01, 0.01, 0.35]},
                   "position": [0, 0, -0.4], "euler_deg": [0, 0, 45]}],)");
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneText(withShape, "", &f, &e));
  REQUIRE(f.scene->NumActors() == 3);
  REQUIRE(f.actorNames.size() == 3);
  CHECK(f.actorNames[1] == "pendulum/bob");
  CHECK(f.actorNames[2] == "rod");
  const ActorHandle bob{1};
  CHECK(f.scene->IsAttached(bob));
  CHECK(f.scene->Parent(bob).index == 0);
  const RigidBodyModel& m = *f.scene->BodyModel(bob);
  CHECK(m.shape.kind == RigidShapeKind::Sphere);
  CHECK(m.collider.type == ColliderType::Sphere);
  CHECK(m.contact.coulombFrictionCoefficient == 0.2);
  // The sphere sits at the bob's centre of mass.
  const auto& kind = static_cast<const ArticulatedKind&>(f.scene->Kind({0}));
  CHECK((f.scene->BodyState(bob).p - kind.LinkCenter(f.scene->KindStateOf({0}).x, 0)).norm() <
        1e-15);
  // The shapes' own fields are checked where they are.
  CHECK(LoadError(Replace(withShape, R"("radius": 0.1)", R"("radius": -0.1)")) ==
        "actors[0].links[0].shapes[0].shape.radius: must be > 0, got -0.1");
  CHECK(LoadError(Replace(withShape, R"("collider_type": "Sphere")", R"("collider_type": "Round")"))
            .rfind("actors[0].links[0].shapes[0].collider_type: unknown value \"Round\"", 0) == 0);
  CHECK(LoadError(Replace(withShape, R"("name": "rod")", R"("name": "pendulum")")) ==
        "actors[0]: articulation 'pendulum': shape name 'pendulum' is not unique");
  CHECK(LoadError(Replace(withShape, R"({"type": "sphere", "radius": 0.1})",
                          R"({"type": "plane"})")) ==
        "actors[0]: articulation 'pendulum': link 0 ('bob'): shapes[0].shape: a plane is a "
        "static actor's shape, not a link's");
}

TEST_CASE("a scene file gives a soft actor skin bindings on its skeleton's links",
          "[scenes][articulated][skin]") {
  // A vertical carriage with a sphere inside a soft cube: the nodes within 2 mm of the sphere
  // and the cube's top layer (a region of the link frame) ride on the carriage.
  const std::string text = R"({
  "settings": {"dt": 0.01, "duration": 0.1, "integrator": "BackwardEuler"},
  "actors": [
    {"name": "rig", "type": "articulated", "links": [
      {"name": "carriage", "joint": "Prismatic", "axis": [0, 0, 1], "mass": 0.2,
       "inertia": [1e-4, 1e-4, 1e-4], "position": 0.3,
       "joint_params": {"drive_stiffness": 2000, "drive_damping": 50, "drive_target_position": 0.3},
       "shapes": [{"shape": {"type": "sphere", "radius": 0.012}, "position": [0, 0, -0.03]}]}
    ]},
    {"name": "pad", "type": "soft", "parent": "rig", "position": [0, 0, 0.27],
     "mesh": {"type": "box", "half_extents": [0.03, 0.03, 0.03], "cells": [4, 4, 4]},
     "material": {"youngs_modulus": 2e4, "density": 500},
     "skin": [{"link": "carriage", "shape_distance": 0.002},
              {"link": "carriage", "region": {"min": [-1, -1, -0.001], "max": [1, 1, 0.001]}}]}
  ]
})";
  SceneFile f;
  Error e;
  REQUIRE(LoadSceneText(text, "", &f, &e));
  REQUIRE(f.scene->NumActors() == 3);
  const ActorHandle pad{2};
  CHECK(f.scene->Carrier(pad).index == 0);
  CHECK_FALSE(f.scene->IsAttached(pad));
  CHECK(f.scene->ContactAllowed(pad, {1}) == false);  // its own link's sphere
  // The 5 × 5 top layer and the node at the sphere's centre (the lattice's middle node; the
  // sphere of radius 12 mm + 2 mm reaches none of its neighbours, 15 mm away; with 5 mm it
  // reaches the six).
  const std::vector<CarriedPart>& parts = *f.scene->Kind(pad).CarriedParts();
  CHECK(parts.size() == 25 + 1);
  for (int i = 0; i < 10; ++i) {
    StepReport r;
    REQUIRE(f.scene->Step(0.01, &r, &e));
    CHECK(r.status == StageStatus::Converged);
  }
  auto bad = [&](const std::string& from, const std::string& to) {
    return LoadError(Replace(text, from, to));
  };
  const std::string first = R"({"link": "carriage", "shape_distance": 0.002})";
  CHECK(bad(first, R"({"link": "wheel", "shape_distance": 0.002})") ==
        "actors[1].skin[0].link: no link named \"wheel\" in 'rig'");
  CHECK(bad(first, R"({"shape_distance": 0.002})") == "actors[1].skin[0].link: missing required field");
  CHECK(bad(first, R"({"link": "carriage"})") ==
        "actors[1].skin[0]: give at least one of \"nodes\", \"region\" and \"shape_distance\"");
  CHECK(bad(first, R"({"link": "carriage", "shape_distance": -1})") ==
        "actors[1].skin[0].shape_distance: must be >= 0 [m]");
  CHECK(bad(first, R"({"link": "carriage", "nodes": [125]})") ==
        "actors[1].skin[0].nodes[0]: node 125 does not exist (the mesh has 125 nodes)");
  CHECK(bad(first, R"({"link": "carriage", "region": {"min": [0, 0, 0]}})") ==
        "actors[1].skin[0].region: needs \"min\" and \"max\"");
  CHECK(bad(R"("parent": "rig", )", "") ==
        "actors[1].skin: a soft-skinned actor needs its skeleton (an articulated actor) as parent");
  CHECK(bad(R"("skin": [)", R"("skin": 3, "unused": [)").rfind("actors[1]", 0) == 0);
}
