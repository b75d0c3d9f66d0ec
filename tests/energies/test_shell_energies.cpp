// Shell energies (energies/shell_energies.h): the StVK membrane on triangles and the hinge
// bending term.
//
// Expectations:
//   - membrane: gradient and Hessian equal central differences of 1e-5 m (relative 1e-6 / 1e-5,
//     measured 9e-10 / 8e-8) at a stretched, sheared, rotated triangle and at a compressed one; zero energy and force under
//     a rigid motion (1e-12 relative); a small uniaxial stretch ε with ν = 0 stores
//     ½ E h A ε² (relative 2ε); the projected Hessian is PSD under compression where the exact
//     one is not;
//   - hinge angle: 0 when flat, ±φ when a wing is turned by φ about the hinge (1e-12), its
//     gradient and Hessian equal differences of the angle (1e-6 / 1e-5, measured 4e-11 / 5e-7);
//   - bending energy: gradient and Hessian equal differences (1e-6 / 1e-5, measured 9e-11 /
//     8e-7), projected PSD where the exact Hessian is indefinite;
//   - calibration: a flat strip of rectangles bent isometrically onto a cylinder of radius R
//     stores the plate's D/2 R⁻² per unit area within 3e-4 at 0.05 rad per facet (the ratio is
//     Δφ² / (4 sin²(Δφ/2)) = 1 + Δφ²/12 + …; measured 1.00021).
#include <catch2/catch.hpp>

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "derivative_check.h"
#include "energies/shell_energies.h"
#include "energies/shell_midedge.h"
#include "core/model/shell_body.h"
#include "geometry/triangle_mesh.h"

namespace superdex {
namespace {

using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat9 = Eigen::Matrix<double, 9, 9>;
using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

double MinEigen(const Eigen::MatrixXd& H) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(H).eigenvalues().minCoeff();
}

}  // namespace

TEST_CASE("shell membrane: derivatives, rigid invariance, small-strain limit", "[energies][shell]") {
  const Eigen::Vector3d X0(0.1, -0.2, 0.3), X1(0.6, -0.1, 0.35), X2(0.2, 0.4, 0.1);
  const ShellTriangle t = MakeShellTriangle(X0, X1, X2);
  REQUIRE(t.restArea == Approx(0.5 * (X1 - X0).cross(X2 - X0).norm()).epsilon(1e-14));
  const LameParameters lame = PlaneStressLame(2e5, 0.3);
  const double h = 1e-3;
  const bool compressed = GENERATE(false, true);
  // A deformation: rotation, then stretch/shear (or compression) and a small perturbation.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::Matrix3d A;
  if (compressed)
    A << 0.7, 0.1, 0.0, 0.05, 0.8, 0.1, 0.0, 0.0, 0.9;
  else
    A << 1.2, 0.1, 0.0, 0.05, 1.1, 0.1, 0.0, 0.2, 0.9;
  Vec9 x;
  x << R * A * X0, R * A * X1 + Eigen::Vector3d(0.01, 0, 0), R * A * X2;
  Vec9 g = Vec9::Zero();
  Mat9 H = Mat9::Zero();
  MembraneEnergy(x, t, lame, h, 2, false, &g, &H);
  const test::DerivativeCheck c = test::CheckDerivatives(
      [&](const Eigen::VectorXd& d) {
        return MembraneEnergy(x + Vec9(d), t, lame, h, 0, false, nullptr, nullptr);
      },
      g, H, 1e-5);
  INFO("gradient " << c.gradientError << ", Hessian " << c.hessianError);
  CHECK(c.gradientError < 1e-6);
  CHECK(c.hessianError < 1e-5);
  Vec9 gp = Vec9::Zero();
  Mat9 Hp = Mat9::Zero();
  MembraneEnergy(x, t, lame, h, 2, true, &gp, &Hp);
  CHECK(MinEigen(Hp) > -1e-9 * Hp.norm());
  if (compressed) CHECK(MinEigen(H) < -1e-6 * H.norm());  // the projection had work to do

  // Rigid motion: no energy, no force.
  Vec9 rigid;
  rigid << R * X0, R * X1, R * X2;
  rigid += Vec9::Constant(0.3);
  Vec9 gr = Vec9::Zero();
  Mat9 Hr = Mat9::Zero();
  CHECK(std::abs(MembraneEnergy(rigid, t, lame, h, 1, false, &gr, &Hr)) < 1e-20);
  CHECK(gr.norm() < 1e-12 * 2e5 * h);

  // Uniaxial stretch ε along the first edge with ν = 0: ½ E h A ε².
  const double eps = 1e-4, E = 3e5;
  const Eigen::Vector3d u = (X1 - X0).normalized();
  const Eigen::Matrix3d S = Eigen::Matrix3d::Identity() + eps * u * u.transpose();
  Vec9 stretched;
  stretched << S * X0, S * X1, S * X2;
  const double W = MembraneEnergy(stretched, t, PlaneStressLame(E, 0.0), h, 0, false, nullptr, nullptr);
  const double expected = 0.5 * E * h * t.restArea * eps * eps;
  INFO("stretch energy " << W << ", expected " << expected);
  CHECK(std::abs(W - expected) < 2.0 * eps * expected);
}

TEST_CASE("shell hinge: the dihedral angle and its derivatives", "[energies][shell]") {
  // Hinge along x from the origin; wing a at +y, wing b at −y, flat.
  const Eigen::Vector3d x0(0, 0, 0), x1(1, 0, 0), a(0.3, 1, 0), b(0.6, -0.8, 0);
  Vec12 x;
  x << x0, x1, a, b;
  Vec12 g;
  Mat12 H;
  CHECK(std::abs(HingeAngle(x, 0, &g, &H)) < 1e-15);
  for (double phi : {0.3, -0.9, 2.5}) {
    // Turn wing b about the hinge by phi: the angle between the normals is ±phi.
    const Eigen::Matrix3d R = Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitX()).toRotationMatrix();
    Vec12 y = x;
    y.segment<3>(9) = R * b;
    CHECK(std::abs(std::abs(HingeAngle(y, 0, &g, &H)) - std::abs(phi)) < 1e-12);
  }
  // A general hinge: derivatives against differences.
  Vec12 y;
  y << 0.1, -0.05, 0.02, 1.0, 0.1, -0.1, 0.4, 0.9, 0.3, 0.5, -0.7, 0.45;
  const double theta = HingeAngle(y, 2, &g, &H);
  CHECK(std::abs(theta) > 0.3);
  const test::DerivativeCheck c = test::CheckDerivatives(
      [&](const Eigen::VectorXd& d) { return HingeAngle(y + Vec12(d), 0, nullptr, nullptr); },
      g, H, 1e-5);
  INFO("gradient " << c.gradientError << ", Hessian " << c.hessianError);
  CHECK(c.gradientError < 1e-6);
  CHECK(c.hessianError < 1e-5);
  // Invariant under translation: the gradient sums to zero over the nodes.
  CHECK((g.segment<3>(0) + g.segment<3>(3) + g.segment<3>(6) + g.segment<3>(9)).norm() < 1e-12);
}

TEST_CASE("shell bending: derivatives and PSD projection", "[energies][shell]") {
  Vec12 y;
  y << 0.1, -0.05, 0.02, 1.0, 0.1, -0.1, 0.4, 0.9, 0.3, 0.5, -0.7, 0.45;
  const double k = HingeStiffness(1.0, 0.8, 2.5e-3), rest = 0.2;
  Vec12 g = Vec12::Zero();
  Mat12 H = Mat12::Zero();
  HingeBendingEnergy(y, k, rest, 2, false, &g, &H);
  const test::DerivativeCheck c = test::CheckDerivatives(
      [&](const Eigen::VectorXd& d) {
        return HingeBendingEnergy(y + Vec12(d), k, rest, 0, false, nullptr, nullptr);
      },
      g, H, 1e-5);
  INFO("gradient " << c.gradientError << ", Hessian " << c.hessianError);
  CHECK(c.gradientError < 1e-6);
  CHECK(c.hessianError < 1e-5);
  Vec12 gp = Vec12::Zero();
  Mat12 Hp = Mat12::Zero();
  HingeBendingEnergy(y, k, rest, 2, true, &gp, &Hp);
  CHECK(MinEigen(H) < 0.0);
  CHECK(MinEigen(Hp) > -1e-12 * Hp.norm());
}

TEST_CASE("shell bending: a strip bent onto a cylinder stores the plate's energy",
          "[energies][shell]") {
  // Facets of angle dphi around a cylinder of radius R and length L: each axial hinge turns by
  // dphi; the rectangles' diagonals stay flat (their corners are coplanar).
  const double R = 0.2, L = 0.05, dphi = 0.05, D = 3.0;
  const double chord = 2.0 * R * std::sin(0.5 * dphi);
  auto P = [&](int i, double z) {
    return Eigen::Vector3d(R * std::cos(i * dphi), R * std::sin(i * dphi), z);
  };
  // The hinge of facet edges i (from P(i, 0) to P(i, L)), its wings P(i−1, 0) and P(i+1, L).
  double W = 0.0;
  const int n = 10;
  for (int i = 1; i < n; ++i) {
    Vec12 x;
    x << P(i, 0), P(i, L), P(i - 1, 0), P(i + 1, L);
    const double k = HingeStiffness(L, chord * L, D);  // two half rectangles, flat at rest
    W += HingeBendingEnergy(x, k, 0.0, 0, false, nullptr, nullptr);
  }
  const double area = (n - 1) * chord * L;  // the hinges' share: one rectangle each
  const double plate = 0.5 * D / (R * R) * area;
  INFO("hinges " << W << " J, plate " << plate << " J, ratio " << W / plate);
  CHECK(std::abs(W / plate - 1.0) < 3e-4);
}

}  // namespace superdex

namespace superdex {
namespace {

// A grid of (n + 1)² points mapped by f from the square [−a, a]² (cells split along (−,−)→(+,+)),
// and its faces.
struct Grid {
  std::vector<Eigen::Vector3d> rest, now;
  std::vector<Eigen::Vector3i> faces, opposite;
};

template <typename Map>
Grid MakeGrid(int n, double a, Map f) {
  Grid g;
  const TriangleMesh m = MakeRectangleMesh(Eigen::Vector2d(-a, -a), Eigen::Vector2d(a, a),
                                           Eigen::Vector2i(n, n));
  g.rest = m.vertices;
  for (const Eigen::Vector3d& X : g.rest) g.now.push_back(f(X.x(), X.y()));
  g.faces = m.faces;
  std::pair<int, int> bad;
  REQUIRE(FaceOppositeVertices(g.faces, &g.opposite, &bad));
  return g;
}

// Σ W / Σ Ā over the faces with three neighbours [J/m²].
double InteriorEnergyDensity(const Grid& g, const LameParameters& lame, double h) {
  double W = 0.0, A = 0.0;
  for (size_t f = 0; f < g.faces.size(); ++f) {
    if ((g.opposite[f].array() < 0).any()) continue;
    const bool has[3] = {true, true, true};
    const MidedgeTriangle t = MakeMidedgeTriangle(MidedgeNodes(g.rest, g.faces[f], g.opposite[f]), has);
    W += MidedgeBendingEnergy(MidedgeNodes(g.now, g.faces[f], g.opposite[f]), t, lame, h, 0, false,
                              nullptr, nullptr);
    A += t.restArea;
  }
  return W / A;
}

}  // namespace

TEST_CASE("shell mid-edge bending: derivatives against differences", "[energies][shell]") {
  const LameParameters lame = PlaneStressLame(2e5, 0.3);
  const double h = 2e-3;
  // A curved patch (rest) and a deformed one.
  const Grid g = MakeGrid(3, 0.1, [](double x, double y) {
    return Eigen::Vector3d(x + 0.01 * y * y, y, 0.8 * x * x - 0.5 * x * y + 0.3 * y * y * y);
  });
  const Grid r = MakeGrid(3, 0.1, [](double x, double y) {
    return Eigen::Vector3d(x, y, 0.2 * x * y);
  });
  for (size_t f : {size_t(0), size_t(8)}) {  // a corner face (boundary edges) and an inner one
    bool has[3];
    for (int k = 0; k < 3; ++k) has[k] = g.opposite[f][k] >= 0;
    const MidedgeTriangle t = MakeMidedgeTriangle(MidedgeNodes(r.now, g.faces[f], g.opposite[f]), has);
    const MidedgeStencil x = MidedgeNodes(g.now, g.faces[f], g.opposite[f]);
    Eigen::Matrix<double, 18, 1> grad = Eigen::Matrix<double, 18, 1>::Zero();
    Eigen::Matrix<double, 18, 18> H = Eigen::Matrix<double, 18, 18>::Zero();
    MidedgeBendingEnergy(x, t, lame, h, 2, false, &grad, &H);
    const test::DerivativeCheck c = test::CheckDerivatives(
        [&](const Eigen::VectorXd& d) {
          return MidedgeBendingEnergy(x + MidedgeStencil(d), t, lame, h, 0, false, nullptr, nullptr);
        },
        grad, H, 1e-5);
    INFO("face " << f << ": gradient " << c.gradientError << ", Hessian " << c.hessianError);
    CHECK(c.gradientError < 1e-6);
    CHECK(c.hessianError < 1e-5);
    Eigen::Matrix<double, 18, 1> gp = Eigen::Matrix<double, 18, 1>::Zero();
    Eigen::Matrix<double, 18, 18> Hp = Eigen::Matrix<double, 18, 18>::Zero();
    MidedgeBendingEnergy(x, t, lame, h, 2, true, &gp, &Hp);
    CHECK(MinEigen(Hp) > -1e-10 * Hp.norm());
  }
}

TEST_CASE("shell mid-edge bending: a cylinder and a sphere store Kirchhoff's plate energy",
          "[energies][shell]") {
  const double E = 1e6, nu = 0.3, h = 1e-3, R = 1.0;
  const LameParameters lame = PlaneStressLame(E, nu);
  const double D = E * h * h * h / (12.0 * (1.0 - nu * nu));
  // A flat 8 × 8 grid of 2 cm wrapped isometrically onto a cylinder (axis along y, κ = 1/R):
  // D/2 κ² per unit area.
  const Grid cylinder = MakeGrid(8, 0.02, [&](double x, double y) {
    return Eigen::Vector3d(R * std::sin(x / R), y, R - R * std::cos(x / R));
  });
  const double c = InteriorEnergyDensity(cylinder, lame, h) / (0.5 * D / (R * R));
  // Pressed onto a sphere of radius R (κ₁ = κ₂ = 1/R): D (1 + ν) κ² per unit area.
  const Grid sphere = MakeGrid(8, 0.02, [&](double x, double y) {
    return Eigen::Vector3d(x, y, R - std::sqrt(R * R - x * x - y * y));
  });
  const double s = InteriorEnergyDensity(sphere, lame, h) / (D * (1.0 + nu) / (R * R));
  INFO("cylinder " << c << ", sphere " << s << " of Kirchhoff's");
  CHECK(std::abs(c - 1.0) < 1e-3);
  CHECK(std::abs(s - 1.0) < 1e-3);
}

}  // namespace superdex
