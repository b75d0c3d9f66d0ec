// Symmetric triangle quadrature rules (see quadrature.h).
//
// Every rule is a union of S3-symmetric orbits in barycentric coordinates:
//   centroid  (1/3, 1/3, 1/3)                       1 point,  unknown w
//   3-orbit   (1 − 2a, a, a) and its permutations     3 points, unknowns a, w
//   6-orbit   (a, b, 1 − a − b) and its permutations  6 points, unknowns a, b, w
// A symmetric rule integrates every polynomial of degree <= d exactly iff it integrates every
// S3-invariant polynomial of degree <= d exactly; on the plane λ1 + λ2 + λ3 = 1 those are spanned
// by  e2^i e3^j  (2i + 3j <= d)  with  e2 = λ1λ2 + λ2λ3 + λ3λ1,  e3 = λ1λ2λ3.
// For the six rules below the number of these moment equations equals the number of orbit
// unknowns (1, 2, 4, 5, 7, 10), so the published values (Dunavant 1985, 15 digits) are refined
// once, at first use, by Newton's method on the square system in extended precision
// (long double; 80-bit on x86-64), then rounded to double. If Newton ever failed to reduce the
// residual, the tabulated values would be kept.
#include "geometry/quadrature.h"

#include <Eigen/LU>
#include <array>
#include <cmath>
#include <vector>

namespace superdex {
namespace {

using Real = long double;
using VectorR = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
using MatrixR = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>;

/// Orbit structure of a symmetric rule with its starting (tabulated) parameters.
struct OrbitSpec {
  int degree = 0;
  bool hasCentroid = false;
  Real centroidWeight = 0;
  std::vector<std::array<Real, 2>> orbit3;  ///< (a, w): points (1 − 2a, a, a), each weight w
  std::vector<std::array<Real, 3>> orbit6;  ///< (a, b, w): points (a, b, 1 − a − b), weight w

  int NumUnknowns() const {
    return (hasCentroid ? 1 : 0) + 2 * static_cast<int>(orbit3.size()) +
           3 * static_cast<int>(orbit6.size());
  }
  VectorR Pack() const {
    VectorR x(NumUnknowns());
    int k = 0;
    if (hasCentroid) x[k++] = centroidWeight;
    for (const auto& o : orbit3)
      for (Real v : o) x[k++] = v;
    for (const auto& o : orbit6)
      for (Real v : o) x[k++] = v;
    return x;
  }
  void Unpack(const VectorR& x) {
    int k = 0;
    if (hasCentroid) centroidWeight = x[k++];
    for (auto& o : orbit3)
      for (Real& v : o) v = x[k++];
    for (auto& o : orbit6)
      for (Real& v : o) v = x[k++];
  }
  /// Positive weights and every point strictly inside the triangle.
  bool Valid() const {
    if (hasCentroid && !(centroidWeight > 0)) return false;
    for (const auto& o : orbit3)
      if (!(o[1] > 0 && o[0] > 0 && 1 - 2 * o[0] > 0)) return false;
    for (const auto& o : orbit6)
      if (!(o[2] > 0 && o[0] > 0 && o[1] > 0 && 1 - o[0] - o[1] > 0)) return false;
    return true;
  }
};

Real Factorial(int n) { return n <= 1 ? Real(1) : n * Factorial(n - 1); }

/// Mean over any triangle of e2^i e3^j, from  (1/A) ∫_T λ1^p λ2^q λ3^r dA = 2 p! q! r!/(p+q+r+2)!
/// after the multinomial expansion  e2^i = Σ i!/(α!β!γ!) (λ1λ2)^α (λ2λ3)^β (λ3λ1)^γ.
Real InvariantMean(int i, int j) {
  Real sum = 0;
  for (int al = 0; al <= i; ++al)
    for (int be = 0; al + be <= i; ++be) {
      const int ga = i - al - be;
      const Real multinomial = Factorial(i) / (Factorial(al) * Factorial(be) * Factorial(ga));
      const int p = al + ga + j, q = al + be + j, r = be + ga + j;
      sum +=
          multinomial * 2 * Factorial(p) * Factorial(q) * Factorial(r) / Factorial(p + q + r + 2);
    }
  return sum;
}

Real IntPow(Real x, int n) {
  Real r = 1;
  for (int k = 0; k < n; ++k) r *= x;
  return r;
}

/// f = e2^i e3^j at λ and its gradient with respect to λ (λ treated as three free variables).
void Invariant(const Eigen::Matrix<Real, 3, 1>& l, int i, int j, Real* f,
               Eigen::Matrix<Real, 3, 1>* grad) {
  const Real e2 = l[0] * l[1] + l[1] * l[2] + l[2] * l[0];
  const Real e3 = l[0] * l[1] * l[2];
  const Eigen::Matrix<Real, 3, 1> de2(l[1] + l[2], l[0] + l[2], l[0] + l[1]);
  const Eigen::Matrix<Real, 3, 1> de3(l[1] * l[2], l[0] * l[2], l[0] * l[1]);
  *f = IntPow(e2, i) * IntPow(e3, j);
  grad->setZero();
  if (i > 0) *grad += Real(i) * IntPow(e2, i - 1) * IntPow(e3, j) * de2;
  if (j > 0) *grad += Real(j) * IntPow(e2, i) * IntPow(e3, j - 1) * de3;
}

/// Residual F_m = Σ_orbits (size · w · f_m(point)) − mean(f_m) of the moment equations and its
/// Jacobian with respect to the packed unknowns.
void MomentSystem(const OrbitSpec& spec, const std::vector<std::array<int, 2>>& moments,
                  const VectorR& exact, VectorR* F, MatrixR* J) {
  const int n = spec.NumUnknowns();
  const int m = static_cast<int>(moments.size());
  F->setZero(m);
  J->setZero(m, n);
  for (int e = 0; e < m; ++e) {
    const int i = moments[e][0], j = moments[e][1];
    Real f;
    Eigen::Matrix<Real, 3, 1> g;
    int k = 0;
    if (spec.hasCentroid) {
      const Real third = Real(1) / 3;
      Invariant(Eigen::Matrix<Real, 3, 1>(third, third, third), i, j, &f, &g);
      (*F)[e] += spec.centroidWeight * f;
      (*J)(e, k++) = f;
    }
    for (const auto& o : spec.orbit3) {
      const Real a = o[0], w = o[1];
      Invariant(Eigen::Matrix<Real, 3, 1>(1 - 2 * a, a, a), i, j, &f, &g);
      (*F)[e] += 3 * w * f;
      (*J)(e, k++) = 3 * w * (-2 * g[0] + g[1] + g[2]);  // dλ/da = (−2, 1, 1)
      (*J)(e, k++) = 3 * f;
    }
    for (const auto& o : spec.orbit6) {
      const Real a = o[0], b = o[1], w = o[2];
      Invariant(Eigen::Matrix<Real, 3, 1>(a, b, 1 - a - b), i, j, &f, &g);
      (*F)[e] += 6 * w * f;
      (*J)(e, k++) = 6 * w * (g[0] - g[2]);  // dλ/da = (1, 0, −1)
      (*J)(e, k++) = 6 * w * (g[1] - g[2]);  // dλ/db = (0, 1, −1)
      (*J)(e, k++) = 6 * f;
    }
    (*F)[e] -= exact[e];
  }
}

/// Newton's method on the moment equations of degree <= spec.degree (a square system).
void Refine(OrbitSpec* spec) {
  std::vector<std::array<int, 2>> moments;
  for (int i = 0; 2 * i <= spec->degree; ++i)
    for (int j = 0; 2 * i + 3 * j <= spec->degree; ++j) moments.push_back({i, j});
  if (static_cast<int>(moments.size()) != spec->NumUnknowns()) return;  // not square: keep table
  VectorR exact(moments.size());
  for (size_t e = 0; e < moments.size(); ++e)
    exact[e] = InvariantMean(moments[e][0], moments[e][1]);

  VectorR F;
  MatrixR J;
  MomentSystem(*spec, moments, exact, &F, &J);
  const Real initialResidual = F.norm();
  OrbitSpec best = *spec;
  Real bestResidual = initialResidual;
  for (int iter = 0; iter < 8 && bestResidual > 0; ++iter) {
    Eigen::FullPivLU<MatrixR> lu(J);
    if (!lu.isInvertible()) break;
    OrbitSpec trial = best;
    trial.Unpack(best.Pack() - lu.solve(F));
    MomentSystem(trial, moments, exact, &F, &J);
    const Real residual = F.norm();
    if (!(residual < bestResidual) || !trial.Valid()) break;  // at round-off, or diverging
    best = trial;
    bestResidual = residual;
  }
  *spec = best;
}

void AddPoint(TriangleQuadratureRule* r, Real l0, Real l1, Real l2, Real w) {
  r->barycentric.emplace_back(static_cast<double>(l0), static_cast<double>(l1),
                              static_cast<double>(l2));
  r->weights.push_back(static_cast<double>(w));
}

TriangleQuadratureRule Build(OrbitSpec spec) {
  Refine(&spec);
  TriangleQuadratureRule r;
  r.degree = spec.degree;
  if (spec.hasCentroid) {
    const Real t = Real(1) / 3;
    AddPoint(&r, t, t, t, spec.centroidWeight);
  }
  for (const auto& o : spec.orbit3) {
    const Real a = o[0], b = 1 - 2 * a, w = o[1];
    AddPoint(&r, b, a, a, w);
    AddPoint(&r, a, b, a, w);
    AddPoint(&r, a, a, b, w);
  }
  for (const auto& o : spec.orbit6) {
    const Real a = o[0], b = o[1], c = 1 - a - b, w = o[2];
    AddPoint(&r, a, b, c, w);
    AddPoint(&r, b, a, c, w);
    AddPoint(&r, a, c, b, w);
    AddPoint(&r, c, a, b, w);
    AddPoint(&r, b, c, a, w);
    AddPoint(&r, c, b, a, w);
  }
  return r;
}

TriangleQuadratureRule Make(ActorBoundaryElementType type) {
  OrbitSpec s;
  switch (type) {
    case ActorBoundaryElementType::P1Q1:  // centroid rule, degree 1
      s.degree = 1;
      s.hasCentroid = true;
      s.centroidWeight = 1;
      break;
    case ActorBoundaryElementType::P1Q3:  // interior points (2/3, 1/6, 1/6), degree 2
      s.degree = 2;
      s.orbit3 = {{Real(1) / 6, Real(1) / 3}};
      break;
    case ActorBoundaryElementType::P1Q6:  // Dunavant (1985), degree 4
      s.degree = 4;
      s.orbit3 = {{0.445948490915965L, 0.223381589678011L},
                  {0.091576213509771L, 0.109951743655322L}};
      break;
    case ActorBoundaryElementType::ExperimentalP1Q7: {  // Radon (1948), degree 5, closed form
      s.degree = 5;
      const Real r15 = std::sqrt(Real(15));
      s.hasCentroid = true;
      s.centroidWeight = Real(9) / 40;
      s.orbit3 = {{(6 - r15) / 21, (155 - r15) / 1200}, {(6 + r15) / 21, (155 + r15) / 1200}};
      break;
    }
    case ActorBoundaryElementType::ExperimentalP1Q12:  // Dunavant (1985), degree 6
      s.degree = 6;
      s.orbit3 = {{0.249286745170910L, 0.116786275726379L},
                  {0.063089014491502L, 0.050844906370207L}};
      s.orbit6 = {{0.053145049844817L, 0.310352451033784L, 0.082851075618374L}};
      break;
    case ActorBoundaryElementType::ExperimentalP1Q16:  // Dunavant (1985), degree 8
      s.degree = 8;
      s.hasCentroid = true;
      s.centroidWeight = 0.144315607677787L;
      s.orbit3 = {{0.459292588292723L, 0.095091634267285L},
                  {0.170569307751760L, 0.103217370534718L},
                  {0.050547228317031L, 0.032458497623198L}};
      s.orbit6 = {{0.008394777409958L, 0.263112829634638L, 0.027230314174435L}};
      break;
  }
  return Build(s);
}

}  // namespace

const TriangleQuadratureRule& GetTriangleQuadratureRule(ActorBoundaryElementType type) {
  using T = ActorBoundaryElementType;
  constexpr T kTypes[] = {T::P1Q1,           T::P1Q3,           T::P1Q6,
                          T::ExperimentalP1Q7, T::ExperimentalP1Q12, T::ExperimentalP1Q16};
  // A function-local static: built once, on first use, thread-safely (C++11 magic statics).
  static const std::vector<TriangleQuadratureRule> rules = [&] {
    std::vector<TriangleQuadratureRule> r;
    for (const T t : kTypes) r.push_back(Make(t));
    return r;
  }();
  for (size_t i = 0; i < rules.size(); ++i)
    if (kTypes[i] == type) return rules[i];
  return rules[1];  // not a valid enumerator: the default rule, P1Q3
}

}  // namespace superdex
