// The C² smoothed ramp h_{ε,δ} of the normal penalty (spec: "Frictionless Normal Penalty").
#pragma once

namespace superdex {

/// h and its first two derivatives with respect to its argument ψ = −φ (so dh/dψ = −dh/dφ).
struct RampValue {
  double h = 0.0;    ///< h_{ε,δ}(−φ) [m]
  double dh = 0.0;   ///< dh/dψ [-]
  double d2h = 0.0;  ///< d²h/dψ² [1/m]
};

/// The spec's ramp, with z = −φ − (ε − δ):
///   h = 0                                         for z <= −ε,
///   h = 3ε/16 + (1/2 + 3z/(8ε) − z³/(16ε³)) z     for |z| < ε,
///   h = z                                         for z >= ε.
/// Evaluated in the algebraically identical form with s = z + ε = δ − φ on 0 < s < 2ε,
///   h = s³(4ε − s)/(16ε³),  h' = s²(3ε − s)/(4ε³),  h'' = 3s(2ε − s)/(4ε³),
/// which has no cancellation near the start of contact. h is C² at both joins; h = 0 for φ >= δ,
/// and h = −φ − (ε − δ) (linear in penetration) for φ <= δ − 2ε.
/// phi: signed distance φ [m]; eps: smoothing half-width ε > 0 [m]; delta: threshold δ [m].
RampValue PenaltyRamp(double phi, double eps, double delta);

/// The ramp exactly in the spec's z-polynomial form (value only); for tests of the s-form.
double PenaltyRampSpecForm(double phi, double eps, double delta);

}  // namespace superdex
