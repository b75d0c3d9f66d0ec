// Validation of a joint's parameters (joint_params.h).
#include "core/model/joint_params.h"

#include <cmath>
#include <sstream>

namespace superdex {

std::string Validate(const JointParams& p, const std::string& prefix) {
  if (std::string m = ValidateFields(kJointParamsFields, p, prefix); !m.empty()) return m;
  std::ostringstream s;
  if (std::isnan(p.lowerLimit) || p.lowerLimit == std::numeric_limits<double>::infinity())
    s << prefix << "lower_limit: must be a number or -inf, got " << p.lowerLimit;
  else if (std::isnan(p.upperLimit) || p.upperLimit == -std::numeric_limits<double>::infinity())
    s << prefix << "upper_limit: must be a number or inf, got " << p.upperLimit;
  else if (!(p.lowerLimit <= p.upperLimit))
    s << prefix << "upper_limit: must be >= lower_limit (" << p.lowerLimit << "), got "
      << p.upperLimit;
  else if (!(p.driveForceLimit > 0.0))
    s << prefix << "drive_force_limit: must be > 0 (inf: no limit), got " << p.driveForceLimit;
  if (!s.str().empty()) return s.str();
  if (std::string m = CheckKeyframes(p.driveTargetPosition, prefix + "drive_target_position");
      !m.empty())
    return m;
  return CheckKeyframes(p.driveTargetVelocity, prefix + "drive_target_velocity");
}

}  // namespace superdex
