// Measured convergence order of every integrator on a soft body: a small stable-neo-Hookean block
// (2 × 2 × 1 cells, 18 nodes, 24 tets) with its x = −a face pinned, released with a uniform
// transverse velocity (the pinned nodes start at rest) and left to oscillate: no gravity, no
// contact, no stiffness damping, so the free nodes obey the smooth autonomous system
//   M ẍ = −∇E(x)   (lumped masses, the same elements and material as the stages).
// The block bends and twists through a nonlinear range (principal stretches up to 14% from 1)
// for about one period of its dominant mode (~0.075 s). Reference: that system integrated
// independently by classical RK4 with 25600 steps, 20 times more than the finest tested (6400
// steps already agree to 3e-14 m; the smallest error measured is 1e-8 m).
//
// Stage solves: exact Hessian (no PSD clamp: the clamped Hessian makes Newton linear here) and full
// Newton steps to a relative gradient of 1e-11. The Armijo line search cannot be used at this
// tolerance: the stage energy carries round-off of ~1e-16 J, so decrements below that are not
// resolved and the stages end Stopped/Diverged.
#include <catch2/catch.hpp>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "core/dynamics/integrators.h"
#include "core/scene.h"

using namespace superdex;

namespace {

constexpr double kHalf = 0.05;   // half extents of the block [m]
constexpr double kT = 0.075;     // about one period of the dominant mode [s]
// 2 × 2 × 1 rather than 2 × 2 × 2: 36 free dofs keep the stages on the dense factorization
// (<= 48 unknowns), about 3 times faster (2 × 2 × 2 gives the same orders, BE only at finer h).
const Eigen::Vector3i kCells(2, 2, 1);
const Eigen::Vector3d kV0(0.0, 0.3, 1.0);  // transverse to the pinned face [m/s]

SoftActorDesc Block() {
  SoftActorDesc d;
  d.name = "block";
  d.mesh = std::make_shared<TetMesh>(MakeTetBox(Eigen::Vector3d::Constant(kHalf), kCells));
  d.meshSource = "MakeTetBox";
  d.material.youngsModulus = 1e5;
  d.material.poissonRatio = 0.3;
  d.material.density = 1000.0;
  d.material.stiffnessDamping = 0.0;
  d.linearVelocity = kV0;
  NodeConstraint pin;  // the face x = −a, held at rest
  for (int i = 0; i < d.mesh->NumVertices(); ++i)
    if (d.mesh->vertices[i].x() == -kHalf) pin.nodes.push_back(i);
  d.constraints.push_back(pin);
  return d;
}

SceneSettings Settings(IntegrationMethod method) {
  SceneSettings s;
  s.integrator = method;
  s.gravity.setZero();
  s.solver.psdProjection = PsdProjection::None;
  s.solver.lineSearch = LineSearchKind::None;
  s.solver.absoluteTolerance = 1e-30;  // effectively off: the gradient test decides
  s.solver.relativeTolerance = 1e-11;
  s.solver.stepTolerance = 1e-13;
  return s;
}

// Accelerations −M⁻¹∇E of the free nodes (zero on the pinned ones).
Eigen::VectorXd Acceleration(const SoftBodyModel& m, const Eigen::VectorXd& x) {
  Eigen::VectorXd a = Eigen::VectorXd::Zero(x.size());
  TetElasticTerm term;
  for (int t = 0; t < m.rest.NumTets(); ++t) {
    const Eigen::Vector4i& T = m.rest.tets[t];
    const Eigen::Vector3d xs[4] = {x.segment<3>(3 * T[0]), x.segment<3>(3 * T[1]),
                                   x.segment<3>(3 * T[2]), x.segment<3>(3 * T[3])};
    EvaluateStableNeoHookean(m.elements[t], m.lame, xs, 1, false, &term);
    for (int k = 0; k < 4; ++k) a.segment<3>(3 * T[k]) -= term.gradient.segment<3>(3 * k);
  }
  for (int i = 0; i < m.NumNodes(); ++i) {
    if (m.freeIndex[i] < 0) a.segment<3>(3 * i).setZero();
    else a.segment<3>(3 * i) /= m.nodeMass[i];
  }
  return a;
}

// Largest |σ − 1| over the tets' principal stretches σ at positions x.
double MaxStrain(const SoftBodyModel& m, const Eigen::VectorXd& x) {
  double s = 0.0;
  for (int t = 0; t < m.rest.NumTets(); ++t) {
    const Eigen::Vector4i& T = m.rest.tets[t];
    Eigen::Matrix3d Ds;
    for (int k = 0; k < 3; ++k) Ds.col(k) = x.segment<3>(3 * T[k + 1]) - x.segment<3>(3 * T[0]);
    const Eigen::Vector3d sigma =
        Eigen::JacobiSVD<Eigen::Matrix3d>(Ds * m.elements[t].DmInv).singularValues();
    s = std::max(s, (sigma.array() - 1.0).abs().maxCoeff());
  }
  return s;
}

struct Reference {
  Eigen::VectorXd x;         // node positions at kT [m]
  double maxStrain = 0.0;    // largest |σ − 1| seen on the way
};

Reference ComputeReference() {
  Scene scene(Settings(IntegrationMethod::BDF2));
  Error e;
  const ActorHandle h = scene.AddSoftActor(Block(), &e);
  REQUIRE(h.IsValid());
  const SoftBodyModel& m = scene.SoftModel(h);
  REQUIRE(m.numFree == 12);  // 6 of the 18 nodes pinned
  Eigen::VectorXd x = scene.SoftState(h).x, v = scene.SoftState(h).v;
  Reference ref;
  const int n = 25600;
  const double dt = kT / n;
  for (int i = 0; i < n; ++i) {
    const Eigen::VectorXd k1x = v, k1v = Acceleration(m, x);
    const Eigen::VectorXd k2x = v + 0.5 * dt * k1v, k2v = Acceleration(m, x + 0.5 * dt * k1x);
    const Eigen::VectorXd k3x = v + 0.5 * dt * k2v, k3v = Acceleration(m, x + 0.5 * dt * k2x);
    const Eigen::VectorXd k4x = v + dt * k3v, k4v = Acceleration(m, x + dt * k3x);
    x += dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (i % 16 == 0) ref.maxStrain = std::max(ref.maxStrain, MaxStrain(m, x));
  }
  ref.x = x;
  return ref;
}

const Reference& GetReference() {
  static const Reference ref = ComputeReference();
  return ref;
}

// Largest error of a free node coordinate at kT [m], integrating with `steps` equal steps.
double FreeNodeError(IntegrationMethod method, int steps) {
  Scene scene(Settings(method));
  Error e;
  const ActorHandle h = scene.AddSoftActor(Block(), &e);
  REQUIRE(h.IsValid());
  const double dt = kT / steps;
  for (int i = 0; i < steps; ++i) {
    StepReport r;
    REQUIRE(scene.Step(dt, &r, &e));
    INFO(ToString(method) << ", " << steps << " steps, step " << i << ": " << r.message);
    REQUIRE(r.status == StageStatus::Converged);
    REQUIRE(r.minDetF > 0.0);
  }
  const SoftBodyModel& m = scene.SoftModel(h);
  const Eigen::VectorXd& x = scene.SoftState(h).x;
  const Eigen::VectorXd& ref = GetReference().x;
  double err = 0.0;
  for (int i = 0; i < m.NumNodes(); ++i)
    if (m.freeIndex[i] >= 0)
      err = std::max(err, (x.segment<3>(3 * i) - ref.segment<3>(3 * i)).lpNorm<Eigen::Infinity>());
  return err;
}

// Free-node positions at kT with stiffness damping β [s], `steps` equal steps.
Eigen::VectorXd DampedFinalPositions(IntegrationMethod method, int steps, double beta) {
  Scene scene(Settings(method));
  Error e;
  SoftActorDesc d = Block();
  d.material.stiffnessDamping = beta;
  const ActorHandle h = scene.AddSoftActor(d, &e);
  REQUIRE(h.IsValid());
  for (int i = 0; i < steps; ++i) {
    StepReport r;
    REQUIRE(scene.Step(kT / steps, &r, &e));
    REQUIRE(r.status == StageStatus::Converged);
  }
  return scene.SoftState(h).x;
}

}  // namespace

TEST_CASE("integrators: stiffness damping keeps second order", "[core][integrator][soft][order]") {
  // The Rayleigh term freezes K at the stage predictor (an O(h²) configuration): the damping
  // force stays second-order accurate, so second-order methods keep their order and third-order
  // ones drop to (at least) 2. Self-convergence against the same method at 1/8 the finest step.
  const double beta = 0.002;  // [s]: damps the dominant mode (≈ 84 rad/s) by ~15 % per period
  for (IntegrationMethod m : {IntegrationMethod::BDF2, IntegrationMethod::DIRK22,
                              IntegrationMethod::SymplecticDIRK12, IntegrationMethod::DIRK33}) {
    DYNAMIC_SECTION(ToString(m)) {
      const int n = 80;
      const Eigen::VectorXd ref = DampedFinalPositions(m, 32 * n, beta);
      double e[3];
      for (int k = 0; k < 3; ++k)
        e[k] = (DampedFinalPositions(m, n << k, beta) - ref).lpNorm<Eigen::Infinity>();
      const double p12 = std::log2(e[0] / e[1]), p23 = std::log2(e[1] / e[2]);
      WARN(ToString(m) << " with beta = " << beta << " s: errors " << e[0] << ", " << e[1] << ", "
                       << e[2] << " m; orders " << p12 << ", " << p23);
      CHECK(p23 > 1.8);
      if (DesignOrder(m) == 2) CHECK(p23 < 2.2);
    }
  }
}

TEST_CASE("integrators: convergence order on an oscillating soft body",
          "[core][integrator][soft][order]") {
  // The test is meant for the nonlinear regime (not a small-strain linear oscillator).
  REQUIRE(GetReference().maxStrain > 0.1);
  for (IntegrationMethod m :
       {IntegrationMethod::BackwardEuler, IntegrationMethod::BDF2, IntegrationMethod::BDF3,
        IntegrationMethod::DIRK22, IntegrationMethod::DIRK23, IntegrationMethod::DIRK33,
        IntegrationMethod::SymplecticDIRK12, IntegrationMethod::SymplecticDIRK22}) {
    DYNAMIC_SECTION(ToString(m)) {
      const int expected = DesignOrder(m);
      // Coarsest step count per order, chosen so that the finest pair is asymptotic: Backward
      // Euler's numerical damping of the stiffer mesh modes (ω up to ~680 rad/s; the dominant
      // mode ≈ 84 rad/s) needs many steps per period before its error is first order.
      const int n = expected == 1 ? 320 : expected == 2 ? 80 : 160;
      const double e1 = FreeNodeError(m, n);
      const double e2 = FreeNodeError(m, 2 * n);
      const double e3 = FreeNodeError(m, 4 * n);
      const double p12 = std::log2(e1 / e2), p23 = std::log2(e2 / e3);
      WARN(ToString(m) << ": h = T/" << n << ", T/" << 2 * n << ", T/" << 4 * n << ": errors "
                       << e1 << ", " << e2 << ", " << e3 << " m; orders " << p12 << ", " << p23
                       << " (design " << expected << "); max strain "
                       << GetReference().maxStrain);
      CHECK(e1 > e2);
      CHECK(e2 > e3);
      CHECK(std::abs(p23 - expected) <= 0.2);
    }
  }
}
