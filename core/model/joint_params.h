// The parameters of one joint coordinate of an articulated actor (a Revolute joint's angle
// [rad], a Prismatic joint's offset [m]): position limits, viscous damping and a PD drive.
// Units below for an angle; for an offset read m for rad and N for N·m.
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include "core/model/keyframes.h"
#include "optim/field_table.h"

namespace superdex {

struct JointParams {
  double lowerLimit = -std::numeric_limits<double>::infinity();  ///< [rad]
  double upperLimit = std::numeric_limits<double>::infinity();   ///< [rad]
  double limitStiffness = 1e4;                                   ///< [N·m/rad]
  double damping = 0.0;                                          ///< [N·m·s/rad]
  double driveStiffness = 0.0;                                   ///< k_p [N·m/rad]
  double driveDamping = 0.0;                                     ///< k_d [N·m·s/rad]
  double driveForceLimit = std::numeric_limits<double>::infinity(); ///< [N·m]
  /// The drive's target x*(t) [rad], piecewise linear (keyframes (t [s], x*)); empty: 0.
  ScalarKeyframes driveTargetPosition;
  /// Its target velocity v*(t) [rad/s], piecewise linear; empty: the position path's slope.
  ScalarKeyframes driveTargetVelocity;

  /// Whether any term is on (a limit, damping or a drive).
  bool Active() const {
    return std::isfinite(lowerLimit) || std::isfinite(upperLimit) || damping > 0.0 ||
           driveStiffness > 0.0 || driveDamping > 0.0;
  }
};

/// The fields (optim/field_table.h), in the order of validation. The keyframes are checked by
/// Validate below.
inline constexpr auto kJointParamsFields = std::make_tuple(
    MakeField("lower_limit", &JointParams::lowerLimit, "rad or m", NoRule(),
              "Lower position limit (-inf: none; a number, <= upper_limit)"),
    MakeField("upper_limit", &JointParams::upperLimit, "rad or m", NoRule(),
              "Upper position limit (inf: none; a number, >= lower_limit)"),
    MakeField("limit_stiffness", &JointParams::limitStiffness, "N·m/rad or N/m", PositiveRule(),
              "Stiffness k of the limits' one-sided quadratic penalty (compliance 1/k)"),
    MakeField("damping", &JointParams::damping, "N·m·s/rad or N·s/m", NonNegativeRule(),
              "Viscous joint damping (dissipation ½ c ẋ²)"),
    MakeField("drive_stiffness", &JointParams::driveStiffness, "N·m/rad or N/m",
              NonNegativeRule(), "PD drive stiffness k_p"),
    MakeField("drive_damping", &JointParams::driveDamping, "N·m·s/rad or N·s/m",
              NonNegativeRule(), "PD drive damping k_d"),
    MakeField("drive_force_limit", &JointParams::driveForceLimit, "N·m or N", NoRule(),
              "Largest drive force or torque (> 0; inf: no limit)"));

constexpr const auto& FieldsOf(const JointParams&) { return kJointParamsFields; }

/// "" when valid, else "<prefix><field>: must be <rule>, got <value>" (the table's rows; limits
/// numbers with lower <= upper, infinite for none; a force limit > 0, infinite for none; the
/// drive's keyframes finite with increasing times).
std::string Validate(const JointParams& p, const std::string& prefix = "");

}  // namespace superdex
