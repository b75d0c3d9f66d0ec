// Joint limit and drive potentials (joint_energies.h).
#include "energies/joint_energies.h"

#include <cmath>

namespace superdex {

JointEnergy JointLimitEnergy(double x, double lower, double upper, double k) {
  JointEnergy e;
  const double over = x > upper ? x - upper : (x < lower ? x - lower : 0.0);
  if (over == 0.0) return e;
  e.value = 0.5 * k * over * over;
  e.d1 = k * over;
  e.d2 = k;
  return e;
}

JointEnergy DriveEnergy(double x, double xEq, double a, double forceLimit) {
  JointEnergy e;
  const double err = x - xEq;
  const double reach = forceLimit / a;  // |e| where the force reaches its limit (inf: never)
  if (std::abs(err) <= reach) {
    e.value = 0.5 * a * err * err;
    e.d1 = a * err;
    e.d2 = a;
  } else {
    e.value = forceLimit * (std::abs(err) - 0.5 * reach);
    e.d1 = std::copysign(forceLimit, err);
  }
  return e;
}

}  // namespace superdex
