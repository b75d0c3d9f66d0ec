// The derivative of one time step, assembled once and applied forward (tangents) or in reverse
// (adjoints, core/sensitivity/adjoint.h).
//
// A step maps the packed state S_n (Scene::PackState) to S_{n+1} through s implicit stages. With
// each stage's solution written as the recorded one moved in the stage's chart, q_i = q_i* ⊕ δ_i
// (δ = [δp, δθ] per dynamic body, δx per free soft node), the step is an explicit function of
// z = (S_n, δ_0, …, δ_{s−1}) and the model parameters θ:
//     ρ_i(z, θ) = r_i(q_i* ⊕ δ_i; inputs_i(S_n, δ_0..δ_{i−1}), θ)     stage residuals
//     S_{n+1}  = F(S_n, δ_0, …, δ_{s−1})                                the integrator's explicit part
// and the step's δ are those with ρ_i = 0. By the implicit function theorem, with
// J_i = ∂ρ_i/∂δ_i the stage Jacobian at the accepted solution:
//   tangent   dδ_i = −J_i⁻¹ (∂ρ_i/∂S dS + Σ_{j<i} ∂ρ_i/∂δ_j dδ_j + ∂ρ_i/∂θ dθ),
//             dS_{n+1} = ∂F/∂S dS + Σ_i ∂F/∂δ_i dδ_i;
//   adjoint   for a cotangent λ of S_{n+1}: w_i = (∂F/∂δ_i)ᵀ λ; for i = s−1 … 0:
//             μ_i = J_i⁻ᵀ w_i, w_j −= (∂ρ_i/∂δ_j)ᵀ μ_i (j < i); then
//             λ_n = (∂F/∂S)ᵀ λ − Σ_i (∂ρ_i/∂S)ᵀ μ_i,  g_θ = −Σ_i (∂ρ_i/∂θ)ᵀ μ_i.
//
// J_i is the recorded stage Jacobian with its LU factors (exact). The other partials are formed
// column by column by central differences of the step run in the tape's Inject mode (no stage
// solve: each stage residual is evaluated at q_i* ⊕ δ_i), Richardson-extrapolated as the forward
// replay of core/sensitivity/sensitivity.h is: exact in the implicit function theorem, O(η⁴) in these partials.
// Locality keeps the number of runs small: F acts on each body and soft node by itself, and a body
// or node's inputs reach only the residual rows it is coupled with in J_i (its contact partners,
// the nodes of its tets). Bodies and nodes whose reached rows do not overlap (a greedy distance-2
// colouring of the union of the stages' Jacobian graphs) are moved together in one run, and each
// changed row is attributed to the one mover that reaches it. The contact parameters of a dynamic
// rigid actor reach the same rows as its body (the pair values of its contacts) and are moved
// with its colour, one slot per parameter of that actor; those of static and soft actors are moved
// alone. A step's linearization costs
//   4 × (colours × (local coordinates + parameter slots) + other parameters)
// runs of the explicit part and the stage residuals: independent of the number of bodies at a
// fixed contact valence, of the number of initial-state parameters and of the number of rigid
// actors with fitted contact parameters. (Local coordinates: 18 per rigid body — p, v, Ṙ and the
// three tangent directions of R, the only variations of R a trajectory has — and 6 per soft node
// for each state block, plus 6 or 3 per stage. Prescribed soft nodes, which have no column in
// J_i, are moved alone.) An actor of the generic layer is moved by the groups its kind gives
// (ActorKind::DifferenceGroups: a RigidKind as the built-in body, a vector kind as one group of
// all its entries); the contact parameters of a kind of one group are moved with its colour.
#pragma once

#include <vector>

#include "core/scene.h"
#include "core/sensitivity/sensitivity.h"

namespace superdex {

class StepLinearizer {
 public:
  /// Takes one step of dt from the scene's current state, recording each stage, and forms the
  /// step's partials, in the model parameters `parameters` (initial-state kinds are ignored here:
  /// they are directions of S_n). Leaves the scene at the end of the step. False with the reason
  /// for a stage that did not converge or a singular stage Jacobian (the derivative is not
  /// defined), or invalid input; the step's report in *report either way.
  bool Linearize(Scene* scene, double dt, const std::vector<SceneParameter>& parameters,
                 StepReport* report, Error* error);

  /// dS_{n+1} for the columns of dS (rows as PackState) and dTheta (one row per parameter).
  Eigen::MatrixXd Tangent(const Eigen::MatrixXd& dS, const Eigen::MatrixXd& dTheta);
  /// λ_n and g_θ for the cotangent λ of S_{n+1}.
  void Adjoint(const Eigen::VectorXd& lambda, Eigen::VectorXd* lambdaPrevious,
               Eigen::VectorXd* parameterGradient);

  /// The partials [∂(ρ, S_{n+1}) / ∂(S_n, δ, θ)]: rows ρ_0 … ρ_{s−1}, then S_{n+1}; columns S_n,
  /// δ_0 … δ_{s−1}, θ.
  const Eigen::SparseMatrix<double>& Partials() const { return partials_; }
  /// The recorded stage Jacobian J_i.
  const Eigen::SparseMatrix<double>& StageJacobian(int i) const { return tape_.stages[i].jacobian; }
  int Stages() const { return tape_.used; }
  int Colors() const { return colors_; }
  /// Runs of the step in Inject mode for the last linearization.
  int Runs() const { return runs_; }
  /// Largest |change| of a row that no mover of its run reaches (0 when the colouring's coupling
  /// graph is complete; a diagnostic for tests).
  double Unattributed() const { return unattributed_; }

 private:
  StepTape tape_;
  Eigen::SparseMatrix<double> partials_;
  int stateSize_ = 0, numDofs_ = 0, parameters_ = 0;
  int colors_ = 0, runs_ = 0;
  double unattributed_ = 0.0;
};

}  // namespace superdex
