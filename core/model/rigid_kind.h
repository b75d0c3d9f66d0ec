// A rigid actor written against the generic actor layer (core/model/actor_kind.h): the layer's
// manifold hooks carry a rigid body's rotation, so the stage, the integrators and the contact
// assembler move it without knowing it is rigid.
//
// Configuration in material-point form (DESIGN "Degrees of freedom"): q = [p, vec R] ∈ R¹²
// (column-major R), v = q̇ = [v, vec Ṙ]; the integrators' affine combinations of states are those
// of the material points x = p + R X. Tangent step δ = [δp, δθ] (m = 6), retraction
//   q ⊕ δ = [p + δp, vec(exp([δθ]×) R)].
// Stage energy (energies/rigid_inertia.h):
//   Φ(q) = 1/(2Δt_i²) (m ‖p − p̂‖² + tr((R − R̂) J (R − R̂)ᵀ)) − m g·p               [J]
// with its gradient and Hessian in δ at δ = 0 (the rotation block projected to PSD when it does
// not factorize). Colliding role: the body's surface samples, y = p + R X on a Rigid map with
// their normals R n_A; collider role: the shape's field in the body frame (p, R), a rigid frame
// on δ's two blocks. DIRK stages follow the three rotation rules of core/dynamics/integrators.h.
// A static body prescribes all of δ (its pose is held).
#pragma once

#include "core/model/actor_kind.h"
#include "core/model/rigid_body.h"

namespace superdex {

class RigidKind : public ActorKind {
 public:
  /// A body built by BuildRigidBody (the same model and initial state as Scene::AddRigidActor).
  RigidKind(RigidBodyModel model, const RigidBodyState& state);
  /// Builds the model from a description; null with *error filled on bad input.
  static std::unique_ptr<RigidKind> Build(const RigidActorDesc& desc, Error* error);

  const RigidBodyModel& Model() const { return model_; }
  /// The configuration and state in and out of the kind's layout.
  static KindState Pack(const RigidBodyState& s);
  static RigidBodyState Unpack(const KindState& s);
  static RigidPose PoseOf(const Eigen::VectorXd& q);

  std::string KindName() const override { return "rigid"; }
  std::unique_ptr<ActorKind> Clone() const override;
  int NumDofs() const override { return 12; }
  int NumTangentDofs() const override { return 6; }
  KindState InitialState() const override { return Pack(initial_); }

  double StageEnergy(const KindStageData& stage, const Eigen::VectorXd& q, int order,
                     PsdProjection projection, Eigen::VectorXd* g,
                     std::vector<Eigen::Triplet<double>>* H) const override;
  bool IsPrescribed(int /*dof*/) const override { return !model_.dynamic; }
  void Prescribe(double t, Eigen::VectorXd* q) const override;

  void Retract(const Eigen::VectorXd& q, const Eigen::VectorXd& delta,
               Eigen::VectorXd* out) const override;
  /// −½[τ]× on the δθ block, τ the potential residual's torque: along exp([δθ]×) R a potential's
  /// world torque changes by (H − ½[τ]×) δθ.
  void AddResidualJacobianCorrection(const Eigen::VectorXd& q, const Eigen::VectorXd& residual,
                                     std::vector<Eigen::Triplet<double>>* J) const override;
  /// I on δp, the left Jacobian J_l(δθ) of SO(3) on δθ.
  Eigen::MatrixXd ChartTangentMap(const Eigen::VectorXd& delta) const override;
  /// max(‖δp‖∞, ‖δθ‖ ρ_rms) [m].
  double StepLength(const Eigen::VectorXd& q, const Eigen::VectorXd& delta) const override;
  /// ‖δp‖ + ‖δθ‖ ρ <= kCorrectionTrust ρ, ρ = max(samples' radius, ρ_rms).
  double TrustFraction(const Eigen::VectorXd& q, const Eigen::VectorXd& delta) const override;
  /// V_i = (Q_i − x⁰)/Δt_i made tangent at Q_i with the same spin momentum; the stage's world
  /// torque τ_i = axial(K J Qᵀ − Q J Kᵀ), K = (V_raw − Ṙ⁰)/Δt_i, kept in `extra`.
  void DirkStageSlope(const Eigen::VectorXd& x, const KindState& start, double dt,
                      KindSlope* out) const override;
  /// R: the last stage's (stiffly accurate methods) or the nearest rotation to the integrated
  /// one; Ṙ corrected along [δω] R so that it carries the spin momentum integrated by the
  /// method's weights, L_n + h Σ b_i τ_i.
  void DirkStepEnd(const KindState& start, const Eigen::VectorXd& lastStage, bool stifflyAccurate,
                   const std::vector<KindSlope>& slopes, const std::vector<double>& hb,
                   KindState* end) const override;

  double KineticEnergy(const KindState& s) const override;
  double GravityEnergy(const KindState& s, const Eigen::Vector3d& gravity) const override;
  Eigen::Vector3d LinearMomentum(const KindState& s) const override;
  Eigen::Vector3d AngularMomentum(const KindState& s) const override;
  Eigen::Vector3d CenterOfMass(const KindState& s) const override { return s.x.head<3>(); }
  Eigen::Vector3d CenterOfMassVelocity(const KindState& s) const override {
    return s.v.head<3>();
  }
  Aabb Bounds(const Eigen::VectorXd& q) const override;

  int NumSamples() const override { return static_cast<int>(model_.samples.size()); }
  KindSample Sample(int k, const Eigen::VectorXd& q) const override;
  /// Descends the body's sample tree (its balls carried by the poses at q and qLast).
  void ForEachSampleNear(
      const Eigen::VectorXd& q, const Eigen::VectorXd& qLast,
      const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&, double)>& keep,
      const std::function<void(int, int)>& visit) const override;
  const RigidCollider* Collider() const override;
  KindFrame ColliderFrame(const Eigen::VectorXd& q) const override;

 private:
  RigidBodyModel model_;
  RigidBodyState initial_;
};

}  // namespace superdex
