#include "energies/contact_dissipation.h"

#include <limits>

namespace superdex {

FrictionRamp EvaluateFrictionRamp(double V, double vf) {
  FrictionRamp r;
  if (V >= vf) {
    r.rho = V - vf / 3.0;
    r.drho = 1.0;
    r.d2rho = 0.0;
    r.slope = 1.0 / V;
    r.curvature = -1.0 / V;
  } else {
    const double u = V / vf;
    r.rho = V * u - V * u * u / 3.0;
    r.drho = 2.0 * u - u * u;
    r.d2rho = (2.0 - 2.0 * u) / vf;
    r.slope = (2.0 - u) / vf;
    r.curvature = -u / vf;
  }
  return r;
}

DissipationDensity EvaluateDissipation(double lambdaHat, const Eigen::Vector3d& N,
                                       const Eigen::Vector3d& V, const DissipationCoefficients& c,
                                       DissipationHessian hessian,
                                       const SlipReference* slip) {
  DissipationDensity d;
  const double Vn = V.dot(N);
  const Eigen::Vector3d Vt = V - Vn * N;
  const double speed = Vt.norm();
  const FrictionRamp f = EvaluateFrictionRamp(speed, c.vf);
  d.R = lambdaHat * (c.mu * f.rho + 0.5 * c.ct * speed * speed + 0.5 * c.cn * Vn * Vn);
  double slope = f.slope;
  if (slip) {
    // The reference's branch, V_t → t*·V_t: 1/V_t sliding (smooth away from V_t = 0, which a
    // sliding reference is far from), 2/V_f − t*·V_t/V_f² in the stick band.
    if (slip->sliding)
      slope = speed > 0.0 ? 1.0 / speed : 0.0;
    else
      slope = (2.0 - slip->direction.dot(Vt) / c.vf) / c.vf;
  }
  d.coulomb = -lambdaHat * c.mu * slope * Vt;
  d.viscousTangential = -lambdaHat * c.ct * Vt;
  d.viscousNormal = -lambdaHat * c.cn * Vn * N;
  d.gradient = -(d.coulomb + d.viscousTangential + d.viscousNormal);
  if (hessian != DissipationHessian::None) {
    // ∂²/∂V² of μρ(‖PV‖) = μ (ρ'/V_t P + (ρ'' − ρ'/V_t) t tᵀ), t = V_t/V_t; P = 1 − N Nᵀ.
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - N * N.transpose();
    d.hessian = lambdaHat * ((c.mu * f.slope + c.ct) * P + c.cn * N * N.transpose());
    if (speed > 0.0 && hessian == DissipationHessian::Exact) {
      const Eigen::Vector3d t = Vt / speed;
      d.hessian += lambdaHat * c.mu * f.curvature * t * t.transpose();
    }
  }
  return d;
}

SlipReference SlipAt(const Eigen::Vector3d& N, const Eigen::Vector3d& V, double vf) {
  const Eigen::Vector3d Vt = V - V.dot(N) * N;
  const double speed = Vt.norm();
  SlipReference s;
  if (speed > 0.0) s.direction = Vt / speed;
  s.sliding = speed >= vf;
  return s;
}

double HuntCrossleyDampingFromRestitution(double e, double v) {
  if (!(e > 0.0 && e <= 1.0 && v > 0.0 && std::isfinite(v)))
    return std::numeric_limits<double>::quiet_NaN();
  return (1.0 - e) * (1.0 + 4.5 * e) / (e * v * (1.0 + 8.0 * e / 3.0));
}

double HuntCrossleyRestitutionFromDamping(double cn, double v) {
  if (!(cn >= 0.0 && std::isfinite(cn) && v > 0.0 && std::isfinite(v)))
    return std::numeric_limits<double>::quiet_NaN();
  const double a = cn * v;
  const double A = 8.0 * a / 3.0 + 4.5;
  const double B = a - 3.5;
  return 2.0 / (B + std::sqrt(B * B + 4.0 * A));
}

}  // namespace superdex
