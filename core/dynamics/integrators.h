// The integrator family as data (spec: IntegrationMethod). Every stage is an incremental-potential
// stage in q with v = (q − q⁰)/Δt_i; a method only says how the stage starts (q⁰, v⁰), its Δt_i,
// and how the step's end state combines the stages.
//
// Diagonally implicit Runge–Kutta (Butcher A lower triangular, a_ii = γ_i > 0, weights b), applied
// to q̇ = v, M v̇ = F: stage i starts at
//   q⁰_i = q_n + h Σ_{j<i} a_ij V_j,   v⁰_i = v_n + h Σ_{j<i} a_ij K_j,   Δt_i = h a_ii,
// its solution Q_i gives V_i = (Q_i − q⁰_i)/Δt_i and K_i = (V_i − v⁰_i)/Δt_i, and the step ends at
//   q_{n+1} = q_n + h Σ b_i V_i,   v_{n+1} = v_n + h Σ b_i K_i.
// Multistep BDF-k with variable steps: with nodes τ_0 = t_{n+1}, τ_j = t_{n+1−j} and the Lagrange
// basis ℓ_j on them, v_{n+1} = Σ_j ℓ'_j(τ_0) q_{n+1−j}, i.e. q_{n+1} = q⁰ + Δt v_{n+1} with
//   Δt = 1/ℓ'_0(τ_0),  q⁰ = −Δt Σ_{j>=1} ℓ'_j(τ_0) q_{n+1−j}   (weights summing to 1),
// and the same for v.
//
// Rigid rotations (core/scene.cpp) live in the material-point embedding R ∈ R^{3×3}, where the
// inertia is quadratic; stage solutions are rotations, stage starts are affine combinations. Three
// rules keep every method at its order on a tumbling body (measured, tests/core/
// test_integrator_tumbling.cpp): (1) each stage velocity V_i is replaced by the tangent velocity
// [ω_i] Q_i with the same spin momentum (J-weighted projection); (2) the end rotation is the last
// stage for stiffly accurate methods, else the polar factor of R_n + h Σ b_i V_i; (3) the spin
// momentum is integrated as L̇ = τ with the method's weights, τ_i the stage's torque, and the end
// velocity is corrected along [δω] R_{n+1} to carry it (exact angular momentum for a free body,
// exact conservation for balanced pair torques). Without (1) every DIRK fell to order 1; with
// rotations combined in the Lie algebra, exp(Σ w_i log(Q_i R_nᵀ)) R_n, DIRK23 fell to order 1.
//
// While its history fills, BDF2 takes one Backward Euler step and BDF3 takes
// DIRK33 steps (a Backward Euler start would cap BDF3 at second order).
#pragma once

#include <vector>

#include "core/model/enums.h"

namespace superdex {

constexpr int kMaxDirkStages = 3;

struct DirkTableau {
  int stages = 1;
  double a[kMaxDirkStages][kMaxDirkStages] = {};
  double b[kMaxDirkStages] = {};
  bool stifflyAccurate = false;   ///< b = last row of A: the end state is the last stage
  int order = 1;
};

/// True for BDF2 and BDF3 (BackwardEuler is run as the one-stage DIRK).
bool IsMultistep(IntegrationMethod m);
/// The number of steps k of a BDF method (1 for the others).
int BdfSteps(IntegrationMethod m);
/// The tableau of a one-step method (BackwardEuler, the DIRKs, the symplectic DIRKs).
const DirkTableau& TableauOf(IntegrationMethod m);
/// The order the method is designed for (the issue table): 1, 2 or 3.
int DesignOrder(IntegrationMethod m);

/// BDF weights for the times t_{n+1} > t_n > ... (times[0] = t_{n+1}, k = times.size() − 1 >= 1):
/// returns Δt and fills weights[j−1] (j = 1..k) with the weights of q_{n+1−j} in q⁰.
double BdfCoefficients(const std::vector<double>& times, std::vector<double>* weights);

}  // namespace superdex
