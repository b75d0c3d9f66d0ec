#include "energies/penalty_ramp.h"

namespace superdex {

RampValue PenaltyRamp(double phi, double eps, double delta) {
  RampValue r;
  const double s = delta - phi;
  if (s <= 0.0) return r;
  if (s >= 2.0 * eps) {
    r.h = s - eps;
    r.dh = 1.0;
    return r;
  }
  const double e3 = eps * eps * eps;
  r.h = s * s * s * (4.0 * eps - s) / (16.0 * e3);
  r.dh = s * s * (3.0 * eps - s) / (4.0 * e3);
  r.d2h = 3.0 * s * (2.0 * eps - s) / (4.0 * e3);
  return r;
}

double PenaltyRampSpecForm(double phi, double eps, double delta) {
  const double z = -phi - (eps - delta);
  if (z <= -eps) return 0.0;
  if (z >= eps) return z;
  return 3.0 * eps / 16.0 +
         (0.5 + 3.0 * z / (8.0 * eps) - z * z * z / (16.0 * eps * eps * eps)) * z;
}

}  // namespace superdex
