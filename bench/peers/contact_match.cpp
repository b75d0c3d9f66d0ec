// Quadrature of superdex's penalty pressure over a flat face and over a sphere, and the two
// matching rules used by the adapters: stiffness at rest and peak penetration of a drop.
#include "contact_match.h"

#include <cmath>

namespace superdex::peers {

double SuperdexPressure(double phi, double k, double eps, double delta) {
  const double s = delta - phi;
  if (s <= 0) return 0.0;
  if (s >= 2 * eps) return k * (s - eps);  // h = −φ − (ε − δ) = s − ε, h' = 1
  const double e3 = eps * eps * eps;
  const double h = s * s * s * (4 * eps - s) / (16 * e3);
  const double dh = s * s * (3 * eps - s) / (4 * e3);
  return k * h * dh;
}

double FlatForce(double phi, double area, const PeerBody& b) {
  return area * SuperdexPressure(phi, b.k, b.eps, b.delta);
}

double SphereForce(double phi, const PeerBody& b) {
  // Each surface element at polar angle θ from the pole sits at φ + r(1 − cos θ). The penalty
  // energy is per unit reference area of the colliding surface and φ is the plane's distance, so
  // every element pushes along the plane normal with k h h'. Only the cap within δ contributes.
  const double r = b.radius;
  const double capMax = std::min(M_PI, std::acos(std::max(-1.0, 1.0 - (b.delta - phi) / r)));
  const int n = 4000;
  double f = 0.0;
  for (int i = 0; i < n; ++i) {
    const double th = (i + 0.5) * capMax / n;
    f += SuperdexPressure(phi + r * (1 - std::cos(th)), b.k, b.eps, b.delta) * 2 * M_PI * r * r *
         std::sin(th);
  }
  return f * capMax / n;
}

namespace {

double Force(double phi, const PeerBody& b) {
  return b.shape == ShapeKind::Box ? FlatForce(phi, 4 * b.halfExtents.x() * b.halfExtents.y(), b)
                                   : SphereForce(phi, b);
}

}  // namespace

double RestStiffness(const PeerBody& b, double g) {
  const double load = b.mass * g;
  double lo = -0.1, hi = b.delta;  // Force decreases in φ: bisect Force(φ) = load
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (Force(mid, b) > load ? lo : hi) = mid;
  }
  const double phi = 0.5 * (lo + hi), h = 1e-7;
  return (Force(phi - h, b) - Force(phi + h, b)) / (2 * h);
}

double DropPeakPenetration(const PeerBody& b, double height, double g) {
  // March φ down from δ, accumulating the work of the contact force (trapezoid rule).
  const double step = 1e-6;
  double phi = b.delta, work = 0.0, f = 0.0;
  while (phi > -0.1) {
    const double f2 = SphereForce(phi - step, b);
    work += 0.5 * (f + f2) * step;
    f = f2;
    phi -= step;
    if (work >= b.mass * g * (height - phi)) return -phi;
  }
  return 0.1;
}

}  // namespace superdex::peers
