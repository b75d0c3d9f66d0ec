// A soft (tet FEM) actor carried by the generic actor layer (core/model/actor_kind.h): q = the
// node positions x (3 per node, [m]), v their velocities, a vector kind (q ⊕ δ = q + δ). Its stage
// energy is the soft stage terms of core/model/soft_terms.h on its free nodes:
//   Φ(x) = Σ_a m_a/(2Δt_i²) |x_a − x̂_a|² − Σ_a m_a g·x_a + Σ_t V_t Ψ(F_t)
//          + β/(2Δt_i) Σ_t (x_t − x⁰_t)ᵀ K_t (x_t − x⁰_t)                               [J]
// (K_t frozen at the stage's predictor x̂). Prescribed nodes (pinned or driven) are prescribed
// tangent dofs, placed by Prescribe. Its colliding role is its boundary faces' quadrature samples:
// y = Σ_a b_a x_a (a Nodes map on the face's three nodes), the colliding normal the deformed unit
// face normal, which moves with the nodes (KindSample::faceNormal). With colliderType Sdf it is
// a collider too: its reference grid SDF pulled back through the deformed tets (TetCollider,
// core/contact/tet_field.h). A soft skin's nodes bound to links are carried parts (SetCarriedParts).
#pragma once

#include <memory>
#include <vector>

#include "core/model/node_body_kind.h"
#include "core/model/soft_terms.h"

namespace superdex {

class SoftKind : public NodeBodyKind {
 public:
  /// A body built by BuildSoftBody (the same model and initial state as Scene::AddSoftActor).
  SoftKind(SoftBodyModel model, const SoftBodyState& initial);
  /// Builds the model from a description; null with *error filled on bad input.
  static std::unique_ptr<SoftKind> Build(const SoftActorDesc& desc, Error* error);

  const SoftBodyModel& Model() const { return model_; }
  /// Replaces Young's modulus E [Pa] and density ρ [kg/m³] (validated by the caller): the Lamé
  /// parameters and the lumped masses follow; Poisson's ratio and stiffness damping are kept.
  void SetMaterial(double youngsModulus, double density);

  /// A soft skin: its nodes bound to links of its skeleton (CarriedPart::Kind::Point parts at
  /// their entries and dofs, Scene::AddSoftActor). Their inertia, gravity, elasticity, damping
  /// and contact reach the skeleton's joints through the links' chart Jacobians.
  void SetCarriedParts(std::vector<CarriedPart> parts) { parts_ = std::move(parts); }
  const std::vector<CarriedPart>* CarriedParts() const override {
    return parts_.empty() ? nullptr : &parts_;
  }

  std::string KindName() const override { return "soft"; }
  std::unique_ptr<ActorKind> Clone() const override;
  int NumDofs() const override { return 3 * model_.NumNodes(); }
  KindState InitialState() const override { return initial_; }
  /// The stage's target: x̂, x⁰, x_n and K_t at x̂ (stiffness damping).
  void PrepareStage(KindStageData* stage) const override;
  double StageEnergy(const KindStageData& stage, const Eigen::VectorXd& q, int order,
                     PsdProjection projection, Eigen::VectorXd* g,
                     std::vector<Eigen::Triplet<double>>* H) const override;
  bool IsPrescribed(int dof) const override { return model_.freeIndex[dof / 3] < 0; }
  /// ApplyNodeConstraints from the initial positions.
  void Prescribe(double t, Eigen::VectorXd* q) const override;
  /// Every stage of a scene with a soft body is solved cold, whole and without step limits:
  ///   warm start: its Sdf collider's stages are only piecewise smooth (the deformed grid SDF's
  ///     gradient jumps across tet and cell faces), and at tolerances near round-off Newton ends
  ///     in the iteration cap from some starts, predicted or not;
  ///   step limit: the limit scales the whole actor's step (it was made for rigid bodies); it
  ///     would hold every node back for the one sample that approaches fastest, so the nodes'
  ///     steps are bounded by the line search alone;
  ///   split parts: the by-parts line search has not been measured on deforming bodies.
  StageShortcuts Shortcuts() const override { return {false, false, false}; }

  const Eigen::VectorXd& NodeMasses() const override { return model_.nodeMass; }
  double TotalMass() const override { return model_.mass; }
  /// Σ_t V_t Ψ(F_t) [J].
  double InternalEnergy(const KindState& s) const override;
  const SoftBodyModel* TetCollider() const override {
    return model_.collider == ColliderType::Sdf ? &model_ : nullptr;
  }

  const std::vector<Eigen::Vector3i>* SurfaceTriangles() const override { return &model_.faces; }
  int NumSamples() const override { return static_cast<int>(model_.samples.size()); }
  KindSample Sample(int k, const Eigen::VectorXd& q) const override;
  /// Face by face (samples are grouped by face): a face's samples lie in the ball about its
  /// centroid through its farthest node, now and at qLast; the face is visited when keep accepts
  /// the larger of the two radii.
  void ForEachSampleNear(
      const Eigen::VectorXd& q, const Eigen::VectorXd& qLast,
      const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&, double)>& keep,
      const std::function<void(int, int)>& visit) const override;

 private:
  SoftBodyModel model_;
  SoftBodyState initial_;
  std::vector<CarriedPart> parts_;  ///< a skin's bound nodes
};

}  // namespace superdex
