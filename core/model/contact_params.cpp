#include "core/model/contact_params.h"

#include <cmath>

namespace superdex {

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
