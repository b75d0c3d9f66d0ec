// The kinematic tree (core/model/kinematic_tree.h): forward kinematics of every joint type, the
// point Jacobian and its curvature, and a link's rigid chart with the curvature that carries a
// pose energy's derivatives into the joint coordinates.
//
// Expectations, on a tree with every joint type (a free root, revolute, spherical, prismatic and
// fixed joints, and a branch) at a random configuration with random origins and axes:
//   - Retract and TangentBetween are inverse (1e-12), and Retract keeps rotations rotations;
//   - a joint moves its link as its type says (a revolute joint by its angle about its axis
//     through the joint origin, a prismatic one along its axis, exact to 1e-12);
//   - ∂x/∂δ and Σ f·∂²x/∂δ² of a material point equal central differences of f·x(q ⊕ δ) (relative
//     1e-7 and 1e-5: the step-size floor of second differences);
//   - a link's rigid inertia E(c, R) (energies/rigid_inertia.h) carried into δ by
//     LinkChartJacobian and AddLinkChartCurvature equals central differences of E(q ⊕ δ), every
//     link, to the same tolerances: the exact inertia Hessian in the joint coordinates.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "core/model/kinematic_tree.h"
#include "core/model/rigid_math.h"
#include "energies/rigid_inertia.h"
#include "derivative_check.h"
#include "seeded_random.h"

namespace superdex {
namespace {

RigidPose RandomPose(std::mt19937& rng) {
  RigidPose p;
  p.p = 0.3 * test::UniformVector(3, rng);
  p.R = ExpSo3(2.0 * test::UniformVector(3, rng));
  return p;
}

Eigen::Vector3d RandomAxis(std::mt19937& rng) { return test::UniformVector(3, rng).normalized(); }

/// Free root 0; revolute 1 on 0; spherical 2 on 1; prismatic 3 on 2; fixed 4 on 3; revolute 5 on
/// 1 (a branch).
KinematicTree EveryJointTree(std::mt19937& rng) {
  std::vector<KinematicJoint> j(6);
  const JointType types[6] = {JointType::Free,      JointType::Revolute, JointType::Spherical,
                              JointType::Prismatic, JointType::Fixed,    JointType::Revolute};
  const int parents[6] = {-1, 0, 1, 2, 3, 1};
  for (int l = 0; l < 6; ++l) {
    j[l].type = types[l];
    j[l].parent = parents[l];
    j[l].origin = RandomPose(rng);
    j[l].axis = RandomAxis(rng);
  }
  return KinematicTree(j);
}

/// A configuration away from zero: angles and offsets in [−1, 1], random rotations.
Eigen::VectorXd RandomConfiguration(const KinematicTree& tree, std::mt19937& rng) {
  Eigen::VectorXd q;
  tree.Retract(tree.ZeroConfiguration(), test::UniformVector(tree.NumTangentDofs(), rng), &q);
  return q;
}

RigidPose LinkPose(const KinematicTree& tree, const Eigen::VectorXd& q, int l) {
  KinematicFrames f;
  tree.Evaluate(q, &f);
  return f.link[l];
}

TEST_CASE("a kinematic tree with every joint type is valid and has their sizes") {
  std::mt19937 rng(3);
  const KinematicTree tree = EveryJointTree(rng);
  CHECK(tree.Validate().empty());
  CHECK(tree.NumCoordinates() == 12 + 1 + 9 + 1 + 0 + 1);
  CHECK(tree.NumTangentDofs() == 6 + 1 + 3 + 1 + 0 + 1);
  CHECK(tree.AncestorDofs(4) == std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10});
  CHECK(tree.AncestorDofs(5) == std::vector<int>{0, 1, 2, 3, 4, 5, 6, 11});
  // Groups: the free joint's translations, its rotations, then one per joint.
  CHECK(tree.GroupOf(2) == 0);
  CHECK(tree.GroupOf(3) == 1);
  CHECK(tree.GroupOf(6) == 2);
  CHECK(tree.GroupOf(7) == 3);
  CHECK(tree.GroupOf(9) == 3);
  CHECK(tree.GroupOf(10) == 4);
}

TEST_CASE("Retract and TangentBetween are inverse on every joint type") {
  std::mt19937 rng(5);
  const KinematicTree tree = EveryJointTree(rng);
  const Eigen::VectorXd q = RandomConfiguration(tree, rng);
  const Eigen::VectorXd d = 0.7 * test::UniformVector(tree.NumTangentDofs(), rng);
  Eigen::VectorXd q1, back;
  tree.Retract(q, d, &q1);
  tree.TangentBetween(q, q1, &back);
  CHECK((back - d).norm() <= 1e-12);
  for (int l = 0; l < tree.NumLinks(); ++l) {
    const Eigen::Matrix3d R = LinkPose(tree, q1, l).R;
    CHECK((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() <= 1e-12);
  }
}

TEST_CASE("a revolute joint turns its link about its axis, a prismatic one slides it") {
  std::mt19937 rng(7);
  const KinematicTree tree = EveryJointTree(rng);
  const Eigen::VectorXd q = RandomConfiguration(tree, rng);
  KinematicFrames f;
  tree.Evaluate(q, &f);
  const Eigen::Vector3d X(0.1, -0.2, 0.3);  // a material point of the link
  SECTION("revolute (link 1)") {
    const double angle = 0.4;
    Eigen::VectorXd d = Eigen::VectorXd::Zero(tree.NumTangentDofs()), q1;
    d[tree.TangentOffset(1)] = angle;
    tree.Retract(q, d, &q1);
    const RigidPose parent = f.link[0];
    const Eigen::Vector3d o = parent.p + parent.R * tree.Joint(1).origin.p;
    const Eigen::Vector3d axis = parent.R * tree.Joint(1).origin.R * tree.Joint(1).axis;
    const Eigen::Vector3d x0 = f.link[1].p + f.link[1].R * X;
    const Eigen::Vector3d expected = o + Eigen::AngleAxisd(angle, axis) * (x0 - o);
    const RigidPose moved = LinkPose(tree, q1, 1);
    CHECK((moved.p + moved.R * X - expected).norm() <= 1e-12);
  }
  SECTION("prismatic (link 3)") {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(tree.NumTangentDofs()), q1;
    d[tree.TangentOffset(3)] = 0.25;
    tree.Retract(q, d, &q1);
    const RigidPose pre = f.link[2];
    const Eigen::Vector3d axis = pre.R * tree.Joint(3).origin.R * tree.Joint(3).axis;
    const RigidPose moved = LinkPose(tree, q1, 3);
    CHECK((moved.p - (f.link[3].p + 0.25 * axis)).norm() <= 1e-12);
    CHECK((moved.R - f.link[3].R).norm() <= 1e-12);
  }
}

TEST_CASE("a material point's Jacobian and curvature match central differences on every link") {
  std::mt19937 rng(11);
  const KinematicTree tree = EveryJointTree(rng);
  const Eigen::VectorXd q = RandomConfiguration(tree, rng);
  KinematicFrames f;
  tree.Evaluate(q, &f);
  const int n = tree.NumTangentDofs();
  for (int l = 0; l < tree.NumLinks(); ++l) {
    const Eigen::Vector3d X = 0.5 * test::UniformVector(3, rng);
    const Eigen::Vector3d load = test::UniformVector(3, rng);
    const Eigen::Vector3d x = f.link[l].p + f.link[l].R * X;
    Eigen::MatrixXd J;
    tree.PointJacobian(f, l, x, &J);
    const Eigen::VectorXd g = J.transpose() * load;
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
    tree.AddPointCurvature(f, l, x, load, &H);
    const auto value = [&](const Eigen::VectorXd& d) {
      Eigen::VectorXd q1;
      tree.Retract(q, d, &q1);
      const RigidPose pose = LinkPose(tree, q1, l);
      return load.dot(pose.p + pose.R * X);
    };
    const test::DerivativeCheck c = test::CheckDerivatives(value, g, H, 1e-4);
    INFO("link " << l);
    CHECK(c.gradientError <= 1e-7);
    CHECK(c.hessianError <= 1e-5);
  }
}

TEST_CASE("a link's inertia carried through its chart has the exact Hessian in the joints") {
  std::mt19937 rng(13);
  const KinematicTree tree = EveryJointTree(rng);
  const Eigen::VectorXd q = RandomConfiguration(tree, rng);
  KinematicFrames f;
  tree.Evaluate(q, &f);
  for (int l = 0; l < tree.NumLinks(); ++l) {
    const double mass = 1.7;
    const Eigen::Vector3d com = 0.2 * test::UniformVector(3, rng);  // in the link frame
    const Eigen::Matrix3d A = test::UniformMatrix(rng);
    const Eigen::Matrix3d J = 0.05 * (A * A.transpose() + Eigen::Matrix3d::Identity());
    // Targets away from the pose, as a stage's are.
    const Eigen::Vector3d cHat = f.link[l].p + 0.3 * test::UniformVector(3, rng);
    const Eigen::Matrix3d RHat = f.link[l].R + 0.3 * test::UniformMatrix(rng);
    const auto energy = [&](const RigidPose& pose, bool derivatives) {
      return RigidInertia(mass, J, pose.p + pose.R * com, pose.R, cHat, RHat, derivatives);
    };
    const RigidInertiaTerm e = energy(f.link[l], true);
    const Eigen::Vector3d c = f.link[l].p + f.link[l].R * com;
    Eigen::MatrixXd chart;
    tree.LinkChartJacobian(f, l, c, &chart);
    const Eigen::VectorXd g = chart.transpose() * e.gradient;
    Eigen::MatrixXd H = chart.transpose() * e.hessian * chart;
    tree.AddLinkChartCurvature(f, l, c, e.gradient.head<3>(), e.gradient.tail<3>(), &H);
    const auto value = [&](const Eigen::VectorXd& d) {
      Eigen::VectorXd q1;
      tree.Retract(q, d, &q1);
      return energy(LinkPose(tree, q1, l), false).value;
    };
    const test::DerivativeCheck check = test::CheckDerivatives(value, g, H, 1e-4);
    INFO("link " << l);
    CHECK(check.gradientError <= 1e-7);
    CHECK(check.hessianError <= 1e-5);
  }
}

TEST_CASE("a kinematic tree names the joint and the rule it breaks") {
  KinematicJoint free;
  free.type = JointType::Free;
  KinematicJoint hinge;
  hinge.type = JointType::Revolute;
  hinge.parent = 0;
  SECTION("a parent that is not an earlier link") {
    hinge.parent = 1;
    CHECK_THAT(KinematicTree({free, hinge}).Validate(),
               Catch::Contains("link 1") && Catch::Contains("earlier link"));
  }
  SECTION("an axis that is not unit length") {
    hinge.axis = Eigen::Vector3d(0, 0, 2);
    CHECK_THAT(KinematicTree({free, hinge}).Validate(),
               Catch::Contains("link 1") && Catch::Contains("unit vector"));
  }
  SECTION("a free joint below a link") {
    hinge.parent = -1;
    free.parent = 0;
    CHECK_THAT(KinematicTree({hinge, free}).Validate(),
               Catch::Contains("link 1") && Catch::Contains("Free joint"));
  }
  SECTION("an origin that is not a rotation") {
    hinge.origin.R(0, 0) = 2.0;
    CHECK_THAT(KinematicTree({free, hinge}).Validate(),
               Catch::Contains("link 1") && Catch::Contains("rotation matrix"));
  }
}

}  // namespace
}  // namespace superdex
