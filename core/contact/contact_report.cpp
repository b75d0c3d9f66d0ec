#include "core/contact/contact_report.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace superdex {

std::vector<ContactPairSummary> SummarizeContactPairs(
    const std::vector<ContactSampleRecord>& records) {
  struct Sums {
    ContactPairSummary s;
    double pressureWeight = 0.0;
    Eigen::Vector3d pressurePoint = Eigen::Vector3d::Zero();
    double area[2] = {0.0, 0.0};  // per pass: a colliding, b colliding
  };
  std::map<std::pair<int, int>, Sums> pairs;
  for (const ContactSampleRecord& r : records) {
    const bool aColliding = r.colliding < r.collider;
    const int a = std::min(r.colliding, r.collider), b = std::max(r.colliding, r.collider);
    Sums& p = pairs[{a, b}];
    p.s.a = a;
    p.s.b = b;
    const double sign = aColliding ? 1.0 : -1.0;  // the record's force acts on its colliding actor
    const Eigen::Vector3d fn = sign * r.weight * r.traction, ff = sign * r.weight * r.friction,
                          fd = sign * r.weight * r.damping;
    p.s.normalForce += fn;
    p.s.frictionForce += ff;
    p.s.dampingForce += fd;
    p.s.torque += r.position.cross(fn + ff + fd);
    const double load = fn.norm();
    p.pressureWeight += load;
    p.pressurePoint += load * r.position;
    if (r.lambdaN > 0) p.area[aColliding ? 0 : 1] += r.weight;
    if (std::isfinite(r.phi)) p.s.maxPenetration = std::max(p.s.maxPenetration, -r.phi);
    ++p.s.samples;
  }
  std::vector<ContactPairSummary> out;
  out.reserve(pairs.size());
  for (auto& [key, p] : pairs) {
    p.s.force = p.s.normalForce + p.s.frictionForce + p.s.dampingForce;
    if (p.pressureWeight > 0) p.s.centreOfPressure = p.pressurePoint / p.pressureWeight;
    p.s.area = std::max(p.area[0], p.area[1]);
    out.push_back(p.s);
  }
  return out;
}

}  // namespace superdex
