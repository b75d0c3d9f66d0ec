#include "core/contact/sphere_cap.h"

#include <algorithm>
#include <cmath>

#include "geometry/gauss_legendre.h"

namespace superdex {

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
  cap.hi = std::min({tAt(std::min(reach, rhoCut)), 1.0});
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
