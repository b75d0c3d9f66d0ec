// Per-actor contact parameters (spec: "ContactParams") and their per-pair combination
// (spec: "Contact Parameter Combination").
#pragma once

#include <string>

#include "optim/field_table.h"

namespace superdex {

/// Contact response of one actor. Defaults are the spec's; names, units and rules are in
/// kContactParamsFields below (Python and scene files use its snake_case names).
struct ContactParams {
  double penaltyCoefficient = 1e9;              ///< k
  double penaltySmoothingHalfDistance = 0.005;  ///< ε
  double penaltyThresholdDefault = 0.001;       ///< δ
  double penaltyThresholdExtraPadding = 0.0;
  bool frictionWithColliderNormal = true;
  double maxAlignmentNormals = 0.0;             ///< m
  double viscousFrictionCoefficient = 0.0;      ///< c_t
  double coulombFrictionCoefficient = 0.5;      ///< μ
  double frictionFalloffVel = 0.01;             ///< V_f
  double normalViscousDampingCoefficient = 0.0; ///< c_n
  double distanceErrorBound = 0.0;              ///< experimental
  double collidingPenaltyLengthScale = 1.0;     ///< experimental
};

/// The fields (optim/field_table.h), in the order of validation.
inline constexpr auto kContactParamsFields = std::make_tuple(
    MakeField("penalty_coefficient", &ContactParams::penaltyCoefficient, "Pa/m", PositiveRule(),
              "Penalty coefficient k"),
    MakeField("penalty_smoothing_half_distance", &ContactParams::penaltySmoothingHalfDistance, "m",
              PositiveRule(), "Smoothing half-width ε of the penalty ramp"),
    MakeField("penalty_threshold_default", &ContactParams::penaltyThresholdDefault, "m",
              FiniteRule(), "Contact threshold δ at which the penalty activates"),
    MakeField("penalty_threshold_extra_padding", &ContactParams::penaltyThresholdExtraPadding, "m",
              NonNegativeRule(),
              "Added to δ when the colliding actor's collider is None or PointCloud"),
    MakeField("friction_with_collider_normal", &ContactParams::frictionWithColliderNormal, "",
              NoRule(), "Split on the collider's field direction N_B (true) or on −N_A (false)"),
    MakeField("max_alignment_normals", &ContactParams::maxAlignmentNormals, "-", InClosed(-1, 1),
              "Maximum normal alignment m; a sample with alignment s > m is rejected"),
    MakeField("viscous_friction_coefficient", &ContactParams::viscousFrictionCoefficient, "s/m",
              NonNegativeRule(), "Tangential viscous friction coefficient c_t"),
    MakeField("coulomb_friction_coefficient", &ContactParams::coulombFrictionCoefficient, "-",
              NonNegativeRule(), "Coulomb friction coefficient μ"),
    MakeField("friction_falloff_vel", &ContactParams::frictionFalloffVel, "m/s", PositiveRule(),
              "Falloff velocity V_f of the regularized Coulomb ramp"),
    MakeField("normal_viscous_damping_coefficient",
              &ContactParams::normalViscousDampingCoefficient, "s/m", NonNegativeRule(),
              "Normal viscous damping coefficient c_n (Hunt–Crossley restitution)"),
    MakeField("distance_error_bound", &ContactParams::distanceErrorBound, "m", NonNegativeRule(),
              "Experimental: extra collider bounding-volume padding"),
    MakeField("colliding_penalty_length_scale", &ContactParams::collidingPenaltyLengthScale, "m",
              PositiveRule(),
              "Experimental: penalty correction scale for lower-dimensional colliding manifolds; "
              "taken from the colliding actor"));

/// The table of Validate (optim/field_table.h): "" when valid, else
/// "<prefix><snake_case field>: must be <rule>, got <value>".
constexpr const auto& FieldsOf(const ContactParams&) { return kContactParamsFields; }

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
