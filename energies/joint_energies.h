// Energy terms of one joint coordinate x (an angle [rad] or an offset [m]) of an articulated
// actor: the position limits' penalty and a PD drive's implicit potential. Generalized force
// units: N·m for an angle, N for an offset; energies in J.
#pragma once

namespace superdex {

/// A scalar energy and its first two derivatives in x.
struct JointEnergy {
  double value = 0.0;  ///< [J]
  double d1 = 0.0;     ///< ∂/∂x [N·m/rad or N]
  double d2 = 0.0;     ///< ∂²/∂x² [N·m/rad² or N/m], >= 0
};

/// One-sided quadratic penalty of the limits lower <= x <= upper with stiffness k > 0:
///   U = ½ k (x − upper)²  for x > upper,   ½ k (lower − x)²  for x < lower,   0 between.
/// C¹ and convex; a load F held against a limit leaves it by F / k (the compliance 1/k).
/// Infinite bounds: no limit on that side.
JointEnergy JointLimitEnergy(double x, double lower, double upper, double k);

/// A PD drive's stage potential, the stiffness term ½ k_p (x − x*)² plus the damping term's
/// incremental potential k_d/(2Δt) (x − x⁰ − Δt v*)² (the dissipation ½ k_d (ẋ − v*)² at the
/// stage velocity ẋ = (x − x⁰)/Δt), which together are ½ a (x − x_eq)² + const with
///   a = k_p + k_d/Δt,   x_eq = (k_p x* + (k_d/Δt)(x⁰ + Δt v*)) / a,
/// and the drive force F = −a (x − x_eq) = −k_p (x − x*) − k_d (ẋ − v*). A force limit F_max
/// caps |F|: the potential continues linearly where |a (x − x_eq)| > F_max (Huber),
///   U = ½ a e²  (|a e| <= F_max),   F_max |e| − F_max²/(2a)  (beyond),   e = x − x_eq,
/// convex and C¹. `a` > 0; F_max > 0 (infinite: no limit).
JointEnergy DriveEnergy(double x, double xEq, double a, double forceLimit);

}  // namespace superdex
