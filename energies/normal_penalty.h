// Frictionless normal penalty energy density W = (k/2) h_{ε,δ}(−φ)² (spec: "Frictionless Normal
// Penalty"), per unit reference area of the colliding actor.
#pragma once

#include "energies/stencil.h"

namespace superdex {

/// Parameters of one contact pair after combination (core/model/contact_params.h).
struct PenaltyParams {
  double k = 1e9;         ///< penalty coefficient k [Pa/m]
  double eps = 0.005;     ///< smoothing half-width ε [m]
  double delta = 0.001;   ///< contact threshold δ [m]
};

/// W and its derivatives with respect to φ:
///   W = (k/2) h²                [J/m² = Pa·m]
///   dW/dφ = −k h h'             [Pa]
///   d²W/dφ² = k (h'² + h h'')   [Pa/m]  (>= 0: W is convex in φ)
/// and the normal-load coefficient λ_n = k h h' = −dW/dφ [Pa] of T_n = λ_n G_B.
struct PenaltyDensity {
  double W = 0.0;
  double dW = 0.0;
  double d2W = 0.0;
  double lambdaN = 0.0;
};
PenaltyDensity NormalPenaltyDensity(double phi, const PenaltyParams& p);

/// Chains W through φ(q) on a stencil of degrees of freedom q:
///   ∇W = W'(φ) ∇φ,   ∇²W = W''(φ) ∇φ ∇φᵀ + W'(φ) ∇²φ,
/// scaled by the quadrature weight w [m²]. Adds w·W to *value, w·∇W to *grad and, if hess is not
/// null, w·∇²W to *hess (hess must be sized; hessPhi is used only then).
void AddNormalPenalty(const PenaltyDensity& density, double weight, const StencilVector& gradPhi,
                      const StencilMatrix& hessPhi, double* value, StencilVector* grad,
                      StencilMatrix* hess);

}  // namespace superdex
