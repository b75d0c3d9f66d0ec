// The stage terms of one soft actor (everything but contact), on its free nodes:
//   Φ_soft(x) = Σ_a m_a/(2Δt_i²) |x_a − x̂_a|²          inertia            [J]
//             − Σ_a m_a g·x_a                            gravity            [J]
//             + Σ_t V_t Ψ(F_t)                           stable neo-Hookean [J]
//             + β/(2Δt_i) Σ_t (x_t − x⁰_t)ᵀ K_t (x_t − x⁰_t)   stiffness damping Δt_i R [J]
// with x̂ = x⁰ + Δt_i v⁰, m_a the lumped node masses [kg], K_t the tet's PSD-projected elastic
// Hessian at the stage's predictor x̂ [N/m], β [s]. The damping term is Δt_i times the Rayleigh
// dissipation R = β/2 vᵀ K v, v = (x − x⁰)/Δt_i: with K frozen for the stage it is an exact
// quadratic potential (force −β K v). Freezing K at the predictor, an O(Δt²) approximation of the
// stage configuration, keeps the damping force second-order accurate; frozen at x_n (O(Δt)) it
// made every method first order. Measured with β = 0.002 s (tests/core/
// test_integrator_order_soft.cpp): BDF2, DIRK22, SymplecticDIRK12 order 2.0; DIRK33 2.7 (third
// order is not guaranteed with β > 0). Prescribed nodes have no dofs; their positions enter the element terms as data.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "core/model/soft_body.h"
#include "optim/stage_problem.h"

namespace superdex {

/// One soft actor's data for one stage.
struct SoftStageTarget {
  Eigen::VectorXd xHat;   ///< inertial target x⁰ + Δt_i v⁰ [m]
  Eigen::VectorXd x0;     ///< stage start x⁰ (affine combination of states) [m]
  Eigen::VectorXd xLast;  ///< last actual configuration x_n [m]
  /// Per tet, K_t at the predictor x̂ (only when β > 0).
  std::vector<Eigen::Matrix<double, 12, 12>> dampingStiffness;
};

/// Fills target->dampingStiffness from target->xHat (no-op when β = 0).
void PrepareSoftDamping(const SoftBodyModel& model, SoftStageTarget* target);

/// Per-tet scratch reused across evaluations (no allocation after the first).
struct SoftTermScratch {
  std::vector<TetElasticTerm> terms;
};

/// Φ_soft at positions x; order >= 1 adds the gradient into *gradient at the free nodes' dofs
/// (node a: 3a, as in x); order 2 appends their Hessian triplets, element Hessians projected
/// per `projection`. Tets are evaluated in parallel and reduced in a fixed order. *minDetF (may be
/// null) receives the smallest det F.
double EvaluateSoftStageTerms(const SoftBodyModel& model, const SoftStageTarget& target, double dt,
                              const Eigen::Vector3d& gravity, const Eigen::VectorXd& x, int order,
                              PsdProjection projection, Eigen::VectorXd* gradient,
                              std::vector<Eigen::Triplet<double>>* triplets,
                              SoftTermScratch* scratch, double* minDetF = nullptr);

}  // namespace superdex
