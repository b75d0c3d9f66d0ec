// Contact results per actor pair, from the per-sample records (Scene::ContactSamples): what MuJoCo's
// mj_contactForce, PyBullet's getContactPoints and Drake's ContactResults give, summed over both
// passes of a pair (A's samples on B's field and B's on A's) so that no load is counted twice.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "core/contact/rigid_contact.h"

namespace superdex {

/// The contact between actors a < b (world frame, SI units). Forces act on a; b takes their
/// opposites. A sample of a on b's field acts at its point x with f = w (t_n + t_f + t_d); a
/// sample of b on a's field acts on a at its point with −f.
struct ContactPairSummary {
  int a = -1, b = -1;                                         ///< actor indices, a < b
  Eigen::Vector3d normalForce = Eigen::Vector3d::Zero();      ///< Σ ± w t_n [N]
  Eigen::Vector3d frictionForce = Eigen::Vector3d::Zero();    ///< Σ ± w t_f [N]
  Eigen::Vector3d dampingForce = Eigen::Vector3d::Zero();     ///< Σ ± w t_d [N]
  Eigen::Vector3d force = Eigen::Vector3d::Zero();            ///< their sum [N]
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();           ///< Σ x × (± f) about the origin [N·m]
  /// Σ |w t_n| x / Σ |w t_n| over both passes' samples [m] (NaN without a normal load).
  Eigen::Vector3d centreOfPressure = Eigen::Vector3d::Constant(NAN);
  /// The active penalty area: Σ w over the samples with a normal load, the larger of the two
  /// passes (each measures the patch on its own colliding surface) [m²].
  double area = 0.0;
  double maxPenetration = 0.0;  ///< max(0, −φ) over the samples [m]
  int samples = 0;              ///< records of both passes
};

/// One summary per actor pair with a record, ordered by (a, b).
std::vector<ContactPairSummary> SummarizeContactPairs(
    const std::vector<ContactSampleRecord>& records);

}  // namespace superdex
