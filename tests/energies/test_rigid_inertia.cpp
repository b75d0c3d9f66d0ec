#include <catch2/catch.hpp>
#include <random>

#include <Eigen/LU>

#include "core/model/rigid_math.h"
#include "derivative_check.h"
#include "energies/rigid_inertia.h"
#include "seeded_random.h"

using namespace superdex;

TEST_CASE("rigid inertia: gradient and Hessian through the exp retraction", "[energies][gradient]") {
  std::mt19937 rng(11);
  std::normal_distribution<double> n01;
  auto rv = [&]() { return Eigen::Vector3d(n01(rng), n01(rng), n01(rng)); };
  for (int trial = 0; trial < 10; ++trial) {
    const double m = 2.5;
    Eigen::Matrix3d A = test::UniformMatrix(rng);
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

TEST_CASE("rigid inertia: the closed-form free-stage minimizer is stationary and global",
          "[energies]") {
  // Φ(p, R) = E(p, R)/Δt² − m g·p over random targets, R̂ a rotation (BackwardEuler's R_n +
  // Δt [ω]× R_n is not one) or an affine combination of rotations (BDF2), and a near-isotropic
  // second moment (a sampled sphere's).
  std::mt19937 rng(5);
  std::normal_distribution<double> n01;
  auto rv = [&]() { return Eigen::Vector3d(n01(rng), n01(rng), n01(rng)); };
  const double m = 1.7, dt = 0.02;
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  for (int trial = 0; trial < 30; ++trial) {
    Eigen::Matrix3d J;
    if (trial % 3 == 0) {
      J = Eigen::Vector3d(0.011, 0.011 * (1 + 1e-9), 0.011).asDiagonal();
    } else {
      const Eigen::Matrix3d A = test::UniformMatrix(rng);
      J = A * A.transpose() + 0.05 * Eigen::Matrix3d::Identity();
    }
    const Eigen::Matrix3d R0 = ExpSo3(rv());
    Eigen::Matrix3d RHat;
    if (trial % 2 == 0) {
      RHat = R0 + dt * 3.0 * Skew(rv()) * R0;  // BackwardEuler: R_n + Δt Ṙ_n, not a rotation
    } else {
      RHat = (4.0 * R0 - ExpSo3(0.3 * rv()) * R0) / 3.0;  // BDF2's combination
    }
    const Eigen::Vector3d pHat = rv();
    const RigidInertiaMinimum x = MinimizeRigidInertia(J, pHat, RHat, dt, g);
    CHECK((x.R.transpose() * x.R - Eigen::Matrix3d::Identity()).norm() < 1e-14);
    CHECK(x.R.determinant() == Approx(1.0).epsilon(1e-14));
    auto phi = [&](const Eigen::Vector3d& p, const Eigen::Matrix3d& R) {
      return RigidInertia(m, J, p, R, pHat, RHat, false).value / (dt * dt) -
             m * g.dot(p);
    };
    // Stationary: the stage gradient (inertia/Δt² and gravity) vanishes to round-off, relative
    // to the inertia forces of a unit step.
    const RigidInertiaTerm t = RigidInertia(m, J, x.p, x.R, pHat, RHat, true);
    Eigen::Matrix<double, 6, 1> grad = t.gradient / (dt * dt);
    grad.head<3>() -= m * g;
    CHECK(grad.head<3>().norm() < 1e-9 * m / (dt * dt));
    CHECK(grad.tail<3>().norm() < 1e-12 * J.norm() / (dt * dt));
    // A minimum: no random rotation or translation, small or large, lowers Φ.
    const double best = phi(x.p, x.R);
    for (int k = 0; k < 50; ++k) {
      const double scale = k < 25 ? 1e-3 : 2.0;
      CHECK(phi(x.p + 1e-3 * rv(), x.R) > best);
      CHECK(phi(x.p, ExpSo3(scale * rv()) * x.R) >= best);
    }
  }
}
