// The normal penalty integrated exactly over a sphere's surface (spec: "Frictionless Normal
// Penalty", Π_AB = ∫_∂Ω_A W dX_A) against a plane or a sphere field: the field then depends on the
// sample's polar angle about one axis only, and the surface integral is a one-dimensional integral
// of the piecewise polynomial W, in closed form.
//
// W(s) = (k/2) h(s)², s = δ − φ (the ramp's argument, energies/penalty_ramp.h), is a polynomial of
// degree 8 on 0 < s < 2ε and of degree 2 beyond; its antiderivatives
//   Q0(s) = ∫_0^s W dσ  [J/m],   Q1(s) = ∫_0^s σ W dσ  [J]
// are polynomials of degree 9 and 10 there, and zero for s <= 0.
//
// Alignment rejection (spec: "Normal/Tangential Split"): a sample is rejected where
// s_al = G_B·N_A > m. Here it is applied to the samples' directions in the configuration the
// integral is evaluated at; the rejected band lies beyond the active cap unless the sphere
// penetrates by about its radius (for m = 0: a plane's cut is the sphere's equator).
#pragma once

#include "energies/normal_penalty.h"

namespace superdex {

/// Q0(s) = ∫_0^s W dσ [J/m] and Q1(s) = ∫_0^s σ W dσ [J] for W = (k/2) h², s = δ − φ [m].
struct PenaltyAntiderivatives {
  double Q0 = 0.0;
  double Q1 = 0.0;
};
PenaltyAntiderivatives PenaltyIntegrals(double s, const PenaltyParams& p);

/// The penalty of a whole sphere as a function of one distance x, with its first two
/// derivatives: E [J], dE/dx [N], d²E/dx² [N/m].
struct SpherePenalty {
  double E = 0.0;
  double dE = 0.0;
  double d2E = 0.0;
};

/// A sphere of radius r [m] whose centre lies at signed height h [m] above a plane (φ = h + r t
/// at the sample of direction u, t = u·n):
///   E(h) = 2π r² ∫_{−1}^{τ} W(h + r t) dt = 2π r [Q0(δ − h + r) − Q0(δ − h − r τ)],
/// τ = clamp(m, −1, 1) (s_al = t: samples with t > m are rejected).
SpherePenalty SpherePlanePenalty(double h, double r, double m, const PenaltyParams& p);

/// A sphere of radius rA [m] on the field of a sphere of radius rB [m] at centre distance
/// d > rA [m] (φ = ρ − rB, ρ² = d² + rA² + 2 d rA t, t = u·e, e from B's centre to A's):
///   E(d) = (2π rA / d) ∫_{|d − rA|}^{ρ_hi} W(ρ − rB) ρ dρ
///        = (2π rA / d) [G(δ + rB − (d − rA)) − G(δ + rB − ρ_hi)],  G = (rB + δ) Q0 − Q1.
/// s_al = (d t + rA)/ρ grows with t (for d > rA), so the accepted samples are t <= τ with
/// ρ_hi = √(d² − (1 − m²) rA²) + m rA (the ρ where s_al = m), capped at d + rA.
SpherePenalty SphereSpherePenalty(double d, double rA, double rB, double m,
                                  const PenaltyParams& p);

}  // namespace superdex
