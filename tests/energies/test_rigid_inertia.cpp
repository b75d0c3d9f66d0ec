#include <catch2/catch.hpp>
#include <random>

#include "core/rigid_math.h"
#include "derivative_check.h"
#include "energies/rigid_inertia.h"

using namespace superdex;

TEST_CASE("rigid inertia: gradient and Hessian through the exp retraction", "[energies][gradient]") {
  std::mt19937 rng(11);
  std::normal_distribution<double> n01;
  auto rv = [&]() { return Eigen::Vector3d(n01(rng), n01(rng), n01(rng)); };
  for (int trial = 0; trial < 10; ++trial) {
    const double m = 2.5;
    Eigen::Matrix3d A = Eigen::Matrix3d::Random();
    const Eigen::Matrix3d J = A * A.transpose() + 0.1 * Eigen::Matrix3d::Identity();
    const Eigen::Vector3d p = rv(), pHat = rv();
    const Eigen::Matrix3d R = ExpSo3(rv());
    // R̂ an affine combination of rotations, as BDF2 makes it.
    const Eigen::Matrix3d RHat = (4.0 * ExpSo3(rv()) - ExpSo3(rv())) / 3.0;
    const RigidInertiaTerm t = RigidInertia(m, J, p, R, pHat, RHat, true);
    auto f = [&](const Eigen::VectorXd& d) {
      return RigidInertia(m, J, p + d.head<3>(), ExpSo3(d.tail<3>()) * R, pHat, RHat, false).value;
    };
    const auto c = test::CheckDerivatives(f, t.gradient, t.hessian, 1e-4);
    INFO("gradient error " << c.gradientError << ", Hessian error " << c.hessianError);
    CHECK(c.gradientError < 1e-8);
    CHECK(c.hessianError < 1e-6);
  }
}

TEST_CASE("rigid inertia: rotational block is the world inertia tensor at R = R^", "[energies]") {
  const Eigen::Matrix3d J = Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal();
  const Eigen::Matrix3d R = ExpSo3(Eigen::Vector3d(0.3, -0.2, 0.5));
  const RigidInertiaTerm t =
      RigidInertia(1.0, J, Eigen::Vector3d::Zero(), R, Eigen::Vector3d::Zero(), R, true);
  const Eigen::Matrix3d I = R * (J.trace() * Eigen::Matrix3d::Identity() - J) * R.transpose();
  CHECK((t.hessian.bottomRightCorner<3, 3>() - I).norm() < 1e-12);
  CHECK(t.gradient.norm() < 1e-12);
  CHECK(t.value == Approx(0.0).margin(1e-14));
}
