#include "core/model/contact_params.h"

#include <cmath>
#include <sstream>

namespace superdex {
namespace {

std::string Rule(const std::string& prefix, const char* field, const char* rule, double value) {
  std::ostringstream s;
  s << prefix << field << ": " << rule << ", got " << value;
  return s.str();
}

}  // namespace

std::string Validate(const ContactParams& p, const std::string& prefix) {
  auto finite = [](double v) { return std::isfinite(v); };
  if (!(finite(p.penaltyCoefficient) && p.penaltyCoefficient > 0))
    return Rule(prefix, "penalty_coefficient", "must be > 0", p.penaltyCoefficient);
  if (!(finite(p.penaltySmoothingHalfDistance) && p.penaltySmoothingHalfDistance > 0))
    return Rule(prefix, "penalty_smoothing_half_distance", "must be > 0",
                p.penaltySmoothingHalfDistance);
  if (!finite(p.penaltyThresholdDefault))
    return Rule(prefix, "penalty_threshold_default", "must be finite", p.penaltyThresholdDefault);
  if (!(finite(p.penaltyThresholdExtraPadding) && p.penaltyThresholdExtraPadding >= 0))
    return Rule(prefix, "penalty_threshold_extra_padding", "must be >= 0",
                p.penaltyThresholdExtraPadding);
  if (!(finite(p.maxAlignmentNormals) && p.maxAlignmentNormals >= -1 &&
        p.maxAlignmentNormals <= 1))
    return Rule(prefix, "max_alignment_normals", "must be in [-1, 1]", p.maxAlignmentNormals);
  if (!(finite(p.viscousFrictionCoefficient) && p.viscousFrictionCoefficient >= 0))
    return Rule(prefix, "viscous_friction_coefficient", "must be >= 0",
                p.viscousFrictionCoefficient);
  if (!(finite(p.coulombFrictionCoefficient) && p.coulombFrictionCoefficient >= 0))
    return Rule(prefix, "coulomb_friction_coefficient", "must be >= 0",
                p.coulombFrictionCoefficient);
  if (!(finite(p.frictionFalloffVel) && p.frictionFalloffVel > 0))
    return Rule(prefix, "friction_falloff_vel", "must be > 0", p.frictionFalloffVel);
  if (!(finite(p.normalViscousDampingCoefficient) && p.normalViscousDampingCoefficient >= 0))
    return Rule(prefix, "normal_viscous_damping_coefficient", "must be >= 0",
                p.normalViscousDampingCoefficient);
  if (!(finite(p.distanceErrorBound) && p.distanceErrorBound >= 0))
    return Rule(prefix, "distance_error_bound", "must be >= 0", p.distanceErrorBound);
  if (!(finite(p.collidingPenaltyLengthScale) && p.collidingPenaltyLengthScale > 0))
    return Rule(prefix, "colliding_penalty_length_scale", "must be > 0",
                p.collidingPenaltyLengthScale);
  return "";
}

PairContactParams CombineContactParams(const ContactParams& a, const ContactParams& b,
                                       bool colliderIsStatic,
                                       bool collidingHasNoColliderOrPointCloud) {
  PairContactParams p;
  if (colliderIsStatic) {
    p.penaltyCoefficient = a.penaltyCoefficient;
    p.frictionFalloffVel = a.frictionFalloffVel;
  } else {
    p.penaltyCoefficient = std::sqrt(a.penaltyCoefficient * b.penaltyCoefficient);
    p.frictionFalloffVel = std::sqrt(a.frictionFalloffVel * b.frictionFalloffVel);
  }
  p.coulombFrictionCoefficient =
      std::sqrt(a.coulombFrictionCoefficient * b.coulombFrictionCoefficient);
  p.viscousFrictionCoefficient =
      std::sqrt(a.viscousFrictionCoefficient * b.viscousFrictionCoefficient);
  p.normalViscousDampingCoefficient =
      std::sqrt(a.normalViscousDampingCoefficient * b.normalViscousDampingCoefficient);
  p.smoothingHalfDistance = b.penaltySmoothingHalfDistance;
  p.threshold = b.penaltyThresholdDefault +
                (collidingHasNoColliderOrPointCloud ? b.penaltyThresholdExtraPadding : 0.0);
  p.maxAlignmentNormals = b.maxAlignmentNormals;
  p.frictionWithColliderNormal = b.frictionWithColliderNormal;
  p.distanceErrorBound = b.distanceErrorBound;
  p.collidingPenaltyLengthScale = a.collidingPenaltyLengthScale;
  return p;
}

}  // namespace superdex
