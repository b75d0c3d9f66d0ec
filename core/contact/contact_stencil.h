// A pair's contact contributions as stencils of 3-dof blocks, and the one place where they are
// projected to PSD and scattered into the stage's gradient, dissipative residual and matrix.
// Stencils over rigid bodies' [δp, δθ] (rigid pairs, kinds' sample bodies on rigid frames) scatter
// as dense 6 × 6 blocks by ScatterStencil6; every other (soft nodes, translating frames) by
// ScatterStencil, as triplets.
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
#include "optim/triplet_assembly.h"

namespace superdex {

/// One stencil [q_A, q_B] of a pair's samples: the penalty's gradient and Hessian (unprojected
/// until ProjectStencil) and the dissipation's residual w J_Yᵀ ∂R/∂V and its Jacobian (with
/// ExplicitNormals the symmetric Hessian of Δt_i Σ w R; otherwise ∂residual/∂q, not symmetric).
/// Its dofs: A's part (a soft face's three nodes, aFace; or a rigid body's [δp, δθ]), then B's
/// (a rigid collider's [δp, δθ] when dynamic, or a soft collider's tet bTet's four nodes).
/// Storage for at most Max dofs, in the object itself (no heap in the inner loops).
template <int Max>
struct BasicContactStencil {
  int aFace = -1;  ///< soft A: its boundary face; −1 for a rigid A
  int bTet = -1;   ///< soft collider B: its tet; −1 otherwise
  /// Pairs of the generic actor layer (core/contact/kind_contact.h): the stencil's 3-dof blocks'
  /// stage offsets (−1: a block without unknowns), A's then B's.
  int blocks = 0;
  int offs[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
  bool penaltyActive = false, dissipationActive = false;
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, Max, 1> penaltyGradient, dissipationResidual;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, Max, Max> penaltyHessian,
      dissipationJacobian;
};
/// Any pair's stencil (up to kMaxStencil dofs).
using ContactStencil = BasicContactStencil<kMaxStencil>;
/// Two rigid bodies' stencil (12 dofs at most). The pipeline keeps one per rigid pair from
/// evaluation to evaluation, so its storage is a quarter of ContactStencil's (2.4 kB instead of
/// 9.2 kB per stencil): on a pile's thousands of pairs, the memory the sweeps touch.
using RigidPairStencil = BasicContactStencil<kMaxSmallStencil>;

/// A pair's stencils (their capacity kept from evaluation to evaluation) and its counts.
template <typename Stencil>
struct BasicPairStencils {
  double penaltyValue = 0.0;      ///< Σ w W [J]
  double dissipationValue = 0.0;  ///< Δt_i Σ w R [J]
  int activeSamples = 0;          ///< penalty samples with φ < δ
  int dissipativeSamples = 0;
  double minPhi = INFINITY;       ///< [m]
  double maxCoulombRatio = 0.0;
  std::vector<Stencil> stencils;
  int count = 0;                  ///< valid entries of `stencils`

  /// Clears the counts and the stencils (their capacity stays).
  void Reset() {
    penaltyValue = dissipationValue = 0.0;
    activeSamples = dissipativeSamples = 0;
    minPhi = INFINITY;
    maxCoulombRatio = 0.0;
    count = 0;
  }
  /// The next stencil's slot, set to `face`, `tet`, inactive, its parts zero on n dofs (order 1:
  /// the vectors, 2: also the matrices). It counts only once Keep() is called.
  Stencil& Slot(int face, int tet, int n, int order) {
    if (count == static_cast<int>(stencils.size())) stencils.emplace_back();
    Stencil& s = stencils[count];
    s.aFace = face;
    s.bTet = tet;
    s.penaltyActive = s.dissipationActive = false;
    if (order >= 1) {
      s.penaltyGradient.setZero(n);
      s.dissipationResidual.setZero(n);
    }
    if (order >= 2) {
      s.penaltyHessian.setZero(n, n);
      s.dissipationJacobian.setZero(n, n);
    }
    return s;
  }
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
  /// Becomes a copy of `from`: its counts and its kept stencils, with the parts of an evaluation
  /// of that order that the scatter reads (each stencil's dofs within this one's storage): the
  /// active terms' vectors, and the Hessian where a term is active, the dissipation Jacobian only
  /// in a residual mode (`potential` false; a potential's is summed into the Hessian, projected).
  template <typename From>
  void CopyFrom(const BasicPairStencils<From>& from, int order, bool potential) {
    penaltyValue = from.penaltyValue;
    dissipationValue = from.dissipationValue;
    activeSamples = from.activeSamples;
    dissipativeSamples = from.dissipativeSamples;
    minPhi = from.minPhi;
    maxCoulombRatio = from.maxCoulombRatio;
    count = 0;
    for (int e = 0; e < from.count; ++e) {
      if (count == static_cast<int>(stencils.size())) stencils.emplace_back();
      Stencil& d = stencils[count++];
      const From& s = from.stencils[e];
      d.aFace = s.aFace;
      d.bTet = s.bTet;
      d.blocks = s.blocks;
      std::copy(s.offs, s.offs + 8, d.offs);
      d.penaltyActive = s.penaltyActive;
      d.dissipationActive = s.dissipationActive;
      if (order >= 1 && s.penaltyActive) d.penaltyGradient = s.penaltyGradient;
      if (order >= 1 && s.dissipationActive) d.dissipationResidual = s.dissipationResidual;
      if (order >= 2 && (s.penaltyActive || s.dissipationActive))
        d.penaltyHessian = s.penaltyHessian;
      if (order >= 2 && !potential && s.dissipationActive)
        d.dissipationJacobian = s.dissipationJacobian;
    }
  }
};
using PairStencils = BasicPairStencils<ContactStencil>;
using RigidPairStencils = BasicPairStencils<RigidPairStencil>;

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
template <int Max>
void ProjectStencil(bool potential, PsdProjection projection, BasicContactStencil<Max>* s) {
  ProjectContactHessian(s->penaltyActive, s->dissipationActive, potential, projection,
                        s->dissipationJacobian, &s->penaltyHessian);
}

/// Adds the stencil's penalty gradient into *gradient and its dissipative residual into
/// *dissipationResidual (null: into *gradient), by groups of Size dofs at the stage offsets
/// offs[g] (−1: a group without dofs).
template <int Size, typename Stencil>
void ScatterStencilVectors(const Stencil& s, const int* offs, int groups,
                           Eigen::VectorXd* gradient, Eigen::VectorXd* dissipationResidual) {
  Eigen::VectorXd* dr = dissipationResidual ? dissipationResidual : gradient;
  for (int g = 0; g < groups; ++g) {
    if (offs[g] < 0) continue;
    if (s.penaltyActive)
      gradient->segment<Size>(offs[g]) += s.penaltyGradient.template segment<Size>(Size * g);
    if (s.dissipationActive)
      dr->segment<Size>(offs[g]) += s.dissipationResidual.template segment<Size>(Size * g);
  }
}

/// Adds the stencil's penalty gradient into *gradient and its dissipative residual into
/// *dissipationResidual (null: into *gradient), and with `triplets` appends its matrix: the
/// (projected) Hessian, plus the dissipation Jacobian in the residual modes, 3 × 3 block by block
/// at offs[b] (−1: a block without dofs, e.g. a prescribed node), nonzero entries only.
template <typename Stencil>
void ScatterStencil(const Stencil& s, const int* offs, int blocks, bool potential,
                    Eigen::VectorXd* gradient, Eigen::VectorXd* dissipationResidual,
                    std::vector<Eigen::Triplet<double>>* triplets) {
  ScatterStencilVectors<3>(s, offs, blocks, gradient, dissipationResidual);
  if (!triplets) return;
  const bool withH = s.penaltyActive || (potential && s.dissipationActive);
  const bool withJ = !potential && s.dissipationActive;
  for (int bi = 0; bi < blocks; ++bi) {
    if (offs[bi] < 0) continue;
    for (int bj = 0; bj < blocks; ++bj) {
      if (offs[bj] < 0) continue;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) {
          double v = 0.0;
          if (withH) v += s.penaltyHessian(3 * bi + r, 3 * bj + c);
          if (withJ) v += s.dissipationJacobian(3 * bi + r, 3 * bj + c);
          if (v != 0.0) triplets->emplace_back(offs[bi] + r, offs[bj] + c, v);
        }
    }
  }
}

/// ScatterStencil for a stencil over rigid bodies: `groups` 6-dof groups [δp, δθ] at the stage
/// offsets offs6[g] (−1: a body without dofs), each two consecutive 3-dof blocks of the stencil;
/// with `blocks`, the matrices are appended as dense 6 × 6 blocks (the Hessian, then in the
/// residual modes the dissipation Jacobian), entries as they are.
template <typename Stencil>
void ScatterStencil6(const Stencil& s, const int* offs6, int groups, bool potential,
                     Eigen::VectorXd* gradient, Eigen::VectorXd* dissipationResidual,
                     std::vector<DenseBlock6>* blocks) {
  ScatterStencilVectors<6>(s, offs6, groups, gradient, dissipationResidual);
  if (!blocks) return;
  auto append = [&](const auto& M) {
    for (int gi = 0; gi < groups; ++gi) {
      if (offs6[gi] < 0) continue;
      for (int gj = 0; gj < groups; ++gj) {
        if (offs6[gj] < 0) continue;
        DenseBlock6& b = blocks->emplace_back();
        b.row = offs6[gi];
        b.col = offs6[gj];
        for (int c = 0; c < 6; ++c)
          for (int r = 0; r < 6; ++r) b.v[6 * c + r] = M(6 * gi + r, 6 * gj + c);
      }
    }
  };
  if (s.penaltyActive || (potential && s.dissipationActive)) append(s.penaltyHessian);
  if (!potential && s.dissipationActive) append(s.dissipationJacobian);
}

/// The 6-dof groups of a stencil's 3-dof block offsets (ScatterStencil6's offs6): whether every
/// pair of consecutive blocks covers six consecutive dofs (offs[2g + 1] = offs[2g] + 3, or both
/// −1), as a rigid sample body's [δp, δθ] and a rigid collider frame's do.
inline bool SixDofGroups(const int* offs, int blocks, int* offs6) {
  if (blocks % 2 != 0) return false;
  for (int g = 0; 2 * g < blocks; ++g) {
    const int p = offs[2 * g], t = offs[2 * g + 1];
    if (p < 0 ? t >= 0 : t != p + 3) return false;
    offs6[g] = p < 0 ? -1 : p;
  }
  return true;
}

}  // namespace superdex
