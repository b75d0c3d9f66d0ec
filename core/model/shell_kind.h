// A shell actor carried by the generic actor layer (core/model/actor_kind.h): q = the node
// positions x (3 per node, [m]), v their velocities, a vector kind (q ⊕ δ = q + δ). Its stage
// energy (core/model/shell_body.h, energies/shell_energies.h):
//   Φ(x) = Σ_a m_a/(2Δt_i²) |x_a − x̂_a|² − Σ_a m_a g·x_a − Σ_loaded f_a(t_i)·x_a
//          + Σ_triangles h A (μ tr E² + λ_s/2 (tr E)²) + W_bending
//          + β/(2Δt_i) Σ_e (x_e − x⁰_e)ᵀ K_e (x_e − x⁰_e)                                  [J]
// the last the stiffness damping Δt_i R (R = β/2 vᵀ K v, v = (x − x⁰)/Δt_i), each element's K_e
// its PSD-projected elastic Hessian at the predictor x̂, frozen for the stage (an exact quadratic
// potential; as a soft body's, core/model/soft_terms.h)
// with W_bending the mid-edge Kirchhoff–Love term per triangle (energies/shell_midedge.h, the
// default) or the hinge term per interior edge (energies/shell_energies.h; ShellBendingModel)
// (lumped masses ρ h A / 3 per triangle corner). Prescribed nodes (pinned or driven) are
// prescribed tangent dofs, placed by Prescribe. Its colliding role is the triangles' quadrature
// samples (contactElementType), y = Σ_a b_a x_a, without a colliding normal: a shell is two-sided,
// so alignment rejection and friction fading are off for it (spec). Its collider role is the
// PointCloud collider (colliderType Auto or PointCloud): its nodes with their lumped areas, or
// its triangles' quadrature points (pointCloud.colliderTriangleElementType), d = 2.
#pragma once

#include <memory>
#include <vector>

#include "core/model/node_body_kind.h"
#include "core/model/shell_body.h"

namespace superdex {

class ShellKind : public NodeBodyKind {
 public:
  ShellKind(ShellModel model, const VectorState& initial);
  /// Builds the model from a description; null with *error filled on bad input.
  static std::unique_ptr<ShellKind> Build(const ShellActorDesc& desc, Error* error);

  const ShellModel& Model() const { return model_; }

  std::string KindName() const override { return "shell"; }
  std::unique_ptr<ActorKind> Clone() const override;
  int NumDofs() const override { return 3 * model_.NumNodes(); }
  KindState InitialState() const override;
  double StageEnergy(const KindStageData& stage, const Eigen::VectorXd& q, int order,
                     PsdProjection projection, Eigen::VectorXd* g,
                     std::vector<Eigen::Triplet<double>>* H) const override;
  bool IsPrescribed(int dof) const override { return model_.freeIndex[dof / 3] < 0; }
  /// The constraints' paths from the rest positions.
  void Prescribe(double t, Eigen::VectorXd* q) const override;
  /// With stiffness damping: the elements' damping stiffnesses at the predictor x̂.
  void PrepareStage(KindStageData* stage) const override;
  /// Cold stages, whole, no step limit, as a soft body's (core/model/soft_kind.h): not measured
  /// on shells yet.
  StageShortcuts Shortcuts() const override { return {false, false, false}; }

  const Eigen::VectorXd& NodeMasses() const override { return model_.nodeMass; }
  double TotalMass() const override { return model_.mass; }
  /// Membrane and bending energy [J].
  double InternalEnergy(const KindState& s) const override;

  const std::vector<Eigen::Vector3i>* SurfaceTriangles() const override { return &model_.faces; }
  int NumSamples() const override { return static_cast<int>(model_.samples.size()); }
  KindSample Sample(int k, const Eigen::VectorXd& q) const override;
  /// Triangle by triangle: a triangle's samples lie in the ball about its centroid through its
  /// farthest node, now and at qLast.
  void ForEachSampleNear(
      const Eigen::VectorXd& q, const Eigen::VectorXd& qLast,
      const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&, double)>& keep,
      const std::function<void(int, int)>& visit) const override;

  const PointCloudColliderParams* PointCloud() const override {
    return model_.pointCloud ? &model_.cloud : nullptr;
  }
  int NumCloudPoints() const override { return static_cast<int>(model_.cloudPoints.size()); }
  KindSample CloudPoint(int j, const Eigen::VectorXd& q) const override;
  /// The rest positions.
  const Eigen::VectorXd* ReferenceConfiguration() const override { return &rest_.x; }

 private:
  /// The elastic terms at x (value; order >= 1 gradient into *g, order 2 triplets into *H).
  /// With `elementHessians`, instead of adding anything, stores each element's Hessian (membrane
  /// triangles, then bending triangles or hinges), projected when `project`.
  double ElasticTerms(const Eigen::VectorXd& x, int order, bool project, Eigen::VectorXd* g,
                      std::vector<Eigen::Triplet<double>>* H,
                      std::vector<Eigen::MatrixXd>* elementHessians = nullptr) const;
  /// The stiffness damping's β/(2Δt) Σ_e uᵀ K_e u, u = x − x⁰ (order >= 1 its gradient into *g,
  /// order 2 its Hessian's triplets into *H).
  double DampingTerms(const KindStageData& stage, const Eigen::VectorXd& x, int order,
                      Eigen::VectorXd* g, std::vector<Eigen::Triplet<double>>* H) const;
  ShellModel model_;
  VectorState rest_;  ///< the rest positions (constraints displace from them) and initial velocity
};

}  // namespace superdex
