// The closed-form linearization of the current-mode dissipation kernel against forward-mode AD
// of the same formulas, on every branch: both load modes, fading on/off, both split directions,
// Coulomb speed at zero, in the stick region and sliding.
#include <catch2/catch.hpp>
#include <random>

#include "core/contact/dissipation_kernels.h"
#include "seeded_random.h"

using namespace superdex;
using namespace superdex::dissipation_kernels;

namespace {

double RelativeDifference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / std::max(1.0, b.norm());
}

}  // namespace

TEST_CASE("current-mode dissipation kernel: closed-form linearization equals AD",
          "[core][dissipation]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto vec = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  int cases = 0;
  for (DissipationMode mode : {DissipationMode::ReconstructedLoad, DissipationMode::ImplicitLoad})
    for (bool fade : {true, false})
      for (bool colliderNormal : {true, false})
        for (double speedScale : {0.0, 0.3, 3.0})  // tangential speed in units of V_f
          for (int trial = 0; trial < 12; ++trial) {
            DissipationSetup s;
            s.mode = mode;
            s.fadeFriction = fade;
            s.frictionWithColliderNormal = colliderNormal;
            s.maxAlignment = fade ? -0.3 : 0.0;
            s.dt = 0.01;
            s.penalty.k = 1e6;
            s.penalty.eps = 2e-3;
            s.penalty.delta = 5e-4;
            s.coefficients.mu = 0.6;
            s.coefficients.ct = 0.2;
            s.coefficients.cn = 0.7;
            s.coefficients.vf = 0.01;
            // A field sample: gradient of norm near 1 (a grid field's is not exactly 1), a
            // symmetric Hessian, and a value inside the ramp or past it (both branches of h).
            SdfSample field;
            field.gradient = (Eigen::Vector3d(0.0, 0.0, 1.0) + 0.2 * vec()).normalized() *
                             (1.0 + 0.05 * u(rng));
            const Eigen::Matrix3d A = test::UniformMatrix(rng);
            // Trials 8-11: a flat field (∇²Φ = 0: planes, box faces), the kernel's short path.
            field.hessian = trial < 8 ? Eigen::Matrix3d(3.0 * (A + A.transpose()))
                                      : Eigen::Matrix3d::Zero();
            field.value = trial % 2 ? -1e-3 * (1.0 + u(rng)) : -1e-4 * (1.0 + u(rng));
            const Eigen::Vector3d Y = 0.1 * vec();
            const Eigen::Vector3d Yn = Y + 1e-4 * vec();
            const Eigen::Vector3d NA = -(field.gradient.normalized() + 0.1 * vec());
            // Stage-start pullback: a velocity (Y − Y0)/Δt with the requested tangential speed.
            const Eigen::Vector3d N = SplitDirection<double>(field.gradient, NA, s);
            Eigen::Vector3d tangent = vec();
            tangent -= tangent.dot(N) * N;
            tangent.normalize();
            const Eigen::Vector3d V = speedScale * s.coefficients.vf * tangent + 0.02 * u(rng) * N;
            const Eigen::Vector3d Y0 = Y - s.dt * V;

            const CurrentModeLinearization closed = LinearizeCurrentModeGradient(Y, NA, field, Yn, Y0, s);
            const CurrentModeLinearization ad = LinearizeCurrentModeGradientByJets(Y, NA, field, Yn, Y0, s);
            INFO("mode " << ToString(mode) << ", fade " << fade << ", collider normal "
                         << colliderNormal << ", speed " << speedScale << " V_f, trial " << trial);
            REQUIRE(ad.g.norm() > 0.0);
            CHECK(RelativeDifference(closed.g, ad.g) < 1e-13);
            CHECK(RelativeDifference(closed.GY, ad.GY) < 1e-12);
            CHECK(RelativeDifference(closed.GN, ad.GN) < 1e-12);
            ++cases;
          }
  CHECK(cases == 2 * 2 * 2 * 3 * 12);
}
