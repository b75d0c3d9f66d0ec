// Adjoint (reverse-mode) gradients of a trajectory loss, for many parameters at once.
//
// For a loss L = Σ_{n=0}^{N} ℓ_n(S_n) over the packed states of a simulation (Scene::PackState),
// the adjoint recursion
//     λ_N = ∂ℓ_N/∂S_N,   λ_n = (∂S_{n+1}/∂S_n)ᵀ λ_{n+1} + ∂ℓ_n/∂S_n,
//     dL/dθ = Σ_n (∂S_{n+1}/∂θ)ᵀ λ_{n+1} + (∂S_0/∂θ)ᵀ λ_0
// runs backwards over the steps with the transposed products of core/sensitivity/step_linearization.h (each
// step's stages solved with J_i⁻ᵀ). Memory: one checkpoint (the scene's state and history) per
// step; the backward pass re-solves each step from its checkpoint to linearize it (the stage
// solves are deterministic, so it reproduces the forward trajectory bit for bit). Cost per step:
// one step solve plus 4 × (colours × local coordinates + model parameters) residual runs — it does
// not grow with the number of initial-state parameters, and for model parameters only by one
// residual run each. Exact in the implicit function theorem like the forward sensitivities
// (core/sensitivity/sensitivity.h), with the same O(η⁴) truncation in the partials of the explicit parts and
// of the stage residuals in their inputs, and the same non-smooth points.
#pragma once

#include <functional>
#include <vector>

#include "core/scene.h"
#include "core/sensitivity/sensitivity.h"

namespace superdex {

class AdjointSensitivity {
 public:
  /// Simulates one step per entry of dts from the scene's current state, keeping a checkpoint
  /// before each step; the per-step reports go to *reports (may be null). False, with the reason,
  /// for invalid input or a stage that did not converge (no gradient is defined through it).
  bool Run(Scene* scene, const std::vector<double>& dts, std::vector<StepReport>* reports,
           Error* error);

  /// Adds ∂ℓ_n/∂S_n into *gradient (sized StateSize), with the scene at S_n.
  using LossGradient = std::function<void(int n, Scene& scene, Eigen::VectorXd* gradient)>;

  /// dL/dθ for `parameters` (model and initial-state kinds) along the trajectory of the last Run.
  /// The scene is left at the trajectory's end.
  bool Gradient(const std::vector<SceneParameter>& parameters, const LossGradient& loss,
                Eigen::VectorXd* gradient, Error* error);

  int Steps() const { return static_cast<int>(dts_.size()); }
  /// Wall seconds of the last Run, and of the last Gradient (backward pass) split into the
  /// re-solves and linearizations and the adjoint products.
  double RunSeconds() const { return runSeconds_; }
  double GradientSeconds() const { return gradientSeconds_; }
  /// Inject-mode residual runs and the largest colour count over the steps of the last Gradient.
  long InjectRuns() const { return injectRuns_; }
  int MaxColors() const { return maxColors_; }

 private:
  Scene* scene_ = nullptr;
  std::vector<double> dts_;
  std::vector<Scene::Snapshot> checkpoints_;  // S_0 … S_N
  double runSeconds_ = 0.0, gradientSeconds_ = 0.0;
  long injectRuns_ = 0;
  int maxColors_ = 0;
};

}  // namespace superdex
