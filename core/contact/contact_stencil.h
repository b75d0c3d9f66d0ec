// A pair's contact contributions as stencils of 3-dof blocks, and the one place where they are
// projected to PSD and scattered into the stage's gradient, dissipative residual and matrix.
// Rigid pairs keep their fixed-size 6-dof-block path (core/contact/contact_pipeline.cpp); every
// other pair kind (soft on rigid, anything on a soft collider, and the kinds to come) writes
// ContactStencils.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <vector>

#include "energies/contact_dissipation.h"
#include "energies/psd_projection.h"
#include "energies/stencil.h"
#include "optim/stage_problem.h"

namespace superdex {

/// One stencil [q_A, q_B] of a pair's samples: the penalty's gradient and Hessian (unprojected
/// until ProjectStencil) and the dissipation's residual w J_Yᵀ ∂R/∂V and its Jacobian (with
/// ExplicitNormals the symmetric Hessian of Δt_i Σ w R; otherwise ∂residual/∂q, not symmetric).
/// Its dofs: A's part (a soft face's three nodes, aFace; or a rigid body's [δp, δθ]), then B's
/// (a rigid collider's [δp, δθ] when dynamic, or a soft collider's tet bTet's four nodes).
struct ContactStencil {
  int aFace = -1;  ///< soft A: its boundary face; −1 for a rigid A
  int bTet = -1;   ///< soft collider B: its tet; −1 otherwise
  /// Pairs of the generic actor layer (core/contact/kind_contact.h): the stencil's 3-dof blocks'
  /// stage offsets (−1: a block without unknowns), A's then B's.
  int blocks = 0;
  int offs[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
  bool penaltyActive = false, dissipationActive = false;
  StencilVector penaltyGradient, dissipationResidual;  ///< [N, N·m]
  StencilMatrix penaltyHessian, dissipationJacobian;
};

/// A pair's stencils (their capacity kept from evaluation to evaluation) and its counts.
struct PairStencils {
  double penaltyValue = 0.0;      ///< Σ w W [J]
  double dissipationValue = 0.0;  ///< Δt_i Σ w R [J]
  int activeSamples = 0;          ///< penalty samples with φ < δ
  int dissipativeSamples = 0;
  double minPhi = INFINITY;       ///< [m]
  double maxCoulombRatio = 0.0;
  std::vector<ContactStencil> stencils;
  int count = 0;                  ///< valid entries of `stencils`

  /// Clears the counts and the stencils (their capacity stays).
  void Reset();
  /// The next stencil's slot, set to `face`, `tet`, inactive, its parts zero on n dofs (order 1:
  /// the vectors, 2: also the matrices). It counts only once Keep() is called.
  ContactStencil& Slot(int face, int tet, int n, int order);
  void Keep() { ++count; }
  /// Counts one dissipative sample of weight w [m²] at step dt [s]: its Δt_i w R [J], and its
  /// ‖T_C‖/(μ λ̂_n) (with friction).
  void AddDissipative(double w, double dt, const DissipationDensity& D, double mu,
                      double lambdaHat) {
    ++dissipativeSamples;
    dissipationValue += w * dt * D.R;
    if (mu > 0.0 && lambdaHat > 0.0)
      maxCoulombRatio = std::max(maxCoulombRatio, D.coulomb.norm() / (mu * lambdaHat));
  }
};

/// The projection rule of every contact stencil's matrix (rigid pairs' fixed-size ones too): in a
/// potential stage (no dissipation, or ExplicitNormals) the dissipation Hessian joins the penalty
/// Hessian and, with a projection, their sum is projected to PSD (PsdProjection::Abs: |λ|, else
/// max(λ, 0)); in the residual modes the penalty Hessian is projected and the dissipation Jacobian
/// is kept as it is (the caller appends it separately).
template <typename Matrix>
void ProjectContactHessian(bool penaltyActive, bool dissipationActive, bool potential,
                           PsdProjection projection, const Matrix& dissipationJacobian,
                           Matrix* hessian) {
  if (potential && dissipationActive) *hessian += dissipationJacobian;
  if ((penaltyActive || (potential && dissipationActive)) && projection != PsdProjection::None)
    ProjectToPsd(hessian, projection == PsdProjection::Abs);
}

/// ProjectContactHessian on a stencil.
inline void ProjectStencil(bool potential, PsdProjection projection, ContactStencil* s) {
  ProjectContactHessian(s->penaltyActive, s->dissipationActive, potential, projection,
                        s->dissipationJacobian, &s->penaltyHessian);
}

/// Adds the stencil's penalty gradient into *gradient and its dissipative residual into
/// *dissipationResidual (null: into *gradient), and with `triplets` appends its matrix: the
/// (projected) Hessian, plus the dissipation Jacobian in the residual modes, 3 × 3 block by block
/// at offs[b] (−1: a block without dofs, e.g. a prescribed node), nonzero entries only.
void ScatterStencil(const ContactStencil& s, const int* offs, int blocks, bool potential,
                    Eigen::VectorXd* gradient, Eigen::VectorXd* dissipationResidual,
                    std::vector<Eigen::Triplet<double>>* triplets);

}  // namespace superdex
