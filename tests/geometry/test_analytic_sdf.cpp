// Analytic SDFs: values against closed forms, exactness (the projection X − Φ∇Φ lands on the
// surface and no surface point is closer), and gradient and Hessian against central finite
// differences of the value, region by region for the box.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "geometry/analytic_sdf.h"

using namespace superdex;

namespace {

// Central differences of the value only: gradient with step hg; Hessian by the four-point second
// difference [Φ(X+h e_i+h e_j) − Φ(X+h e_i−h e_j) − Φ(X−h e_i+h e_j) + Φ(X−h e_i−h e_j)]/(4h²)
// (on the diagonal the three-point formula with step 2h).
template <typename Sdf>
void CheckAgainstDifferences(const Sdf& sdf, const Eigen::Vector3d& X) {
  const double hg = 1e-6, hh = 5e-5;
  const SdfSample s = sdf.Evaluate(X);
  auto phi = [&](const Eigen::Vector3d& Y) { return sdf.Evaluate(Y).value; };
  Eigen::Vector3d g;
  Eigen::Matrix3d H;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d ei = Eigen::Vector3d::Unit(i);
    g[i] = (phi(X + hg * ei) - phi(X - hg * ei)) / (2 * hg);
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d ej = Eigen::Vector3d::Unit(j);
      H(i, j) = (phi(X + hh * ei + hh * ej) - phi(X + hh * ei - hh * ej) -
                 phi(X - hh * ei + hh * ej) + phi(X - hh * ei - hh * ej)) /
                (4 * hh * hh);
    }
  }
  INFO("X = " << X.transpose() << ", value " << s.value << "\ngradient " << s.gradient.transpose()
              << "\ndifferences " << g.transpose() << "\nHessian\n"
              << s.hessian << "\ndifferences\n"
              << H);
  CHECK((s.gradient - g).norm() <= 1e-8);
  CHECK((s.hessian - H).norm() <= 1e-5 * (1.0 + s.hessian.norm()));
  CHECK(std::abs(s.gradient.norm() - 1.0) <= 1e-14);         // exact SDF: |∇Φ| = 1
  CHECK((s.hessian - s.hessian.transpose()).norm() == 0.0);  // symmetric
  CHECK((s.hessian * s.gradient).norm() <= 1e-12 * (1.0 + s.hessian.norm()));
}

// Number of eigenvalues of a symmetric matrix above tol in magnitude.
int Rank(const Eigen::Matrix3d& H, double tol) {
  const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(H).eigenvalues();
  return static_cast<int>((ev.array().abs() > tol).count());
}

// Point on the box surface from two uniform numbers per face coordinate.
Eigen::Vector3d SurfacePoint(const Eigen::Vector3d& b, int face, double s, double t) {
  const int k = face % 3, u = (k + 1) % 3, v = (k + 2) % 3;
  Eigen::Vector3d p;
  p[k] = face < 3 ? b[k] : -b[k];
  p[u] = s * b[u];
  p[v] = t * b[v];
  return p;
}

}  // namespace

TEST_CASE("sdf: sphere values, exactness and derivatives", "[geometry][sdf]") {
  const SphereSdf sphere{0.2};
  CHECK(sphere.Evaluate({0.5, 0, 0}).value == Approx(0.3));
  CHECK(sphere.Evaluate({0, -0.1, 0}).value == Approx(-0.1));
  CHECK(sphere.Evaluate({0.12, 0.16, 0}).value == Approx(0.0).margin(1e-16));
  CHECK(sphere.Evaluate({0.3, 0.4, 1.2}).value == Approx(1.1));
  const SdfSample centre = sphere.Evaluate(Eigen::Vector3d::Zero());
  CHECK(centre.value == -0.2);
  CHECK(centre.gradient == Eigen::Vector3d::UnitZ());
  CHECK(centre.hessian == Eigen::Matrix3d::Zero());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d X(u(rng), u(rng), u(rng));
    if (X.norm() < 0.05) continue;  // the Hessian grows like 1/|X|
    CheckAgainstDifferences(sphere, X);
    const SdfSample s = sphere.Evaluate(X);
    CHECK(std::abs((X - s.value * s.gradient).norm() - 0.2) <= 1e-15);
    CHECK(Rank(s.hessian, 1e-12) == 2);
    CHECK(s.hessian.trace() == Approx(2.0 / X.norm()));  // mean curvature of the level set
  }
}

TEST_CASE("sdf: box values against closed forms", "[geometry][sdf]") {
  const BoxSdf box{Eigen::Vector3d(0.1, 0.2, 0.3)};
  CHECK(box.Evaluate({0, 0, 0}).value == Approx(-0.1));
  CHECK(box.Evaluate({0.0, 0.15, 0.05}).value == Approx(-0.05));  // nearest: +y face
  CHECK(box.Evaluate({0.0, 0.15, 0.05}).gradient == Eigen::Vector3d::UnitY());
  CHECK(box.Evaluate({-0.08, 0.0, 0.0}).gradient == -Eigen::Vector3d::UnitX());
  CHECK(box.Evaluate({0.0, 0.0, -0.29}).value == Approx(-0.01));
  CHECK(box.Evaluate({0.1, 0.05, -0.2}).value == 0.0);         // on a face
  CHECK(box.Evaluate({0.4, 0.0, 0.0}).value == Approx(0.3));   // face region
  CHECK(box.Evaluate({0.0, -0.5, 0.1}).value == Approx(0.3));  // face region
  CHECK(box.Evaluate({0.4, 0.6, 0.0}).value == Approx(0.5));   // edge: (0.3, 0.4)
  CHECK(box.Evaluate({-0.4, 0.6, -1.5}).value == Approx(std::sqrt(0.09 + 0.16 + 1.44)));  // corner
  const SdfSample edge = box.Evaluate({0.4, 0.6, 0.0});
  CHECK(edge.gradient.isApprox(Eigen::Vector3d(0.6, 0.8, 0.0), 1e-15));
  Eigen::Matrix3d He = Eigen::Matrix3d::Zero();  // (I − t tᵀ − n nᵀ)/Φ, t = e_z
  He.topLeftCorner<2, 2>() << 0.64, -0.48, -0.48, 0.36;
  CHECK((edge.hessian - He / 0.5).norm() <= 1e-14);
  const SdfSample corner = box.Evaluate({-0.4, 0.6, -1.5});
  const Eigen::Vector3d n = Eigen::Vector3d(-0.3, 0.4, -1.2) / 1.3;
  CHECK(corner.gradient.isApprox(n, 1e-15));
  CHECK((corner.hessian - (Eigen::Matrix3d::Identity() - n * n.transpose()) / 1.3).norm() <= 1e-14);
}

TEST_CASE("sdf: box is exact and its derivatives match differences in every region",
          "[geometry][sdf]") {
  const Eigen::Vector3d b(0.1, 0.2, 0.3);
  const BoxSdf box{b};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Keep the difference stencils (reach 1e-4) inside one smooth region, and outside points at
  // distance >= 0.05 so that the Hessian (~1/Φ) stays moderate.
  const double margin = 0.01;
  auto sign = [&] { return unit(rng) < 0.5 ? -1.0 : 1.0; };
  // Surface samples for the brute-force closest-distance check.
  std::vector<Eigen::Vector3d> surface;
  for (int f = 0; f < 6; ++f)
    for (int i = 0; i < 400; ++i)
      surface.push_back(SurfacePoint(b, f, 2 * unit(rng) - 1, 2 * unit(rng) - 1));
  auto checkExact = [&](const Eigen::Vector3d& X) {
    const SdfSample s = box.Evaluate(X);
    const Eigen::Vector3d p = X - s.value * s.gradient;  // closest surface point
    CHECK(std::abs((p.cwiseAbs() - b).maxCoeff()) <= 1e-15);
    CHECK(std::abs((X - p).norm() - std::abs(s.value)) <= 1e-15);
    double nearest = 1e300;
    for (const auto& q : surface) nearest = std::min(nearest, (X - q).norm());
    CHECK(nearest >= std::abs(s.value) - 1e-15);
  };

  SECTION("inside, away from the medial surfaces") {
    int tested = 0;
    while (tested < 150) {
      Eigen::Vector3d X;
      for (int k = 0; k < 3; ++k) X[k] = (2 * unit(rng) - 1) * b[k];
      Eigen::Vector3d d = X.cwiseAbs() - b;
      std::sort(d.data(), d.data() + 3);
      if (d[2] > -margin || d[2] - d[1] < 2 * margin) continue;
      ++tested;
      CheckAgainstDifferences(box, X);
      CHECK(box.Evaluate(X).value < 0.0);
      CHECK(box.Evaluate(X).hessian == Eigen::Matrix3d::Zero());
      checkExact(X);
    }
  }
  SECTION("outside: face, edge and corner regions") {
    for (int outsideAxes = 1; outsideAxes <= 3; ++outsideAxes) {
      INFO(outsideAxes << " axes outside");
      for (int i = 0; i < 100; ++i) {
        // Choose which axes lie outside the slab |X_k| <= b_k, the rest well inside it.
        int axes[3] = {0, 1, 2};
        std::shuffle(axes, axes + 3, rng);
        Eigen::Vector3d X;
        for (int a = 0; a < 3; ++a) {
          const int k = axes[a];
          X[k] = a < outsideAxes ? sign() * (b[k] + 0.05 + 0.5 * unit(rng))
                                 : sign() * (b[k] - margin) * unit(rng);
        }
        CheckAgainstDifferences(box, X);
        const SdfSample s = box.Evaluate(X);
        CHECK(s.value > 0.0);
        // Hessian rank: 0 on a face region, 1 on an edge region, 2 on a corner region.
        CHECK(Rank(s.hessian, 1e-9) == outsideAxes - 1);
        checkExact(X);
      }
    }
  }
}

TEST_CASE("sdf: half space", "[geometry][sdf]") {
  const PlaneSdf plane{Eigen::Vector3d(0, 0.6, 0.8), 0.1};
  CHECK(plane.Evaluate({0, 1, 1}).value == Approx(1.3));
  CHECK(plane.Evaluate({5, 0, 0.125}).value == Approx(0.0).margin(1e-16));
  CHECK(plane.Evaluate({0, -1, 0}).value == Approx(-0.7));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d X(u(rng), u(rng), u(rng));
    CheckAgainstDifferences(plane, X);
    const SdfSample s = plane.Evaluate(X);
    CHECK(s.hessian == Eigen::Matrix3d::Zero());
    CHECK(std::abs(plane.Evaluate(X - s.value * s.gradient).value) <= 1e-15);
  }
}

TEST_CASE("sdf: value-only and bounded evaluations agree with the full one", "[geometry][sdf]") {
  SphereSdf sphere;
  sphere.radius = 0.3;
  BoxSdf box;
  box.halfExtents = Eigen::Vector3d(0.2, 0.5, 0.1);
  PlaneSdf plane;
  plane.normal = Eigen::Vector3d(1.0, 2.0, -2.0).normalized();
  plane.offset = 0.1;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.8, 0.8);
  int below = 0, beyond = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Vector3d X(u(rng), u(rng), u(rng));
    const double bound = 0.5 * u(rng);
    auto check = [&](const SdfSample& full, double value, bool isBelow, const SdfSample& bounded) {
      CHECK(value == Approx(full.value).margin(1e-15));
      CHECK(bounded.value == Approx(full.value).margin(1e-15));
      CHECK(isBelow == (full.value < bound));
      if (isBelow) {
        ++below;
        CHECK((bounded.gradient - full.gradient).norm() <= 1e-15);
        CHECK((bounded.hessian - full.hessian).norm() <= 1e-12);
      } else {
        ++beyond;
      }
    };
    SdfSample s;
    bool b = sphere.EvaluateBelow(X, bound, &s);
    check(sphere.Evaluate(X), sphere.Value(X), b, s);
    SdfSample t;
    b = box.EvaluateBelow(X, bound, &t);
    check(box.Evaluate(X), box.Value(X), b, t);
    SdfSample w;
    b = plane.EvaluateBelow(X, bound, &w);
    check(plane.Evaluate(X), plane.Value(X), b, w);
  }
  CHECK(below > 200);  // both branches exercised (3 fields × 2000 points)
  CHECK(beyond > 200);
}

TEST_CASE("sdf: capsule values, exactness and derivatives beside and about its caps",
          "[geometry][sdf][capsule]") {
  // Radius 0.1 about the segment z in [-0.3, 0.3].
  const CapsuleSdf capsule{0.1, 0.3};
  CHECK(capsule.Evaluate({0.5, 0, 0.2}).value == Approx(0.4));    // beside: |(x, y)| − r
  CHECK(capsule.Evaluate({0, 0.05, -0.1}).value == Approx(-0.05));
  CHECK(capsule.Evaluate({0, 0, 0.7}).value == Approx(0.3));      // above: |X − h ẑ| − r
  CHECK(capsule.Evaluate({0.3, 0, -0.7}).value == Approx(0.4));   // |(0.3, 0, −0.4)| − r
  const SdfSample axis = capsule.Evaluate({0, 0, 0.1});
  CHECK(axis.value == -0.1);
  CHECK(axis.gradient == Eigen::Vector3d::UnitX());
  CHECK(axis.hessian == Eigen::Matrix3d::Zero());
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int beside = 0, caps = 0;
  for (int i = 0; i < 400; ++i) {
    const Eigen::Vector3d X(0.5 * u(rng), 0.5 * u(rng), u(rng));
    const double rho = std::hypot(X.x(), X.y());
    const double away = std::abs(X.z()) - 0.3;  // past the segment's end (> 0: a cap's region)
    // The Hessian grows like 1/distance to the segment and jumps across |z| = h: keep the
    // difference stencil off both.
    if (rho < 0.05 && away < 0.05) continue;
    if (std::abs(away) < 1e-3) continue;
    CheckAgainstDifferences(capsule, X);
    const SdfSample s = capsule.Evaluate(X);
    // Exact: the projection lands on the surface.
    CHECK(std::abs(capsule.Value(X - s.value * s.gradient)) <= 1e-15);
    // Level sets: a cylinder beside (one curvature), a sphere about the caps (two).
    CHECK(Rank(s.hessian, 1e-12) == (away < 0 ? 1 : 2));
    (away < 0 ? beside : caps) += 1;
    SdfSample b;
    CHECK(capsule.EvaluateBelow(X, s.value + 1e-9, &b));
    CHECK_FALSE(capsule.EvaluateBelow(X, s.value, &b));
    CHECK(b.value == s.value);
    CHECK(capsule.Value(X) == s.value);
  }
  CHECK(beside > 50);
  CHECK(caps > 50);
}
