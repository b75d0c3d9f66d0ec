// Actor descriptions and dissipation-mode settings shared by the physics tests.
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "core/model/eval_params.h"
#include "core/model/rigid_body.h"

namespace superdex::test {

/// The three dissipation modes by index (README "Dissipation modes"): 0 explicit normals,
/// 1 reconstructed stage-start load (the default), 2 current load.
inline ExperimentalEvalParams EvalParamsForMode(int m) {
  ExperimentalEvalParams e;
  e.explicitNormals = m == 0;
  e.implicitNormalForceForDissipation = m == 2;
  return e;
}
inline const char* const kModeNames[3] = {
    "explicit normals", "reconstructed load (default)", "current load"};

/// A static ground plane z <= 0 with penalty coefficient k [Pa/m] and Coulomb coefficient mu.
inline RigidActorDesc StaticGround(double k = 1e9, double mu = 0.5) {
  RigidActorDesc d;
  d.name = "ground";
  d.dynamic = false;
  d.shape.kind = RigidShapeKind::Plane;
  d.contact.penaltyCoefficient = k;
  d.contact.coulombFrictionCoefficient = mu;
  return d;
}

/// A static plane through the origin with outward normal n, penalty coefficient k [Pa/m], Coulomb
/// coefficient mu and normal damping cn [s/m].
inline RigidActorDesc Ground(const Eigen::Vector3d& n, double k, double mu, double cn) {
  RigidActorDesc d = StaticGround(k, mu);
  d.shape.planeNormal = n;
  d.contact.normalViscousDampingCoefficient = cn;
  return d;
}

/// Sphere k of a heap of 1 kg spheres (r = 0.05 m, surface resolution 2) on a 5 × 5 lattice
/// in layers of 25, each pressed 0.5 mm into its neighbours and the lowest layer into a ground at
/// z = 0, sliding a little (k % 3 · 1 cm/s along x, −(k % 2) · 2 cm/s along y).
inline RigidActorDesc HeapSphere(int k) {
  RigidActorDesc d;
  d.name = "s" + std::to_string(k);
  d.shape.radius = 0.05;
  d.shape.surfaceResolution = 2;
  d.mass = 1.0;
  const double pitch = 0.1 - 5e-4;
  d.position =
      Eigen::Vector3d((k % 5) * pitch, ((k / 5) % 5) * pitch, 0.05 - 5e-4 + (k / 25) * pitch);
  d.linearVelocity = Eigen::Vector3d(0.01 * (k % 3), -0.02 * (k % 2), 0.0);
  return d;
}

/// A static sphere "fixed" of radius r [m] at the origin (default contact parameters).
inline RigidActorDesc FixedSphere(double r) {
  RigidActorDesc d;
  d.name = "fixed";
  d.dynamic = false;
  d.shape.kind = RigidShapeKind::Sphere;
  d.shape.radius = r;
  return d;
}

/// A dynamic 1 kg ball "ball" of radius r [m] (surface resolution 3) with Coulomb coefficient mu.
inline RigidActorDesc Ball(double r, double mu) {
  RigidActorDesc ball;
  ball.name = "ball";
  ball.shape.kind = RigidShapeKind::Sphere;
  ball.shape.radius = r;
  ball.shape.surfaceResolution = 3;
  ball.mass = 1.0;
  ball.contact.coulombFrictionCoefficient = mu;
  return ball;
}

/// A dynamic cube "cube" of edge 0.2 m and 1 kg, 2 × 2 quadrature cells per face.
inline RigidActorDesc Cube(double k, double mu, double cn) {
  RigidActorDesc d;
  d.name = "cube";
  d.shape.kind = RigidShapeKind::Box;
  d.shape.halfExtents = Eigen::Vector3d::Constant(0.1);
  d.shape.surfaceResolution = 2;
  d.mass = 1.0;
  d.contact.penaltyCoefficient = k;
  d.contact.coulombFrictionCoefficient = mu;
  d.contact.normalViscousDampingCoefficient = cn;
  return d;
}

/// The cube of Cube(k, mu, cn) released face down, 10 µm above contact, on the plane through the
/// origin tilted by theta [rad] about y (outward normal (sin θ, 0, cos θ); add Ground(n, ...)).
inline RigidActorDesc CubeOnIncline(double theta, double k, double mu, double cn) {
  RigidActorDesc d = Cube(k, mu, cn);
  d.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()));
  d.position = Eigen::Vector3d(std::sin(theta), 0, std::cos(theta)) * (0.1 + 1e-5);
  return d;
}

}  // namespace superdex::test
