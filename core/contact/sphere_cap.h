// A quadrature on the active cap of a sphere against a plane's or a sphere's field, for the
// dissipation of a sphere whose penalty is integrated exactly (SurfaceIntegral::ExactSphere,
// energies/sphere_penalty.h).
//
// On such a field φ depends on the sample's polar coordinate t = u·e alone (u the sample's unit
// direction from A's centre; e the plane's normal, or the unit vector from B's centre to A's;
// the deepest sample has t = −1), and the area element is r² dt dψ for the azimuth ψ about e.
// The active cap (φ < δ, alignment s_al <= m) is an interval −1 <= t <= hi; the load λ_n of the
// spec's ramp is a polynomial of degree 7 in s = δ − φ on the ramp (0 < s < 2ε) and linear
// beyond, with a kink between, so the interval is split at s = 2ε and each panel gets its own
// Gauss–Legendre rule in t (the ramp kRampPoints, the linear part kLinearPoints), times
// kAzimuths equally spaced azimuths:
//   ∫_cap f dA ≈ Σ_panel Σ_i Σ_j r² w_i (2π / kAzimuths) f(t_i, ψ_j).
// On a plane s is linear in t, so the load's integral (the normal force) is exact; on a sphere's
// field s(t) = rB + δ − √(d² + r² + 2 d r t) is smooth and the rule converges with its degree.
// The azimuth rule integrates trigonometric polynomials of degree < kAzimuths exactly: a rigid
// body's slip velocity is affine in the point, so uniform sliding and rolling are resolved; the
// friction's ρ(V_t) is smooth in ψ except where V_t crosses V_f.
#pragma once

#include <Eigen/Core>

#include "core/model/rigid_body.h"
#include "energies/normal_penalty.h"

namespace superdex {

/// B's field about a sphere of radius r [m] centred at Y (B's frame) where it depends on one
/// coordinate x: a plane's, or a box face's where every point of the sphere the plane's field
/// puts below δ lies in the face's region (there the box's exact distance is the face plane's,
/// and elsewhere both are >= δ, φ_box >= φ_plane); or a sphere's at centre distance x > r (the
/// closed forms' range, energies/sphere_penalty.h). Otherwise None (the samples carry it).
struct AxialField {
  enum class Kind { None, Plane, Sphere };
  Kind kind = Kind::None;
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();  ///< ∇_Y x: the face's normal, or Y/|Y|
  double x = 0.0;       ///< the centre's height over the plane, or its distance from B's [m]
  double radius = 0.0;  ///< B's sphere radius [m]
};
/// m: the maximum alignment that bounds the cap (t <= m on a plane).
AxialField AxialFieldAt(const RigidCollider& f, const Eigen::Vector3d& Y, double r, double m,
                        const PenaltyParams& p);

/// The cap's interval in t: [lo, hi] with the ramp's start at `split` (s = 2ε; outside
/// (lo, hi) when one panel only). Empty when hi <= lo.
struct SphereCap {
  double lo = -1.0;
  double split = -1.0;
  double hi = -1.0;
  bool Empty() const { return !(hi > lo); }
};

/// A sphere of radius r [m] whose centre is at height h [m] above a plane, maximum alignment m:
/// s = δ − h − r t, hi = min(m, (δ − h)/r) (the alignment s_al = t).
SphereCap PlaneCap(double h, double r, double m, const PenaltyParams& p);

/// A sphere of radius rA [m] on the field of a sphere of radius rB [m] at centre distance d > rA
/// [m]: ρ² = d² + rA² + 2 d rA t, s = rB + δ − ρ, hi where ρ = rB + δ or at the alignment cut
/// ρ_hi = √(d² − (1 − m²) rA²) + m rA (energies/sphere_penalty.h).
SphereCap SphereFieldCap(double d, double rA, double rB, double m, const PenaltyParams& p);

/// The rule's sizes: Gauss points on the ramp's panel and on the linear panel, and azimuths.
constexpr int kCapRampPoints = 4;
constexpr int kCapLinearPoints = 3;
constexpr int kCapAzimuths = 4;
constexpr int kSphereCapMaxSamples = (kCapRampPoints + kCapLinearPoints) * kCapAzimuths;

/// The cap's samples of a sphere of radius r [m] centred at its body origin, with axis e (unit,
/// in the frame the cap was found in) and `toBody` that frame's rotation into the body frame:
/// X = toBody r u, normal toBody u, weight r² w_i 2π / kAzimuths [m²]. Writes at most
/// kSphereCapMaxSamples into out; returns their number (0 for an empty cap).
int SphereCapSamples(const SphereCap& cap, double r, const Eigen::Vector3d& e,
                     const Eigen::Matrix3d& toBody, SurfaceSample* out);

}  // namespace superdex
