// URDF robots as articulated actors (scenes/urdf_reader.h).
//
// Expectations:
//   - the shipped three-link arm read from its URDF (scenes/data/urdf_arm.json) follows the same
//     arm written link by link (scenes/data/swinging_arm.json) to 1e-12 over 1 s: joint origins,
//     axes, inertials, limits and damping are read as the URDF says;
//   - an <inertial> with a rotated origin gives the link the tensor R I Rᵀ in its frame and its
//     centre of mass at the origin's position (1e-15); a free base gives a Free root joint at the
//     placement's pose; joint positions and velocities by name land in the tree's layout;
//   - bad URDFs and placements are refused naming the file, the element and the problem (nine
//     cases);
//   - <collision> boxes, spheres, cylinders (closed meshes along z) and mesh files become their
//     links' shapes at their origins, with the placement's contact role; a missing mesh, a
//     package:// URI and a zero box size are named (three cases);
//   - the shipped robot scenes' expectations hold: the gripper lifts its box by 10 cm less the
//     lift drive's sag (within 1 mm), the arm pushes its box to the finger's stop (within 4 mm),
//     every stage converged.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "core/model/articulated_kind.h"
#include "core/scene.h"
#include "scene_text.h"
#include "scenes/runner.h"
#include "scenes/scene_file.h"
#include "scenes/urdf_reader.h"

using namespace superdex;

namespace {

const char* kTwoLinks = R"(<?xml version="1.0"?>
<robot name="two">
  <link name="base">
    <inertial><mass value="2"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
  </link>
  <link name="arm">
    <inertial>
      <origin xyz="0.1 0.2 0.3" rpy="0.3 -0.2 1.1"/>
      <mass value="1.5"/>
      <inertia ixx="0.02" ixy="0.001" ixz="0" iyy="0.03" iyz="0.002" izz="0.04"/>
    </inertial>
  </link>
  <joint name="hinge" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.5" rpy="0 0 0.5"/>
    <axis xyz="0 0 2"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>)";

using test::Replace;

std::string UrdfError(const std::string& text, const UrdfPlacement& placement = {}) {
  ArticulatedActorDesc d;
  Error e;
  return ReadUrdf(text, "two.urdf", placement, &d, &e) ? "<read>" : e.message;
}

}  // namespace

TEST_CASE("a URDF arm follows the same arm written link by link", "[scenes][urdf]") {
  SceneFile fromUrdf, byLinks;
  Error e;
  const std::string dir = std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/";
  REQUIRE(LoadSceneFile(dir + "urdf_arm.json", &fromUrdf, &e));
  REQUIRE(LoadSceneFile(dir + "swinging_arm.json", &byLinks, &e));
  const auto& a = dynamic_cast<const ArticulatedKind&>(fromUrdf.scene->Kind({0}));
  const auto& b = dynamic_cast<const ArticulatedKind&>(byLinks.scene->Kind({0}));
  REQUIRE(a.NumLinks() == 4);  // the URDF's massless base, fixed to the world
  REQUIRE(b.NumLinks() == 3);
  double worst = 0.0;
  for (int i = 0; i < 500; ++i) {
    StepReport r;
    REQUIRE(fromUrdf.scene->Step(0.002, &r, &e));
    REQUIRE(r.status == StageStatus::Converged);
    REQUIRE(byLinks.scene->Step(0.002, &r, &e));
    const Eigen::VectorXd qa = a.JointPositions(fromUrdf.scene->KindStateOf({0}).x);
    const Eigen::VectorXd qb = b.JointPositions(byLinks.scene->KindStateOf({0}).x);
    worst = std::max(worst, (qa - qb).cwiseAbs().maxCoeff());
    const std::vector<RigidPose> posesA = a.LinkPoses(fromUrdf.scene->KindStateOf({0}).x);
    const std::vector<RigidPose> posesB = b.LinkPoses(byLinks.scene->KindStateOf({0}).x);
    for (int l = 0; l < 3; ++l) {
      const RigidPose& pa = posesA[l + 1];
      const RigidPose& pb = posesB[l];
      worst = std::max(worst, (pa.p - pb.p).norm() + (pa.R - pb.R).norm());
    }
  }
  INFO("largest joint or link-pose difference " << worst);
  CHECK(worst <= 1e-12);
}

TEST_CASE("a URDF's inertials, joints and placement land where the file says", "[scenes][urdf]") {
  UrdfPlacement placement;
  placement.freeBase = true;
  placement.base.p = Eigen::Vector3d(1, 2, 3);
  placement.jointPositions["hinge"] = 0.4;
  placement.jointVelocities["hinge"] = -0.7;
  ArticulatedActorDesc d;
  Error e;
  REQUIRE(ReadUrdf(kTwoLinks, "two.urdf", placement, &d, &e));
  REQUIRE(d.links.size() == 2);
  CHECK(d.name == "two");
  CHECK(d.links[0].joint.type == JointType::Free);
  CHECK(d.links[0].joint.origin.p == Eigen::Vector3d(1, 2, 3));
  CHECK(d.links[0].mass == 2.0);
  const ArticulatedLinkDesc& arm = d.links[1];
  CHECK(arm.joint.type == JointType::Revolute);
  CHECK(arm.joint.parent == 0);
  CHECK((arm.joint.axis - Eigen::Vector3d::UnitZ()).norm() <= 1e-15);
  CHECK((arm.joint.origin.p - Eigen::Vector3d(0, 0, 0.5)).norm() <= 1e-15);
  CHECK(arm.jointParams.lowerLimit == -1.0);
  CHECK(arm.jointParams.upperLimit == 1.0);
  // URDF's rpy: fixed-axis roll, pitch, yaw, R = Rz(yaw) Ry(pitch) Rx(roll).
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  Eigen::Matrix3d I;
  I << 0.02, 0.001, 0, 0.001, 0.03, 0.002, 0, 0.002, 0.04;
  CHECK((arm.inertia - R * I * R.transpose()).norm() <= 1e-15);
  CHECK((arm.centerOfMass - Eigen::Vector3d(0.1, 0.2, 0.3)).norm() <= 1e-15);
  CHECK(arm.mass == 1.5);
  // Free root: 12 coordinates, then the hinge's angle; 6 tangent dofs, then its rate.
  CHECK(d.jointPositions.size() == 13);
  CHECK(d.jointPositions[12] == 0.4);
  CHECK(d.jointVelocities.size() == 7);
  CHECK(d.jointVelocities[6] == -0.7);
  REQUIRE(ArticulatedKind::Build(d, &e));
}

TEST_CASE("bad URDFs name the file, the element and the problem", "[scenes][urdf][bad_input]") {
  CHECK(UrdfError("<robot name='x'><link name='a'>").rfind("two.urdf: not a valid URDF: ", 0) == 0);
  CHECK(UrdfError(Replace(kTwoLinks, R"(type="revolute")", R"(type="floating")")) ==
        "two.urdf: joint 'hinge': floating joints are supported only as the base (\"base\": "
        "\"free\" in the scene file), not below a link");
  CHECK(UrdfError(Replace(kTwoLinks, R"(type="revolute")", R"(type="planar")")) ==
        "two.urdf: joint 'hinge': planar joints are not supported");
  CHECK(UrdfError(Replace(kTwoLinks, R"(<axis xyz="0 0 2"/>)",
                          R"(<axis xyz="0 0 2"/><mimic joint="other"/>)")) ==
        "two.urdf: joint 'hinge': mimic joints are not supported");
  CHECK(UrdfError(Replace(kTwoLinks, R"(<axis xyz="0 0 2"/>)", R"(<axis xyz="0 0 0"/>)")) ==
        "two.urdf: joint 'hinge': <axis> must be a non-zero vector");
  CHECK(UrdfError(Replace(kTwoLinks, R"(<mass value="1.5"/>)", R"(<mass value="-1.5"/>)")) ==
        "two.urdf: link 'arm': <inertial> mass must be finite and >= 0, got -1.5");
  CHECK(UrdfError(Replace(kTwoLinks, R"(lower="-1" upper="1")", R"(lower="1" upper="-1")")) ==
        "two.urdf: joint 'hinge': <limit> lower 1 must be <= upper -1");
  UrdfPlacement unknown;
  unknown.jointPositions["knee"] = 0.1;
  CHECK(UrdfError(kTwoLinks, unknown) ==
        "two.urdf: joint 'knee': no revolute, continuous or prismatic joint of that name");
  ArticulatedActorDesc d;
  Error e;
  CHECK_FALSE(ReadUrdfFile("/nonexistent/robot.urdf", {}, &d, &e));
  CHECK(e.message == "/nonexistent/robot.urdf: cannot open the URDF file");
}

TEST_CASE("a URDF in a scene file: bad placements are named", "[scenes][urdf][bad_input]") {
  const std::string scene = R"({"settings": {"dt": 0.01, "duration": 0.01}, "actors": [
    {"name": "arm", "type": "articulated", "urdf": "robots/three_link_arm.urdf", "base": "fixed"}]})";
  const std::string dir = std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data";
  const auto load = [&](const std::string& text) {
    SceneFile f;
    Error e;
    return LoadSceneText(text, dir, &f, &e) ? std::string("<loaded>") : e.message;
  };
  CHECK(load(scene) == "<loaded>");
  CHECK(load(Replace(scene, R"("base": "fixed")", R"("base": "floating")")) ==
        "actors[0].base: must be \"fixed\" or \"free\", got \"floating\"");
  CHECK(load(Replace(scene, R"("base": "fixed")", R"("links": [])")) ==
        "actors[0].links: unknown field");
  CHECK(load(Replace(scene, R"("base": "fixed")",
                     R"("joint_params": {"elbow": {"damping": -1}})")) ==
        "actors[0]: articulation 'arm': link 2 ('fore'): joint_params.damping: must be >= 0, "
        "got -1");
  CHECK(load(Replace(scene, "three_link_arm.urdf", "missing.urdf")) ==
        "actors[0].urdf: " + dir + "/robots/missing.urdf: cannot open the URDF file");
}

TEST_CASE("a URDF's collision geometry becomes its links' shapes", "[scenes][urdf][attached]") {
  const std::string withShapes = Replace(
      Replace(kTwoLinks, "</inertial>\n  </link>\n  <link name=\"arm\">",
              "</inertial>\n    <collision><geometry><sphere radius=\"0.05\"/></geometry></collision>\n"
              "  </link>\n  <link name=\"arm\">"),
      "</inertial>\n  </link>\n  <joint",
      "</inertial>\n"
      "    <collision><origin xyz=\"0.1 0 0\" rpy=\"0 0 0.5\"/><geometry><box size=\"0.2 0.04 0.02\"/></geometry></collision>\n"
      "    <collision><geometry><cylinder radius=\"0.01\" length=\"0.1\"/></geometry></collision>\n"
      "  </link>\n  <joint");
  UrdfPlacement p;
  p.contact.coulombFrictionCoefficient = 0.3;
  ArticulatedActorDesc d;
  Error e;
  REQUIRE(ReadUrdf(withShapes, "two.urdf", p, &d, &e));
  REQUIRE(d.links.size() == 2);
  REQUIRE(d.links[0].shapes.size() == 1);
  CHECK(d.links[0].shapes[0].shape.kind == RigidShapeKind::Sphere);
  CHECK(d.links[0].shapes[0].shape.radius == 0.05);
  REQUIRE(d.links[1].shapes.size() == 2);
  const LinkShapeDesc& box = d.links[1].shapes[0];
  CHECK(box.shape.kind == RigidShapeKind::Box);
  CHECK((box.shape.halfExtents - Eigen::Vector3d(0.1, 0.02, 0.01)).norm() < 1e-15);
  CHECK(box.shape.surfaceResolution == 20);  // 0.2 m at 1 cm
  CHECK((box.position - Eigen::Vector3d(0.1, 0, 0)).norm() < 1e-15);
  CHECK(std::abs(box.orientation.angularDistance(
            Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ())))) < 1e-12);
  CHECK(box.contact.coulombFrictionCoefficient == 0.3);
  // A cylinder is a closed mesh along z: its bounds are its radius and half length.
  const LinkShapeDesc& cyl = d.links[1].shapes[1];
  REQUIRE(cyl.shape.kind == RigidShapeKind::Mesh);
  Eigen::Vector3d lo = cyl.shape.mesh->vertices[0], hi = lo;
  for (const Eigen::Vector3d& v : cyl.shape.mesh->vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  CHECK((hi - Eigen::Vector3d(0.01, 0.01, 0.05)).norm() < 1e-12);
  CHECK((lo + Eigen::Vector3d(0.01, 0.01, 0.05)).norm() < 1e-12);
  // Or as a capsule of the cylinder's radius and total length.
  UrdfPlacement capsules = p;
  capsules.cylindersAsCapsules = true;
  REQUIRE(ReadUrdf(withShapes, "two.urdf", capsules, &d, &e));
  CHECK(d.links[1].shapes[1].shape.kind == RigidShapeKind::Capsule);
  CHECK(std::abs(d.links[1].shapes[1].shape.halfLength - 0.04) < 1e-15);
  CHECK(UrdfError(Replace(withShapes, "length=\"0.1\"", "length=\"0.02\""), capsules) ==
        "two.urdf: link 'arm': <cylinder> length 0.02 is not longer than its diameter 0.02: no "
        "capsule of that length (read cylinders as meshes)");
  REQUIRE(ReadUrdf(withShapes, "two.urdf", p, &d, &e));
  // The shapes become attached actors of the articulation.
  Scene scene;
  const ActorHandle h = scene.AddArticulatedActor(d, &e);
  INFO(e.message);
  REQUIRE(h.IsValid());
  CHECK(scene.AttachedActors(h).size() == 3);
  CHECK(scene.ActorName(scene.AttachedActors(h)[2]) == "two/arm#1");
  // Ignored on request.
  p.collisions = false;
  REQUIRE(ReadUrdf(withShapes, "two.urdf", p, &d, &e));
  CHECK(d.links[1].shapes.empty());
  // Mesh files: relative to the URDF's folder; a missing file and package:// URIs are named.
  const std::string mesh = Replace(kTwoLinks, "</inertial>\n  </link>\n  <joint",
                                   "</inertial>\n    <collision><geometry><mesh filename=\"FILE\"/>"
                                   "</geometry></collision>\n  </link>\n  <joint");
  CHECK(UrdfError(Replace(mesh, "FILE", "package://robot/meshes/a.stl")) ==
        "two.urdf: link 'arm': <mesh> 'package://robot/meshes/a.stl': package:// URIs are not "
        "resolved (give a path relative to the URDF file)");
  const std::string missing = UrdfError(Replace(mesh, "FILE", "meshes/none.obj"));
  CHECK(missing.rfind("two.urdf: link 'arm': <mesh> ", 0) == 0);
  CHECK(missing.find("none.obj") != std::string::npos);
  UrdfPlacement inRobots;
  inRobots.meshDirectory = std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/robots";
  REQUIRE(ReadUrdf(Replace(mesh, "FILE", "meshes/gripper_palm.obj"), "two.urdf", inRobots, &d, &e));
  CHECK(d.links[1].shapes.at(0).shape.mesh->NumFaces() == 20);
  CHECK(UrdfError(Replace(withShapes, "<box size=\"0.2 0.04 0.02\"/>", "<box size=\"0.2 0 0.02\"/>")) ==
        "two.urdf: link 'arm': <box> size must be > 0");
}

TEST_CASE("the shipped robot scenes: a gripper lifts a box, an arm pushes one",
          "[scenes][urdf][attached][shipped]") {
  // Their expectations (the scene files' "expect") hold: the runner's checks. soft_pad_grip
  // lifts the box with soft-skinned pads on the fingers.
  for (const char* name : {"gripper_lift.json", "arm_push.json", "soft_pad_grip.json"}) {
    DYNAMIC_SECTION(name) {
      SceneFile f;
      Error e;
      REQUIRE(LoadSceneFile(std::string(SUPERDEX_SOURCE_DIR) + "/scenes/data/" + name, &f, &e));
      RunOptions options;
      options.out = "";
      RunSummary r;
      REQUIRE(RunScene(&f, options, &r, &e));
      for (const std::string& m : r.expectationFailures) UNSCOPED_INFO(m);
      CHECK(r.expectationFailures.empty());
      CHECK(r.converged == r.steps);
    }
  }
}
