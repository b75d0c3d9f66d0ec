// Per-actor contact parameters (spec: "ContactParams") and their per-pair combination
// (spec: "Contact Parameter Combination").
#pragma once

#include <string>

namespace superdex {

/// Contact response of one actor. Names, defaults and units are the spec's table; Python uses the
/// snake_case names (penalty_coefficient, ...).
struct ContactParams {
  double penaltyCoefficient = 1e9;             ///< k [Pa/m], > 0
  double penaltySmoothingHalfDistance = 0.005; ///< ε [m], > 0
  double penaltyThresholdDefault = 0.001;      ///< δ [m]
  double penaltyThresholdExtraPadding = 0.0;   ///< added to δ when the colliding actor's
                                               ///< collider is None or PointCloud [m], >= 0
  bool frictionWithColliderNormal = true;      ///< split on N_B (true) or −N_A (false)
  double maxAlignmentNormals = 0.0;            ///< m [-], in [−1, 1]
  double viscousFrictionCoefficient = 0.0;     ///< c_t [s/m], >= 0
  double coulombFrictionCoefficient = 0.5;     ///< μ [-], >= 0
  double frictionFalloffVel = 0.01;            ///< V_f [m/s], > 0
  double normalViscousDampingCoefficient = 0.0;///< c_n [s/m], >= 0
  double distanceErrorBound = 0.0;             ///< experimental: collider bounding-volume
                                               ///< padding [m], >= 0
  double collidingPenaltyLengthScale = 1.0;    ///< experimental [m], > 0; from the colliding actor
};

/// Returns "" when valid, else "<prefix><snake_case field>: <rule>, got <value>".
std::string Validate(const ContactParams& params, const std::string& prefix = "");

/// Parameters of one ordered pair (A colliding, B collider) after combination.
struct PairContactParams {
  double penaltyCoefficient = 0.0;         ///< k: √(k_A k_B) if both dynamic, else k_A
  double frictionFalloffVel = 0.0;         ///< V_f: as k
  double coulombFrictionCoefficient = 0.0; ///< μ: √(μ_A μ_B)
  double viscousFrictionCoefficient = 0.0; ///< c_t: √(c_tA c_tB)
  double normalViscousDampingCoefficient = 0.0; ///< c_n: √(c_nA c_nB)
  double smoothingHalfDistance = 0.0;      ///< ε: the collider's
  double threshold = 0.0;                  ///< δ: the collider's default, plus its extra padding
                                           ///< when the colliding actor's collider is None or
                                           ///< PointCloud
  double maxAlignmentNormals = 0.0;        ///< m: the collider's
  bool frictionWithColliderNormal = true;  ///< the collider's
  double distanceErrorBound = 0.0;         ///< the collider's
  double collidingPenaltyLengthScale = 1.0;///< always the colliding actor's
};

/// Combines the colliding actor A's and the collider B's parameters by the spec's rules.
/// `colliderIsStatic`: B is a static actor (then k and V_f are A's).
/// `collidingHasNoColliderOrPointCloud`: A's resolved collider type is None or PointCloud.
PairContactParams CombineContactParams(const ContactParams& colliding,
                                       const ContactParams& collider, bool colliderIsStatic,
                                       bool collidingHasNoColliderOrPointCloud);

}  // namespace superdex
