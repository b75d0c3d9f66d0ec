#include "core/contact/sphere_cap.h"

#include <algorithm>
#include <cmath>

#include "geometry/gauss_legendre.h"

namespace superdex {

namespace {

// A box's face k (sign ±) as a plane, where the sphere's part below δ on it lies in the face's
// region: with D the sphere's depth past the face, every point of the cap t <= t_hi has
// |Y_j ± lateral| − h_j <= −D <= min(q_k, 0) for the other axes j (q = |X| − h), so the box's
// distance is q_k there.
AxialField BoxFace(const BoxSdf& box, const Eigen::Vector3d& Y, double r, double m,
                   const PenaltyParams& p) {
  const Eigen::Vector3d q = Y.cwiseAbs() - box.halfExtents;
  Eigen::Index k;
  q.maxCoeff(&k);
  AxialField a;
  a.x = q[k];
  const double tHi = PlaneCap(a.x, r, m, p).hi;  // the face plane's cap
  if (tHi > -1.0) {  // else the sphere is beyond δ of the face plane, hence of the box
    const double lateral = tHi < 0.0 ? r * std::sqrt(1.0 - tHi * tHi) : r;
    const double depth = std::max(r - a.x, 0.0);
    for (int j = 0; j < 3; ++j)
      if (j != k && !(std::abs(Y[j]) + lateral + depth <= box.halfExtents[j])) return {};
  }
  a.kind = AxialField::Kind::Plane;
  a.axis = Eigen::Vector3d::Unit(k) * (Y[k] < 0.0 ? -1.0 : 1.0);
  return a;
}

}  // namespace

AxialField AxialFieldAt(const RigidCollider& f, const Eigen::Vector3d& Y, double r, double m,
                        const PenaltyParams& p) {
  AxialField a;
  switch (f.type) {
    case ColliderType::Plane:
      a.kind = AxialField::Kind::Plane;
      a.axis = f.plane.normal;
      a.x = f.plane.normal.dot(Y) - f.plane.offset;
      return a;
    case ColliderType::Box:
      return BoxFace(f.box, Y, r, m, p);
    case ColliderType::Sphere:
      a.x = Y.norm();
      if (!(a.x > r * (1.0 + 1e-9))) return a;  // deeper, the alignment is not monotone in t
      a.kind = AxialField::Kind::Sphere;
      a.axis = Y / a.x;
      a.radius = f.sphere.radius;
      return a;
    default:
      return a;
  }
}

SphereCap PlaneCap(double h, double r, double m, const PenaltyParams& p) {
  SphereCap cap;
  cap.hi = std::min(std::clamp(m, -1.0, 1.0), (p.delta - h) / r);
  cap.split = (p.delta - h - 2.0 * p.eps) / r;
  return cap;
}

SphereCap SphereFieldCap(double d, double rA, double rB, double m, const PenaltyParams& p) {
  const double mm = std::clamp(m, -1.0, 1.0);
  auto tAt = [&](double rho) { return (rho * rho - d * d - rA * rA) / (2.0 * d * rA); };
  const double reach = rB + p.delta;
  const double rhoCut = std::sqrt(std::max(d * d - (1.0 - mm * mm) * rA * rA, 0.0)) + mm * rA;
  SphereCap cap;
  cap.hi = std::min(tAt(std::min(reach, rhoCut)), 1.0);
  cap.split = reach - 2.0 * p.eps > 0.0 ? tAt(reach - 2.0 * p.eps) : -1.0;
  return cap;
}

namespace {

// Appends panel [a, b]'s n Gauss points times the azimuths.
int AddPanel(double a, double b, int n, double r, const Eigen::Vector3d& e,
             const Eigen::Vector3d& e1, const Eigen::Vector3d& e2, const Eigen::Matrix3d& toBody,
             SurfaceSample* out) {
  const GaussLegendreRule& rule = GaussLegendre(n);
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  const double dpsi = 2.0 * M_PI / kCapAzimuths;
  int count = 0;
  for (int i = 0; i < n; ++i) {
    const double t = mid + half * rule.nodes[i];
    const double sinT = std::sqrt(std::max(1.0 - t * t, 0.0));
    const double w = r * r * half * rule.weights[i] * dpsi;
    for (int j = 0; j < kCapAzimuths; ++j) {
      const double psi = dpsi * (j + 0.5);
      const Eigen::Vector3d u = t * e + sinT * (std::cos(psi) * e1 + std::sin(psi) * e2);
      SurfaceSample& s = out[count++];
      s.normal = toBody * u;
      s.X = r * s.normal;
      s.weight = w;
    }
  }
  return count;
}

}  // namespace

int SphereCapSamples(const SphereCap& cap, double r, const Eigen::Vector3d& e,
                     const Eigen::Matrix3d& toBody, SurfaceSample* out) {
  if (cap.Empty()) return 0;
  // e1, e2 complete e to an orthonormal frame, from the axis e is least aligned with.
  Eigen::Index k;
  e.cwiseAbs().minCoeff(&k);
  const Eigen::Vector3d e1 = e.cross(Eigen::Vector3d::Unit(k)).normalized();
  const Eigen::Vector3d e2 = e.cross(e1);
  if (!(cap.split > cap.lo && cap.split < cap.hi)) {  // one panel: all ramp, or all beyond it
    const int n = cap.split <= cap.lo ? kCapRampPoints : kCapLinearPoints;
    return AddPanel(cap.lo, cap.hi, n, r, e, e1, e2, toBody, out);
  }
  const int deep = AddPanel(cap.lo, cap.split, kCapLinearPoints, r, e, e1, e2, toBody, out);
  return deep + AddPanel(cap.split, cap.hi, kCapRampPoints, r, e, e1, e2, toBody, out + deep);
}

}  // namespace superdex
