#include "geometry/quadrature.h"

#include <cmath>

namespace superdex {
namespace {

// Symmetric orbits in barycentric coordinates; the last coordinate is 1 minus the others so
// every point sums to 1 exactly.
void Centroid(TriangleQuadratureRule* r, double w) {
  r->barycentric.emplace_back(1.0 / 3.0, 1.0 / 3.0, 1.0 - 2.0 / 3.0);
  r->weights.push_back(w);
}

void Orbit3(TriangleQuadratureRule* r, double a, double w) {  // (1−2a, a, a) and permutations
  const double b = 1.0 - 2.0 * a;
  r->barycentric.emplace_back(b, a, 1.0 - b - a);
  r->barycentric.emplace_back(a, b, 1.0 - a - b);
  r->barycentric.emplace_back(a, a, 1.0 - 2.0 * a);
  for (int i = 0; i < 3; ++i) r->weights.push_back(w);
}

void Orbit6(TriangleQuadratureRule* r, double a, double b, double w) {  // (a, b, 1−a−b), all 6
  const double c = 1.0 - a - b;
  const double p[6][2] = {{a, b}, {b, a}, {a, c}, {c, a}, {b, c}, {c, b}};
  for (const auto& q : p) {
    r->barycentric.emplace_back(q[0], q[1], 1.0 - q[0] - q[1]);
    r->weights.push_back(w);
  }
}

TriangleQuadratureRule Make(ActorBoundaryElementType type) {
  TriangleQuadratureRule r;
  switch (type) {
    case ActorBoundaryElementType::P1Q1:
      r.degree = 1;
      Centroid(&r, 1.0);
      break;
    case ActorBoundaryElementType::P1Q3:
      r.degree = 2;
      Orbit3(&r, 1.0 / 6.0, 1.0 / 3.0);
      break;
    case ActorBoundaryElementType::P1Q6:  // Dunavant (1985), degree 4
      r.degree = 4;
      Orbit3(&r, 0.445948490915965, 0.223381589678011);
      Orbit3(&r, 0.091576213509771, 0.109951743655322);
      break;
    case ActorBoundaryElementType::ExperimentalP1Q7: {  // Radon's degree-5 rule, closed form
      r.degree = 5;
      const double s = std::sqrt(15.0);
      Centroid(&r, 9.0 / 40.0);
      Orbit3(&r, (6.0 - s) / 21.0, (155.0 - s) / 1200.0);
      Orbit3(&r, (6.0 + s) / 21.0, (155.0 + s) / 1200.0);
      break;
    }
    case ActorBoundaryElementType::ExperimentalP1Q12:  // Dunavant (1985), degree 6
      r.degree = 6;
      Orbit3(&r, 0.249286745170910, 0.116786275726379);
      Orbit3(&r, 0.063089014491502, 0.050844906370207);
      Orbit6(&r, 0.053145049844817, 0.310352451033784, 0.082851075618374);
      break;
    case ActorBoundaryElementType::ExperimentalP1Q16:  // Dunavant (1985), degree 8
      r.degree = 8;
      Centroid(&r, 0.144315607677787);
      Orbit3(&r, 0.459292588292723, 0.095091634267285);
      Orbit3(&r, 0.170569307751760, 0.103217370534718);
      Orbit3(&r, 0.050547228317031, 0.032458497623198);
      Orbit6(&r, 0.008394777409958, 0.263112829634638, 0.027230314174435);
      break;
  }
  // The tabulated weights carry 15 digits; normalize so they sum to 1 to round-off.
  double sum = 0.0;
  for (double w : r.weights) sum += w;
  for (double& w : r.weights) w /= sum;
  return r;
}

}  // namespace

const TriangleQuadratureRule& GetTriangleQuadratureRule(ActorBoundaryElementType type) {
  static const TriangleQuadratureRule rules[6] = {
      Make(ActorBoundaryElementType::P1Q1),
      Make(ActorBoundaryElementType::P1Q3),
      Make(ActorBoundaryElementType::P1Q6),
      Make(ActorBoundaryElementType::ExperimentalP1Q7),
      Make(ActorBoundaryElementType::ExperimentalP1Q12),
      Make(ActorBoundaryElementType::ExperimentalP1Q16)};
  return rules[static_cast<int>(type)];
}

}  // namespace superdex
