// The rigid chain of the contact assembler (core/contact/kind_contact.h): a function of the
// pullback of a rigid body's sample into a rigid collider's frame, chained through both bodies'
// rotation retractions, per sample and as regrouped moments; the sample records; and the step
// limit of rigid pairs.
#pragma once

#include <vector>

#include "core/model/rigid_body.h"
#include "energies/normal_penalty.h"
#include "energies/stencil.h"

namespace superdex {

/// The stencil of one rigid body A's sample on a rigid collider B:
///   [δp_A, δθ_A]            (6 dofs, B static) or
///   [δp_A, δθ_A, δp_B, δθ_B] (12 dofs, B dynamic),
/// with the retractions p ← p + δp, R ← exp([δθ]×) R.
///
/// Kinematics of one sample (X in A's body frame): r = R_A X, x = p_A + r, d = x − p_B,
/// Y = R_Bᵀ d (the pullback X_B(x)), φ = Φ_B(Y), G = ∇Φ_B(Y), world normal n = R_B G.
///   ∇φ = [n, r × n, −n, −d × n]   (balanced: equal and opposite forces at x, zero net torque)
///   ∇²φ = J_xᵀ (R_B ∇²Φ_B R_Bᵀ) J_x + S,  J_x = [I, −[r]×, −I, [d]×],
/// with S the curvature of the retractions contracted with n:
///   S_θAθA = ½(n rᵀ + r nᵀ) − (n·r) I,   S_θBθB = ½(n dᵀ + d nᵀ) − (n·d) I,
///   S_θBpA = [n]×,  S_θBpB = −[n]×,  S_θBθA = (n·r) I − r nᵀ   (and their transposes).

/// One active contact sample (its penalty, φ < δ, or its dissipation active, not rejected), in the
/// world frame, for reporting. The force on A is w_q (t_n + t_f + t_d); B takes its opposite.
struct ContactSampleRecord {
  int colliding = -1;        ///< actor index of A (filled by the pipeline)
  int collider = -1;         ///< actor index of B
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< x_A [m]
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< R_B N_B: the collider field's unit direction
  double phi = 0.0;          ///< φ_B(x_A) [m] (NaN for a sample with dissipation only, not read)
  double lambdaN = 0.0;      ///< normal-load coefficient λ_n [Pa]
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();  ///< normal traction on A, t_n = λ_n R_B G_B [Pa]
  /// The dissipation's traction on A, −R_B ∂R/∂V split as the density is: friction t_f (Coulomb and
  /// viscous, tangential) and normal damping t_d [Pa]; zero without the stage that produced the
  /// state (Scene::ContactSamples).
  Eigen::Vector3d friction = Eigen::Vector3d::Zero(), damping = Eigen::Vector3d::Zero();
  double weight = 0.0;       ///< reference-area weight w_q [m²]
  int face = -1;             ///< soft colliding actor: its boundary face; −1 for rigid actors
};

/// Round-off allowance of the alignment test: a sample is rejected when s > m + this. A face
/// exactly perpendicular to the collider's surface has s = 0 up to round-off.
constexpr double kAlignmentRoundoff = 1e-9;

/// Chains a scalar function f(Y) of the pullback Y = R_Bᵀ(p_A + r − p_B), r = R_A X, through the
/// rigid retractions (the stencil above): adds w·J_Yᵀ g_Y = w·[n, r × n, −n, −d × n] (n = R_B g_Y,
/// d = p_A + r − p_B) to *grad and, if hess is not null, w·(J_xᵀ R_B H_Y R_Bᵀ J_x + S(n)) with S the
/// retraction curvature of the comment above (n in place of the normal).
void AddFunctionOfPullback(const Eigen::Vector3d& r, const Eigen::Vector3d& d,
                           const Eigen::Matrix3d& RB, const Eigen::Vector3d& gY,
                           const Eigen::Matrix3d* HY, bool bDynamic, double w,
                           StencilVector* grad, StencilMatrix* hess);
/// A rigid pair's stencil with fixed sizes (12 entries; the first 6 with a static B): the pair
/// sweeps accumulate into these, whose 3 × 3 blocks have compile-time strides.
using PairVector = Eigen::Matrix<double, 12, 1>;
using PairMatrix = Eigen::Matrix<double, 12, 12>;
/// As above, into a pair's fixed-size stencil (the same sums in the same order).
void AddFunctionOfPullback(const Eigen::Vector3d& r, const Eigen::Vector3d& d,
                           const Eigen::Matrix3d& RB, const Eigen::Vector3d& gY,
                           const Eigen::Matrix3d* HY, bool bDynamic, double w, PairVector* grad,
                           PairMatrix* hess);

/// The Hessian part of AddFunctionOfPullback summed over a pair's samples as moments in B's
/// frame, mapped to the stencil once per pair. With r_B = R_Bᵀ r (= Y − Y_A, Y_A = R_Bᵀ(p_A − p_B)),
/// K = −[r_B]× and c = p_A − p_B (world, so that d = c + r):
///   H₀ = Σ w H_Y,  H₁ = Σ w H_Y K,  H₂ = Σ w Kᵀ H_Y K,  P = Σ w g_Y r_Bᵀ,  N = Σ w g_Y,
/// and with A_k = R_B H_k R_Bᵀ, the stencil blocks are the per-sample sums of AddFunctionOfPullback
/// regrouped: e.g. Σ Hw [d]× = A₀ [c]× − A₁, Σ [d]×ᵀ Hw [d]× = [c]×ᵀA₀[c]× − [c]×ᵀA₁ − A₁ᵀ[c]× + A₂,
/// and the retraction curvature from R_B P R_Bᵀ and R_B N. Per sample 2 skew products and two
/// outer products instead of the 12 × 12 stencil's 16 blocks; the same Hessian up to rounding
/// (tests/core/test_rigid_contact.cpp). H_Y must be symmetric.
class PairHessianSums {
 public:
  void Add(const Eigen::Vector3d& rB, const Eigen::Vector3d& gY, const Eigen::Matrix3d& HY,
           double w);
  /// Adds the summed Hessian to *hess (the first 6 × 6 block with a static B).
  void AddTo(const Eigen::Matrix3d& RB, const Eigen::Vector3d& c, bool bDynamic,
             PairMatrix* hess) const;
  bool Empty() const { return empty_; }
  /// Starts the sums again (they are zeroed at the next Add).
  void Clear() { empty_ = true; }

 private:
  // Valid once a sample was added (a stencil's sums are cleared at every pair: zeroing them only
  // where a sample comes keeps a pair without contact free of that cost).
  Eigen::Matrix3d H0_, H1_, H2_, P_;
  Eigen::Vector3d N_;
  bool empty_ = true;
};

}  // namespace superdex
