#include "energies/sphere_penalty.h"

#include <algorithm>
#include <cmath>

namespace superdex {

namespace {

// The ramp's part in u = s/ε on 0 <= u <= 2 (h = ε u³(4 − u)/16):
//   Q0 = (k/2) ε³/256 (16u⁷/7 − u⁸ + u⁹/9),  Q1 = (k/2) ε⁴/256 (2u⁸ − 8u⁹/9 + u¹⁰/10).
PenaltyAntiderivatives RampIntegrals(double u, const PenaltyParams& p) {
  const double u2 = u * u, u4 = u2 * u2, u7 = u4 * u2 * u, u8 = u4 * u4;
  const double e3 = p.eps * p.eps * p.eps;
  PenaltyAntiderivatives q;
  q.Q0 = 0.5 * p.k * e3 / 256.0 * u7 * (16.0 / 7.0 - u + u2 / 9.0);
  q.Q1 = 0.5 * p.k * e3 * p.eps / 256.0 * u8 * (2.0 - 8.0 * u / 9.0 + u2 / 10.0);
  return q;
}

// W(s) and dW/ds = λ_n at s = δ − φ.
struct DensityInS {
  double W = 0.0, Ws = 0.0;
};
DensityInS AtS(double s, const PenaltyParams& p) {
  if (!(s > 0.0)) return {};
  const PenaltyDensity d = NormalPenaltyDensity(p.delta - s, p);
  return {d.W, d.lambdaN};
}

}  // namespace

PenaltyAntiderivatives PenaltyIntegrals(double s, const PenaltyParams& p) {
  if (!(s > 0.0)) return {};
  const double u = s / p.eps;
  if (u <= 2.0) return RampIntegrals(u, p);
  // Beyond the ramp h = s − ε: (k/2)((s − ε)³ − ε³)/3, and (k/2)[σ⁴/4 − 2εσ³/3 + ε²σ²/2] from 2ε.
  PenaltyAntiderivatives q = RampIntegrals(2.0, p);
  const double e3 = p.eps * p.eps * p.eps;
  auto f1 = [](double v) { return v * v * (v * v / 4.0 - 2.0 * v / 3.0 + 0.5); };  // in units ε⁴
  q.Q0 += 0.5 * p.k * e3 * ((u - 1.0) * (u - 1.0) * (u - 1.0) - 1.0) / 3.0;
  q.Q1 += 0.5 * p.k * e3 * p.eps * (f1(u) - f1(2.0));
  return q;
}

SpherePenalty SpherePlanePenalty(double h, double r, double m, const PenaltyParams& p) {
  const double tau = std::clamp(m, -1.0, 1.0);
  const double sHi = p.delta - h + r;        // the deepest sample, t = −1
  const double sLo = p.delta - h - r * tau;  // the cut, t = τ
  const double c = 2.0 * M_PI * r;
  const DensityInS hi = AtS(sHi, p), lo = AtS(sLo, p);
  SpherePenalty out;
  out.E = c * (PenaltyIntegrals(sHi, p).Q0 - PenaltyIntegrals(sLo, p).Q0);
  out.dE = c * (lo.W - hi.W);
  out.d2E = c * (hi.Ws - lo.Ws);
  return out;
}

SpherePenalty SphereSpherePenalty(double d, double rA, double rB, double m,
                                  const PenaltyParams& p) {
  // ρ_hi(d) = q + m rA with q = √(d² − (1 − m²) rA²); ρ_hi' = d/q, ρ_hi'' = −(1 − m²) rA²/q³.
  const double mm = std::clamp(m, -1.0, 1.0);
  const double q = std::sqrt(d * d - (1.0 - mm * mm) * rA * rA);
  const double rhoHi = q + mm * rA, rhoHi1 = d / q, rhoHi2 = -(1.0 - mm * mm) * rA * rA / (q * q * q);
  const double reach = rB + p.delta;  // ρ where s = 0
  const double sMax = reach - (d - rA), sMin = reach - rhoHi;
  // G = (rB + δ) Q0 − Q1, G' = ρ W, G'' = −W + ρ W_s (ρ = rB + δ − s).
  auto G = [&](double s, double* g1, double* g2) {
    const PenaltyAntiderivatives Q = PenaltyIntegrals(s, p);
    const DensityInS w = AtS(s, p);
    const double rho = reach - s;
    *g1 = rho * w.W;
    *g2 = -w.W + rho * w.Ws;
    return reach * Q.Q0 - Q.Q1;
  };
  double gMax1, gMax2, gMin1, gMin2;
  const double F = G(sMax, &gMax1, &gMax2) - G(sMin, &gMin1, &gMin2);
  // s_max' = −1, s_min' = −ρ_hi', s_min'' = −ρ_hi''.
  const double F1 = -gMax1 + gMin1 * rhoHi1;
  const double F2 = gMax2 - (gMin2 * rhoHi1 * rhoHi1 - gMin1 * rhoHi2);
  const double c = 2.0 * M_PI * rA;
  SpherePenalty out;
  out.E = c * F / d;
  out.dE = c * (F1 / d - F / (d * d));
  out.d2E = c * (F2 / d - 2.0 * F1 / (d * d) + 2.0 * F / (d * d * d));
  return out;
}

}  // namespace superdex
