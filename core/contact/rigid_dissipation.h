// Stage-discrete contact dissipation between a colliding rigid actor's surface samples and a rigid
// collider (spec: "Friction and Damping", "Stage-Discrete Dissipation"), as the contact assembler
// (core/contact/kind_contact.h) evaluates it, and the regrouped sums of its residual Jacobian.
//
// Per sample (X, n_A in A's body frame, quadrature weight w [m²]):
//   Y  = R_Bᵀ (p_A + R_A X − p_B)            current pullback X_B,i(x_A,i)             [m]
//   Y⁰ = (R⁰_B)⁻¹ (p⁰_A + R⁰_A X − p⁰_B)     stage-start pullback X⁰_B,i(x⁰_A,i)       [m]
//   V_rel = (Y − Y⁰)/Δt_i                                                              [m/s]
// x⁰ is the integrator's stage-start state, the q⁰ of v = (q − q⁰)/Δt_i. For multistep and
// multistage methods it is an affine combination of poses (R⁰ need not be a rotation; its exact
// inverse is used), an extrapolation rather than a configuration the bodies occupied. The
// stage-start *geometry* (normals, alignment and normal load, and the distance the reconstructed
// mode extrapolates from) is therefore taken at the last configuration the bodies actually had,
// x_n = (p_n, R_n), with pullback Y_n = R_n,Bᵀ (p_n,A + R_n,A X − p_n,B). For single-stage
// one-step methods (BackwardEuler, SymplecticDIRK12) x_n = x⁰. Extrapolated geometry would feed the
// strongly convex load λ_n(φ) with an amplified copy of any contact chatter and bias the mean
// friction (measured: +3.4% on a sliding cube under BDF2).
// The stage contributes Δt_i Σ w R(V_rel) with λ̂_n, N taken per DissipationMode:
//   ExplicitNormals      N, alignment, λ_n from the stage-start geometry Y_n (φ⁰ = Φ_B(Y_n));
//                        the contact set is the samples with φ⁰ < δ. Exact potential: the residual is
//                        ∇_q(Δt_i Σ w R) and the Hessian is its exact (symmetric) second derivative.
//   ReconstructedLoad    (default) N, alignment from the current Y; λ_n at the stage-start
//                        distance reconstructed to first order, φ⁰ ≈ Φ(Y) + G(Y)·(Y_n − Y).
//   ImplicitLoad         N, alignment and λ_n from the current Y.
// In the last two modes only ∂R/∂V enters the residual (r = w J_Yᵀ ∂R/∂V); it is not a gradient.
// Its Jacobian, including the dependence of λ̂_n and N on the state, is computed exactly by
// forward-mode automatic differentiation of the world forces and torques.
#pragma once

#include "core/model/rigid_body.h"
#include "core/contact/rigid_contact.h"
#include "core/contact/dissipation_setup.h"
#include "core/contact/slip_tape.h"
#include "energies/contact_dissipation.h"
#include "energies/normal_penalty.h"
#include "energies/stencil.h"

namespace superdex {


/// Σ over a pair's samples of w ∂(J_Yᵀ f)/∂δ — the stencil rows [df; [r]× df − [f]× dr; −df;
/// [f]× dd − [d]× df] of a sample force f (world) with differential df (δ = [δp_A, δθ_A, δp_B,
/// δθ_B]), dr = −[r]× δθ_A, dd = δp_A − [r]× δθ_A − δp_B — for a current-geometry mode's force
/// f = R_B g(Y, N_A), whose differential is df = [R_B G_Y R_Bᵀ, −R_B G_Y R_Bᵀ[r]× − R_B G_N R_Bᵀ[n]×,
/// −R_B G_Y R_Bᵀ, R_B G_Y R_Bᵀ[d]× + R_B G_N R_Bᵀ[n]× − [f]×] (CurrentModeLinearization's g, G_Y, G_N),
/// accumulated as moments in B's frame and mapped to the stencil once per pair. With S = [r_B]×,
/// M = w G_Y, Q = w G_N [n_B]×, F = w [g]× per sample: Σ M, Σ MS, Σ SM, Σ SMS, Σ Q, Σ SQ, Σ F,
/// Σ FS, Σ SF, rotated by R_B, and [d]× = [c]× + [r]× (c = p_A − p_B) regrouped. Equal to the
/// per-sample stencil rows up to rounding (tests/core/test_rigid_dissipation.cpp).
class PairForceJacobianSums {
 public:
  /// With a static B only the first 6 × 6 block is formed, and Σ F, Σ SF (its columns) are skipped.
  explicit PairForceJacobianSums(bool bDynamic) : bDynamic_(bDynamic) {}
  /// Starts the sums again for a B that is dynamic or not (zeroed at the next Add).
  void Clear(bool bDynamic) {
    bDynamic_ = bDynamic;
    empty_ = true;
  }
  /// One sample: r_B = R_Bᵀ r, n_B = R_Bᵀ n_w (the kernel's N_A), the kernel's g, G_Y, G_N.
  void Add(const Eigen::Vector3d& rB, const Eigen::Vector3d& nB, const Eigen::Vector3d& g,
           const Eigen::Matrix3d& GY, const Eigen::Matrix3d& GN, double w);
  /// Adds the summed Jacobian to *J (the first 6 × 6 block with a static B).
  void AddTo(const Eigen::Matrix3d& RB, const Eigen::Vector3d& c, PairMatrix* J) const;

 private:
  // Valid once a sample was added (zeroed there, as PairHessianSums's).
  Eigen::Matrix3d M_, MS_, SM_, SMS_, Q_, SQ_, F_, FS_, SF_;
  bool bDynamic_;
  bool empty_ = true;
};


}  // namespace superdex
