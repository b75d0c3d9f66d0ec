// Contact dissipation potential (spec: "Friction and Damping", "Traction Model"), per unit
// reference area of the colliding actor, in collider-reference coordinates:
//
//   R(V_rel) = λ̂_n ( μ ρ(V_t) + (c_t/2) V_t² + (c_n/2) V_n² )                    [W/m² = Pa·m/s]
//   V_n = V_rel·N,  V_t = (1 − N Nᵀ) V_rel,  V_t = ‖V_t‖,
//   ρ(V) = V²/V_f − V³/(3 V_f²)  (V < V_f),   V − V_f/3  (V >= V_f)                [m/s]
//
// with λ̂_n = a λ_n [Pa] the effective normal load, μ [-], c_t, c_n [s/m], V_f [m/s] and N the unit
// split direction. The dissipative traction is T_diss = −∂R/∂V_rel [Pa]:
//   T_v,n = −c_n λ̂_n V_n N,   T_v,t = −c_t λ̂_n V_t,   T_C = −μ λ̂_n ρ'(V_t) V_t/V_t (0 at V_t = 0).
// λ̂_n and N are parameters here: which time level they come from is the caller's choice
// (ExperimentalEvalParams). R is C² in V_rel (ρ is C², and ρ(‖V_t‖) keeps a continuous Hessian
// at V_t = 0 because ρ'(V)/V is bounded), so the traction −∂R/∂V_rel is C¹: its Jacobian has kinks
// at V_t = 0 and V_t = V_f, which differences across must avoid (SlipReference below).
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace superdex {

/// Combined dissipation coefficients of one contact pair.
struct DissipationCoefficients {
  double mu = 0.0;  ///< Coulomb friction coefficient μ [-]
  double ct = 0.0;  ///< viscous friction coefficient c_t [s/m]
  double cn = 0.0;  ///< normal viscous damping coefficient c_n [s/m]
  double vf = 0.01; ///< friction falloff velocity V_f [m/s]
  bool Any() const { return mu > 0.0 || ct > 0.0 || cn > 0.0; }
};

/// The friction ramp ρ at speed V >= 0 and the quantities its derivatives need:
///   rho = ρ(V) [m/s], drho = ρ'(V) [-] (in [0, 1]), d2rho = ρ''(V) [s/m],
///   slope = ρ'(V)/V [s/m] (= 2/V_f at V = 0), curvature = ρ''(V) − ρ'(V)/V [s/m].
struct FrictionRamp {
  double rho = 0.0;
  double drho = 0.0;
  double d2rho = 0.0;
  double slope = 0.0;
  double curvature = 0.0;
};
FrictionRamp EvaluateFrictionRamp(double V, double vf);

/// Which second derivative of R EvaluateDissipation returns.
enum class DissipationHessian {
  None,       ///< value and gradient only
  Exact,      ///< ∂²R/∂V_rel²
  /// ∂²R/∂V_rel² with the Coulomb term's curvature along the slip direction, μ λ̂_n ρ''(V_t),
  /// raised to the in-plane value μ λ̂_n ρ'(V_t)/V_t: H_C = μ λ̂_n (ρ'(V_t)/V_t) P. Since
  /// ρ'(V)/V >= ρ''(V) for every V (ρ' is concave on [0, V_f) and constant beyond), H_C − exact
  /// is positive semi-definite: the quadratic model majorizes μ ρ(‖V_t‖) (the iteratively
  /// reweighted least-squares model of a regularized |V_t|). Projected Newton uses it far from
  /// the solution, where the exact model, flat along the slip (ρ'' = 0 for V_t >= V_f), sends a
  /// sliding sample across the stick region V_t < V_f in one step.
  Isotropic,
};

/// A recorded slip of one sample (sensitivities, core/contact/slip_tape.h): the direction t* = V_t/V_t of
/// its tangential velocity at a reference point (0 where V_t = 0) and whether V_t >= V_f there.
///
/// ∂R/∂V_rel is only C¹ in V_rel: the Coulomb slope ρ'(V_t)/V_t = 2/V_f − V_t/V_f² (V_t < V_f)
/// has a kink at V_t = 0 (and ρ'' one at V_f), so central differences of the dissipative force
/// across V_t ≈ 0 carry an O(η/V_f) error that no extrapolation removes. With a reference, the
/// slope is evaluated on the reference's branch with V_t replaced by its linearization about
/// the reference, t*·V_t (= V_t there): the force keeps its value and first derivatives in every
/// argument at the reference and is smooth (a quadratic in V_t on the stick branch) about it.
struct SlipReference {
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< t* [-]
  bool sliding = false;                                 ///< V_t >= V_f at the reference
};

/// R, ∂R/∂V_rel = −T_diss and ∂²R/∂V_rel² (symmetric positive semi-definite) at fixed λ̂_n, N.
struct DissipationDensity {
  double R = 0.0;                                  ///< [Pa·m/s]
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();///< ∂R/∂V [Pa]
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero(); ///< ∂²R/∂V² [Pa·s/m]
  Eigen::Vector3d coulomb = Eigen::Vector3d::Zero(); ///< T_C [Pa]
  Eigen::Vector3d viscousTangential = Eigen::Vector3d::Zero();///< T_v,t [Pa]
  Eigen::Vector3d viscousNormal = Eigen::Vector3d::Zero();    ///< T_v,n [Pa]
};
/// With `slip` (a recorded reference, SlipReference) the Coulomb traction, and with it the
/// gradient, use the linearized slope about the reference; R and the Hessian stay exact (only
/// the force is differenced).
DissipationDensity EvaluateDissipation(double lambdaHat, const Eigen::Vector3d& N,
                                       const Eigen::Vector3d& V, const DissipationCoefficients& c,
                                       DissipationHessian hessian,
                                       const SlipReference* slip = nullptr);
/// The slip reference of a sample at (N, V): its tangential direction and branch.
SlipReference SlipAt(const Eigen::Vector3d& N, const Eigen::Vector3d& V, double vf);

/// ∂R/∂V_rel for any scalar type (double or an automatic-differentiation jet), for callers that
/// differentiate through λ̂_n and N as well. `value` extracts the double value of a T.
template <typename T, typename ValueOf>
Eigen::Matrix<T, 3, 1> DissipationGradient(const T& lambdaHat, const Eigen::Matrix<T, 3, 1>& N,
                                           const Eigen::Matrix<T, 3, 1>& V,
                                           const DissipationCoefficients& c, ValueOf value) {
  const T Vn = V.dot(N);
  const Eigen::Matrix<T, 3, 1> Vt = V - Vn * N;
  const T Vt2 = Vt.squaredNorm();
  const double speed = std::sqrt(value(Vt2));
  // μ ρ'(V_t)/V_t · V_t, written so that no derivative of √(V_t²) is taken at V_t = 0.
  T coulombSlope;
  if (speed >= c.vf) {
    using std::sqrt;
    coulombSlope = T(c.mu) / sqrt(Vt2);
  } else if (value(Vt2) > 0.0) {
    using std::sqrt;
    coulombSlope = T(c.mu) * (T(2.0 / c.vf) - sqrt(Vt2) / (c.vf * c.vf));
  } else {
    // At V_t = 0 the V_t/V_f² term has zero derivative as well (it multiplies V_t).
    coulombSlope = T(c.mu * 2.0 / c.vf);
  }
  return lambdaHat * ((coulombSlope + T(c.ct)) * Vt + T(c.cn) * Vn * N);
}

/// Hunt–Crossley calibration (spec: "Restitution Behavior of Rigid Collisions"): the rational
/// approximation c_n ≈ (1 − e)(1 + 9e/2) / (e v (1 + 8e/3)) [s/m] for a coefficient of
/// restitution e in (0, 1] at impact speed v > 0 [m/s]. Returns NaN outside the domain.
double HuntCrossleyDampingFromRestitution(double e, double v);

/// Its closed-form inverse: with a = c_n v, e solves (8a/3 + 9/2) e² + (a − 7/2) e − 1 = 0,
///   e = 2 / (B + √(B² + 4A)),  A = 8a/3 + 9/2,  B = a − 7/2,
/// the positive root (e = 1 at c_n = 0; e ≈ 1/(c_n v) for large c_n v).
/// c_n >= 0 [s/m], v > 0 [m/s]; NaN outside the domain.
double HuntCrossleyRestitutionFromDamping(double cn, double v);

}  // namespace superdex
