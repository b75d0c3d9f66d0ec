#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "derivative_check.h"
#include "energies/stable_neo_hookean.h"
#include "seeded_random.h"

using namespace superdex;

namespace {

using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

Eigen::Matrix3d RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n01;
  return Eigen::Quaterniond(n01(rng), n01(rng), n01(rng), n01(rng)).normalized()
      .toRotationMatrix();
}

/// A well-shaped rest tet of size ~L = 0.1 m, randomly rotated, perturbed and placed.
struct RestTet {
  Eigen::Vector3d X[4];
  TetElement e;
};
RestTet RandomRestTet(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  const double L = 0.1;
  const Eigen::Matrix3d R = RandomRotation(rng);
  const Eigen::Vector3d c(u(rng), u(rng), u(rng));
  const Eigen::Vector3d base[4] = {{0, 0, 0}, {1, 0, 0}, {0.5, 0.87, 0}, {0.5, 0.29, 0.82}};
  RestTet t;
  for (int i = 0; i < 4; ++i)
    t.X[i] = c + L * R * (base[i] + Eigen::Vector3d(u(rng), u(rng), u(rng)));
  REQUIRE(MakeTetElement(t.X, &t.e));
  return t;
}

struct Deformed {
  RestTet rest;
  Eigen::Matrix3d F;
  LameParameters p;
  const char* kind;
  Eigen::Vector3d x[4];
};

/// 30 states: compressed, stretched, sheared, inverted, near-flat (J ≈ 0, either sign) and
/// general, over soft to stiff, compressible to nearly incompressible (and auxetic) materials.
std::vector<Deformed> RandomStates(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const double E[] = {1e4, 1e6, 1e8};
  const double nu[] = {0.3, 0.45, 0.49, 0.0, -0.3};
  std::vector<Deformed> states;
  for (int n = 0; n < 30; ++n) {
    Deformed d;
    d.rest = RandomRestTet(rng);
    d.p = LameFromYoungPoisson(E[n % 3], nu[n % 5]);
    const Eigen::Matrix3d R1 = RandomRotation(rng), R2 = RandomRotation(rng);
    auto range = [&](double a, double b) { return a + (b - a) * u01(rng); };
    Eigen::Vector3d s;
    switch (n % 6) {
      case 0:
        d.kind = "compressed";
        s = Eigen::Vector3d(range(0.4, 0.9), range(0.4, 0.9), range(0.4, 0.9));
        d.F = R1 * s.asDiagonal() * R2.transpose();
        break;
      case 1:
        d.kind = "stretched";
        s = Eigen::Vector3d(range(1.2, 2.0), range(1.2, 2.0), range(0.8, 1.2));
        d.F = R1 * s.asDiagonal() * R2.transpose();
        break;
      case 2: {
        d.kind = "sheared";
        Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
        S(n % 3, (n + 1) % 3) = range(0.3, 1.5);
        d.F = R1 * S;
        break;
      }
      case 3:
        d.kind = "inverted";
        s = Eigen::Vector3d(range(0.3, 1.5), range(0.3, 1.5), -range(0.3, 1.5));
        d.F = R1 * s.asDiagonal() * R2.transpose();
        break;
      case 4:
        d.kind = "near-flat";
        s = Eigen::Vector3d(range(0.5, 1.5), range(0.5, 1.5), (n % 12 < 6 ? 1 : -1) * 0.02);
        d.F = R1 * s.asDiagonal() * R2.transpose();
        break;
      default:
        d.kind = "general";
        d.F = Eigen::Matrix3d::Identity() + 0.6 * test::UniformMatrix(rng);
        break;
    }
    const Eigen::Vector3d t(range(-1, 1), range(-1, 1), range(-1, 1));
    for (int i = 0; i < 4; ++i) d.x[i] = d.F * d.rest.X[i] + t;
    states.push_back(d);
  }
  return states;
}

/// The same rest tet and material deformed by F instead (translation dropped).
Deformed WithF(const Deformed& d, const Eigen::Matrix3d& F, const char* kind) {
  Deformed m = d;
  m.F = F;
  m.kind = kind;
  for (int i = 0; i < 4; ++i) m.x[i] = F * d.rest.X[i];
  return m;
}

TetElasticTerm Evaluate(const Deformed& d, int order, bool project) {
  TetElasticTerm t;
  EvaluateStableNeoHookean(d.rest.e, d.p, d.x, order, project, &t);
  return t;
}

double MinEigenvalue(const Eigen::MatrixXd& H) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(H).eigenvalues().minCoeff();
}

Eigen::Matrix3d Dm(const TetElement& e) { return e.DmInv.inverse(); }

/// P recovered from the nodal gradient of nodes 1..3 (gradient = V P Dm⁻ᵀ).
Eigen::Matrix3d StressFromGradient(const TetElasticTerm& t, const TetElement& e) {
  Eigen::Matrix3d G;
  for (int i = 0; i < 3; ++i) G.col(i) = t.gradient.segment<3>(3 * (i + 1));
  return G * Dm(e).transpose() / e.restVolume;
}

}  // namespace

TEST_CASE("stable neo-Hookean: Lame parameters and material validation", "[soft]") {
  const LameParameters p = LameFromYoungPoisson(1e6, 0.3);
  CHECK(p.mu == Approx(1e6 / 2.6).epsilon(1e-14));
  CHECK(p.lambda == Approx(0.3e6 / (1.3 * 0.4)).epsilon(1e-14));
  const LameParameters q = LameFromYoungPoisson(2.0, 0.0);
  CHECK(q.mu == 1.0);
  CHECK(q.lambda == 0.0);

}

TEST_CASE("stable neo-Hookean: tet element construction", "[soft]") {
  const Eigen::Vector3d X[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  TetElement e;
  REQUIRE(MakeTetElement(X, &e));
  CHECK(e.restVolume == Approx(1.0 / 6.0));
  CHECK((e.DmInv - Eigen::Matrix3d::Identity()).norm() == 0.0);
  const Eigen::Vector3d inverted[4] = {X[0], X[2], X[1], X[3]};
  CHECK_FALSE(MakeTetElement(inverted, &e));
  const Eigen::Vector3d flat[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 0}};
  CHECK_FALSE(MakeTetElement(flat, &e));
  const Eigen::Vector3d repeated[4] = {X[0], X[1], X[1], X[3]};
  CHECK_FALSE(MakeTetElement(repeated, &e));
  const Eigen::Vector3d notFinite[4] = {X[0], X[1], X[2],
                                        {0, 0, std::numeric_limits<double>::infinity()}};
  CHECK_FALSE(MakeTetElement(notFinite, &e));
}

TEST_CASE("stable neo-Hookean: gradient and Hessian against finite differences",
          "[soft][gradient]") {
  double worstGradient = 0.0, worstHessian = 0.0;
  int inverted = 0;
  for (const Deformed& d : RandomStates(17)) {
    const TetElasticTerm t = Evaluate(d, 2, false);
    inverted += t.detF < 0.0;
    auto f = [&](const Eigen::VectorXd& dx) {
      Eigen::Vector3d x[4];
      for (int i = 0; i < 4; ++i) x[i] = d.x[i] + dx.segment<3>(3 * i);
      TetElasticTerm v;
      EvaluateStableNeoHookean(d.rest.e, d.p, x, 0, false, &v);
      return v.value;
    };
    const auto c = test::CheckDerivatives(f, t.gradient, t.hessian, 1e-5);
    INFO(d.kind << ", J = " << t.detF << ", mu = " << d.p.mu << ", lambda = " << d.p.lambda
                << ": gradient error " << c.gradientError << ", Hessian error "
                << c.hessianError);
    CHECK(c.gradientError <= 1e-6);
    CHECK(c.hessianError <= 1e-5);
    worstGradient = std::max(worstGradient, c.gradientError);
    worstHessian = std::max(worstHessian, c.hessianError);
  }
  CHECK(inverted >= 6);
  WARN("stable neo-Hookean FD check, 30 states (" << inverted << " inverted): worst gradient "
                                                   << worstGradient << ", worst Hessian "
                                                   << worstHessian);
}

TEST_CASE("stable neo-Hookean: zero energy and force at rest and under rigid motions", "[soft]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  const LameParameters p = LameFromYoungPoisson(1e6, 0.45);
  double worstValue = 0.0, worstGradient = 0.0;
  for (int n = 0; n < 20; ++n) {
    const RestTet r = RandomRestTet(rng);
    const Eigen::Matrix3d R = n == 0 ? Eigen::Matrix3d::Identity() : RandomRotation(rng);
    const Eigen::Vector3d c = n == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(u(rng), u(rng), u(rng));
    Eigen::Vector3d x[4];
    for (int i = 0; i < 4; ++i) x[i] = R * r.X[i] + c;
    TetElasticTerm t;
    EvaluateStableNeoHookean(r.e, p, x, 2, false, &t);
    // Natural scales: energy μ V [J], force μ V ‖Dm⁻¹‖ [N].
    const double energyScale = p.mu * r.e.restVolume;
    const double forceScale = energyScale * r.e.DmInv.norm();
    worstValue = std::max(worstValue, std::abs(t.value) / energyScale);
    worstGradient = std::max(worstGradient, t.gradient.norm() / forceScale);
    CHECK(std::abs(t.detF - 1.0) < 1e-12);
  }
  CHECK(StableNeoHookeanEnergyDensity(Eigen::Matrix3d::Identity(), p) == 0.0);
  CHECK(StableNeoHookeanStress(Eigen::Matrix3d::Identity(), p).norm() == 0.0);
  INFO("worst relative energy " << worstValue << ", force " << worstGradient);
  CHECK(worstValue <= 1e-12);
  CHECK(worstGradient <= 1e-12);
}

TEST_CASE("stable neo-Hookean: projected Hessian is PSD and exact where no projection is needed",
          "[soft]") {
  int indefinite = 0, definite = 0;
  double worstMin = 0.0, worstUnchanged = 0.0, worst9 = 0.0;
  std::vector<Deformed> states;
  std::mt19937 mild(41);
  for (unsigned seed : {17u, 18u, 19u}) {
    for (const Deformed& d : RandomStates(seed)) {
      states.push_back(d);
      // Mild deformations, mostly PSD already (and the rest state itself).
      states.push_back(WithF(d, Eigen::Matrix3d::Identity() + 0.05 * test::UniformMatrix(mild),
                             "mild"));
    }
  }
  states.push_back(WithF(states[0], Eigen::Matrix3d::Identity(), "rest"));
  {
    for (const Deformed& d : states) {
      const TetElasticTerm t = Evaluate(d, 2, false);
      const TetElasticTerm tp = Evaluate(d, 2, true);
      const double norm = tp.hessian.norm();
      const double minProjected = MinEigenvalue(tp.hessian);
      INFO(d.kind << ", J = " << t.detF);
      CHECK(minProjected >= -1e-9 * norm);
      worstMin = std::min(worstMin, minProjected / norm);
      CHECK(tp.value == t.value);
      CHECK((tp.gradient - t.gradient).norm() == 0.0);
      if (MinEigenvalue(t.hessian) >= -1e-12 * t.hessian.norm()) {
        ++definite;
        const double diff = (tp.hessian - t.hessian).norm() / t.hessian.norm();
        CHECK(diff <= 1e-12);
        worstUnchanged = std::max(worstUnchanged, diff);
      } else {
        ++indefinite;
        CHECK((tp.hessian - t.hessian).norm() > 1e-6 * t.hessian.norm());
      }
      // The analytic eigensystem projection of ∂²Ψ/∂F² equals the numerical one (eigenvalues
      // of the 9×9 matrix clamped at zero).
      const Eigen::Matrix<double, 9, 9> A = StableNeoHookeanStressDerivative(d.F, d.p, false);
      const Eigen::Matrix<double, 9, 9> Ap = StableNeoHookeanStressDerivative(d.F, d.p, true);
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> es(A);
      const Eigen::Matrix<double, 9, 9> An = es.eigenvectors() *
                                             es.eigenvalues().cwiseMax(0.0).asDiagonal() *
                                             es.eigenvectors().transpose();
      const double diff9 = (Ap - An).norm() / An.norm();
      CHECK(diff9 <= 1e-10);
      worst9 = std::max(worst9, diff9);
    }
  }
  CHECK(indefinite >= 30);
  CHECK(definite >= 30);
  WARN("stable neo-Hookean projection, " << definite << " PSD and " << indefinite
       << " indefinite states: worst min eigenvalue / norm " << worstMin
       << ", worst change of a PSD Hessian " << worstUnchanged
       << ", worst analytic vs numerical 9x9 projection " << worst9);
}

TEST_CASE("stable neo-Hookean: projected Hessian at rest has the rigid null space", "[soft]") {
  std::mt19937 rng(23);
  const LameParameters p = LameFromYoungPoisson(1e6, 0.3);
  for (int n = 0; n < 5; ++n) {
    const RestTet r = RandomRestTet(rng);
    TetElasticTerm t;
    EvaluateStableNeoHookean(r.e, p, r.X, 2, true, &t);
    const double norm = t.hessian.norm();
    Eigen::SelfAdjointEigenSolver<Matrix12d> es(t.hessian);
    const Vector12d ev = es.eigenvalues();
    INFO("eigenvalues / norm: " << (ev / norm).transpose());
    CHECK(ev.head<6>().cwiseAbs().maxCoeff() <= 1e-9 * norm);
    CHECK(ev[6] >= 1e-3 * norm);
    // The six rigid modes themselves: translations and infinitesimal rotations ω × X.
    for (int k = 0; k < 3; ++k) {
      Vector12d tr, rot;
      for (int i = 0; i < 4; ++i) {
        tr.segment<3>(3 * i) = Eigen::Vector3d::Unit(k);
        rot.segment<3>(3 * i) = Eigen::Vector3d::Unit(k).cross(r.X[i]);
      }
      CHECK((t.hessian * tr).norm() <= 1e-9 * norm * tr.norm());
      CHECK((t.hessian * rot).norm() <= 1e-9 * norm * rot.norm());
    }
  }
}

TEST_CASE("stable neo-Hookean: uniform stretch patch test and the linear-elastic limit",
          "[soft]") {
  std::mt19937 rng(29);
  for (double nu : {0.0, 0.3, 0.45, -0.2}) {
    const LameParameters p = LameFromYoungPoisson(1e6, nu);
    const RestTet r = RandomRestTet(rng);
    auto stressAt = [&](const Eigen::Matrix3d& F, Eigen::Matrix3d* fromNodes) {
      Eigen::Vector3d x[4];
      for (int i = 0; i < 4; ++i) x[i] = F * r.X[i];
      TetElasticTerm t;
      EvaluateStableNeoHookean(r.e, p, x, 1, false, &t);
      // Node 0 balances the others (translation invariance).
      CHECK((t.gradient.segment<3>(0) + t.gradient.segment<3>(3) + t.gradient.segment<3>(6) +
             t.gradient.segment<3>(9))
                .norm() <= 1e-12 * t.gradient.norm());
      *fromNodes = StressFromGradient(t, r.e);
    };
    // Large uniaxial stretches and compressions: the nodal forces are V P Dm⁻ᵀ.
    for (double s : {0.5, 0.8, 1.25, 2.0}) {
      const Eigen::Matrix3d F = Eigen::Vector3d(s, 1.0, 1.0).asDiagonal();
      Eigen::Matrix3d Pn;
      stressAt(F, &Pn);
      const Eigen::Matrix3d P = StableNeoHookeanStress(F, p);
      INFO("nu " << nu << ", s " << s);
      CHECK((Pn - P).norm() <= 1e-10 * P.norm());
      // Uniaxial F: P is diagonal.
      CHECK((P - Eigen::Matrix3d(P.diagonal().asDiagonal())).norm() <= 1e-14 * P.norm());
    }
    // Small strain: σ = 2μ ε + λ tr(ε) I, uniaxial and a general symmetric strain.
    std::mt19937 strainRng(43);
    Eigen::Matrix3d S = test::UniformMatrix(strainRng);
    S = (0.5 * (S + S.transpose())).eval();
    for (const Eigen::Matrix3d& strain :
         {Eigen::Matrix3d(Eigen::Vector3d(1e-6, 0.0, 0.0).asDiagonal()),
          Eigen::Matrix3d(1e-6 * S / S.norm())}) {
      const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + strain;
      const Eigen::Matrix3d sigma =
          2.0 * p.mu * strain + p.lambda * strain.trace() * Eigen::Matrix3d::Identity();
      Eigen::Matrix3d Pn;
      stressAt(F, &Pn);
      const Eigen::Matrix3d P = StableNeoHookeanStress(F, p);
      INFO("nu " << nu << ", small strain: |P - sigma|/|sigma| = "
                 << (P - sigma).norm() / sigma.norm() << ", from nodes "
                 << (Pn - sigma).norm() / sigma.norm());
      CHECK((P - sigma).norm() <= 1e-4 * sigma.norm());
      CHECK((Pn - sigma).norm() <= 1e-4 * sigma.norm());
    }
    // ∂²Ψ/∂F² at rest is the linear elasticity tensor: H ↦ μ (H + Hᵀ) + λ tr(H) I.
    Eigen::Matrix<double, 9, 9> C;
    for (int k = 0; k < 9; ++k) {
      Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
      H(k % 3, k / 3) = 1.0;
      const Eigen::Matrix3d CH =
          p.mu * (H + H.transpose()) + p.lambda * H.trace() * Eigen::Matrix3d::Identity();
      C.col(k) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(CH.data());
    }
    const Eigen::Matrix<double, 9, 9> A =
        StableNeoHookeanStressDerivative(Eigen::Matrix3d::Identity(), p, false);
    CHECK((A - C).norm() <= 1e-12 * C.norm());
  }
}

TEST_CASE("stable neo-Hookean: value-only and derivative calls agree exactly", "[soft]") {
  for (const Deformed& d : RandomStates(31)) {
    const TetElasticTerm t0 = Evaluate(d, 0, false);
    const TetElasticTerm t1 = Evaluate(d, 1, false);
    const TetElasticTerm t2 = Evaluate(d, 2, false);
    const TetElasticTerm t2p = Evaluate(d, 2, true);
    CHECK(t0.value == t1.value);
    CHECK(t0.value == t2.value);
    CHECK(t0.value == t2p.value);
    CHECK(t0.detF == t2p.detF);
    Eigen::Matrix3d Ds;
    for (int i = 0; i < 3; ++i) Ds.col(i) = d.x[i + 1] - d.x[0];
    const Eigen::Matrix3d F = Ds * d.rest.e.DmInv;
    CHECK(t0.value == d.rest.e.restVolume * StableNeoHookeanEnergyDensity(F, d.p));
    CHECK((t1.gradient - t2.gradient).norm() == 0.0);
    CHECK(t0.gradient.norm() == 0.0);
    CHECK(t1.hessian.norm() == 0.0);
    CHECK(std::isfinite(t2p.value));
  }
}

TEST_CASE("stable neo-Hookean: collapsed elements (J = 0) are smooth and pushed back",
          "[soft][gradient]") {
  std::mt19937 rng(37);
  const Deformed base = RandomStates(41)[0];
  const Eigen::Matrix3d R = RandomRotation(rng);
  const Eigen::Matrix3d collapsed[] = {
      Eigen::Matrix3d::Zero(),                                       // to a point
      R * Eigen::Vector3d(1.2, 0.0, 0.0).asDiagonal(),               // to a segment
      R * Eigen::Vector3d(1.1, 0.9, 0.0).asDiagonal(),               // to a plane
  };
  for (const Eigen::Matrix3d& F : collapsed) {
    const Deformed d = WithF(base, F, "collapsed");
    const TetElasticTerm t = Evaluate(d, 2, false);
    const TetElasticTerm tp = Evaluate(d, 2, true);
    REQUIRE(std::isfinite(t.value));
    REQUIRE(t.gradient.allFinite());
    REQUIRE(tp.hessian.allFinite());
    CHECK(t.value > 0.0);
    CHECK(MinEigenvalue(tp.hessian) >= -1e-9 * tp.hessian.norm());
    auto f = [&](const Eigen::VectorXd& dx) {
      Eigen::Vector3d x[4];
      for (int i = 0; i < 4; ++i) x[i] = d.x[i] + dx.segment<3>(3 * i);
      TetElasticTerm v;
      EvaluateStableNeoHookean(d.rest.e, d.p, x, 0, false, &v);
      return v.value;
    };
    if (F.norm() == 0.0) {
      // F = 0 is a critical point: P = 0 and ∂²Ψ/∂F² = 0 (I_C = 0, cof F and H_J vanish), so
      // relative finite-difference errors are meaningless there.
      CHECK(t.gradient.norm() == 0.0);
      CHECK(t.hessian.norm() == 0.0);
      continue;
    }
    const auto c = test::CheckDerivatives(f, t.gradient, t.hessian, 1e-5);
    INFO("gradient error " << c.gradientError << ", Hessian error " << c.hessianError);
    CHECK(c.gradientError <= 1e-6);
    CHECK(c.hessianError <= 1e-5);
    // The volume force points towards un-collapsing: moving along −gradient raises J.
    {
      Eigen::Vector3d x[4];
      for (int i = 0; i < 4; ++i) x[i] = d.x[i] - 1e-9 * t.gradient.segment<3>(3 * i) / t.gradient.norm();
      TetElasticTerm moved;
      EvaluateStableNeoHookean(d.rest.e, d.p, x, 0, false, &moved);
      CHECK(moved.value < t.value);
    }
  }
}
