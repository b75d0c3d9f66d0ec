// A rigid actor written against the generic actor layer (core/model/actor_kind.h): the layer's
// manifold hooks carry a rigid body's rotation, so the stage, the integrators and the contact
// assembler move it without knowing it is rigid.
//
// Configuration in material-point form (DESIGN "Degrees of freedom"): q = [p, vec R] ∈ R¹²
// (column-major R), v = q̇ = [v, vec Ṙ]; the integrators' affine combinations of states are those
// of the material points x = p + R X. Tangent step δ = [δp, δθ] (m = 6), retraction
//   q ⊕ δ = [p + δp, vec(exp([δθ]×) R)].
// Stage energy (energies/rigid_inertia.h), with an applied force F(t_i) at the centre of mass:
//   Φ(q) = 1/(2Δt_i²) (m ‖p − p̂‖² + tr((R − R̂) J (R − R̂)ᵀ)) − m g·p − F·p        [J]
// and an applied world torque τ(t_i) as the stage load −τ on δθ (not a potential).
// with its gradient and Hessian in δ at δ = 0 (the rotation block projected to PSD when it does
// not factorize). Colliding role: the body's surface samples, y = p + R X on a Rigid map with
// their normals R n_A; collider role: the shape's field in the body frame (p, R), a rigid frame
// on δ's two blocks. DIRK stages follow the three rotation rules of core/dynamics/integrators.h.
// A static body prescribes all of δ (its pose is held); a kinematic one prescribes all of δ on its
// path (RigidActorDesc::kinematic, KinematicStateAt).
#pragma once

#include "core/model/actor_kind.h"
#include "core/model/rigid_body.h"

namespace superdex {

// --- The rigid body's stage rules, written once for the built-in rigid actor (core/dynamics) and
// for RigidKind.

/// Appends the stage's inertia Hessian H (6 × 6 in [δp, δθ], block diagonal: w m I and the rotation
/// block) at stage dof `offset`: projected to PSD per `projection` only when the rotation block
/// does not factorize (otherwise the whole matrix is positive definite and a projection would
/// return it unchanged). The translation diagonal and the whole rotation block are appended even
/// where an entry is zero: a body in free flight has rotation-block entries that are exact zeros
/// at one stage and round-off at the next, and each such change made the assembly rebuild its
/// pattern. Other entries (the coupling a projection may leave at round-off level) only where
/// nonzero.
void AppendRigidInertiaHessian(const Eigen::Matrix<double, 6, 6>& H, PsdProjection projection,
                               int offset,
                               std::vector<Eigen::Triplet<double>>* triplets);
/// The residual modes' trivialization of a rotation block at stage dof `row`: along
/// exp([δθ]×) R the world torque τ of a potential changes by (H − ½[τ]×) δθ; appends −½[τ]×'s
/// off-diagonal entries, zero or not (so that the pattern stays the same when τ changes).
void AppendSpinTrivialization(const Eigen::Vector3d& tau, int row,
                              std::vector<Eigen::Triplet<double>>* triplets);
/// The fraction (0, 1] of a Newton correction (δp, δθ) a rigid body trusts:
/// ‖δp‖ + ‖δθ‖ ρ <= kCorrectionTrust ρ, ρ = max(samples' radius, ρ_rms).
double RigidTrustFraction(const RigidBodyModel& m, const Eigen::Vector3d& dp,
                          const Eigen::Vector3d& dtheta);
/// The size of a rigid step as a length: max(‖δp‖∞, ‖δθ‖ ρ_rms) [m].
double RigidStepLength(const RigidBodyModel& m, const Eigen::Vector3d& dp,
                       const Eigen::Vector3d& dtheta);
/// A DIRK stage's rotation (core/dynamics/integrators.h, the three rotation rules), from the
/// stage's solution Q and its start (R⁰, Ṙ⁰) with step Δt_i [s]: the stage velocity V made
/// tangent to SO(3) at Q with the spin momentum of (Q − R⁰)/Δt_i, and the stage's world torque
/// τ = axial(K J Qᵀ − Q J Kᵀ), K = ((Q − R⁰)/Δt_i − Ṙ⁰)/Δt_i, whose stationarity balances the
/// rotational inertia force [N·m].
struct DirkRotationSlope {
  Eigen::Matrix3d V;
  Eigen::Vector3d torque;
};
DirkRotationSlope DirkStageRotation(const Eigen::Matrix3d& J, const Eigen::Matrix3d& Q,
                                    const Eigen::Matrix3d& R0, const Eigen::Matrix3d& Rdot0,
                                    double dt);
/// A DIRK step's end rate: Ṙ corrected along the tangent directions [δω] R so that it carries
/// exactly the spin momentum `spin` [kg·m²/s] integrated by the method's weights.
Eigen::Matrix3d SpinCorrectedRate(const Eigen::Matrix3d& J, const Eigen::Matrix3d& R,
                                  const Eigen::Matrix3d& Rdot, const Eigen::Vector3d& spin);

/// The acceleration of a body in a closed-form free stage (energies/rigid_inertia.h,
/// MinimizeRigidInertia): gravity plus an applied force F [N] over the mass m [kg] (`force` null:
/// none) into *a [m/s²]; false when an applied torque (`torque`, may be null) is nonzero, which
/// has no closed form.
bool FreeStageAcceleration(double mass, const Eigen::Vector3d& gravity,
                           const Eigen::Vector3d* force, const Eigen::Vector3d* torque,
                           Eigen::Vector3d* a);
/// The warm start's predicted pose of a body τ [s] after t_n (core/dynamics/warm_start.h):
///   R = Exp(τ ω_n + ½ τ² α) R_n,   α = (ω_n − ω_{n−1}) / h_{n−1},
///   p = p⁰ + Δt_i (v_n + τ a)  with the stage's start p⁰ (`stageStart`, Δt_i = stageDt), or
///   p = p_n + τ v_n + ½ τ² a   without (null),   a = (v_n − v_{n−1}) / h_{n−1};
/// a = α = 0 without `previous` (null, or hPrevious <= 0).
RigidPose PredictRigidPose(const RigidBodyState& s, const RigidBodyState* previous,
                           double hPrevious, double tau, const Eigen::Vector3d* stageStart,
                           double stageDt);
/// How much the force and the torque on a body changed over the last two steps, as an
/// acceleration [m/s²]: |a_n − a_{n−1}| + |τ_n − τ_{n−1}| / (m ρ), a_n = (v_n − v_{n−1})/h_{n−1},
/// τ_n = (L_n − L_{n−1})/h_{n−1}, L = I_w ω the world angular momentum [kg·m²/s], ρ the RMS
/// radius √(tr J/m) [m] (a torque as the acceleration it gives the body's points at ρ).
double RigidForceChange(const RigidBodyModel& m, const RigidBodyState& current,
                        const RigidBodyState& previous, double hPrevious,
                        const RigidBodyState& before, double hBefore);

/// A rigid pose's chart on q = [p, vec R]: q ⊕ [δp, δθ] = [p + δp, vec(exp([δθ]×) R)], and the
/// step between two poses, [p_to − p_from, Log(R_to R_fromᵀ)] (rigid and attached bodies).
void RigidChartRetract(const Eigen::VectorXd& q, const Eigen::VectorXd& delta,
                       Eigen::VectorXd* out);
void RigidChartBetween(const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                       Eigen::VectorXd* delta);

class RigidKind : public ActorKind {
 public:
  /// A body built by BuildRigidBody (the same model and initial state as Scene::AddRigidActor).
  RigidKind(RigidBodyModel model, const RigidBodyState& state);
  /// Builds the model from a description; null with *error filled on bad input.
  static std::unique_ptr<RigidKind> Build(const RigidActorDesc& desc, Error* error);

  const RigidBodyModel& Model() const { return model_; }
  /// Replaces the mass [kg] (> 0); J scales with it (the same shape, uniformly denser).
  void SetMass(double mass);
  /// A static body's state from now on: it is held there (Scene::SetState, Scene::Restore).
  void Hold(const RigidBodyState& s) { initial_ = s; }
  const RigidBodyState& Held() const { return initial_; }
  /// Replaces the contact parameters (the kind's and its model's).
  void SetContactParams(const ContactParams& params);
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
  /// Static: held where created; a kinematic body moves on its path (it collides as a dynamic
  /// one and its pairs combine their parameters as a dynamic one's) with every dof prescribed.
  bool IsStatic() const override { return !model_.Moves(); }
  bool IsPrescribed(int /*dof*/) const override { return !model_.dynamic; }
  void Prescribe(double t, Eigen::VectorXd* q) const override;
  /// A kinematic body's exact state on its path (KinematicStateAt).
  void EndPrescribed(double t, KindState* s) const override;
  /// The applied torque τ(t_i) on δθ (RigidActorDesc::appliedTorque); the applied force is the
  /// stage energy's potential −F(t_i)·p.
  bool StageLoad(const KindStageData& stage, Eigen::VectorXd* f) const override;

  void Retract(const Eigen::VectorXd& q, const Eigen::VectorXd& delta,
               Eigen::VectorXd* out) const override;
  /// −½[τ]× on the δθ block, τ the potential residual's torque: along exp([δθ]×) R a potential's
  /// world torque changes by (H − ½[τ]×) δθ.
  void AddResidualJacobianCorrection(const Eigen::VectorXd& q, const Eigen::VectorXd& residual,
                                     std::vector<Eigen::Triplet<double>>* J) const override;
  /// I on δp, the left Jacobian J_l(δθ) of SO(3) on δθ.
  Eigen::MatrixXd ChartTangentMap(const Eigen::VectorXd& delta) const override;
  int DofBlockSize() const override { return 6; }
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
  /// PredictRigidPose through the stage's slope (a static body keeps its pose).
  void PredictStage(const KindState& current, const KindState* previous, double hPrevious,
                    double tau, const Eigen::VectorXd& stageStart, double stageDt,
                    Eigen::VectorXd* q) const override;
  /// [p_to − p_from, Log(R_to R_fromᵀ)].
  void TangentBetween(const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                      Eigen::VectorXd* delta) const override;
  /// RigidForceChange (0 for a static body).
  double ForceChange(const KindState& current, const KindState& previous, double hPrevious,
                     const KindState& before, double hBefore) const override;
  /// The minimizer of inertia and gravity (energies/rigid_inertia.h, MinimizeRigidInertia); a
  /// static body keeps its pose.
  bool FreeStageMinimizer(const KindStageData& stage, Eigen::VectorXd* q) const override;

  /// One group (none for a static body): p, the three tangent directions vec([e_k]× R) of R
  /// (length ρ = ρ_rms, the only variations of R a trajectory has), v and Ṙ; δ = [δp, δθ] with
  /// lengths 1 and ρ.
  void DifferenceGroups(const KindState& s,
                        std::vector<KindDifferenceGroup>* groups) const override;
  /// p_c, v_c (unit directions) and ω_c = axial(Ṙ Rᵀ)_c (direction vec([e_c]× R) in Ṙ); none
  /// for a static body.
  bool MotionParameter(KindMotion motion, int component, const KindState& s, double* value,
                       Eigen::VectorXd* direction) const override;
  /// [I 0]: the centre of mass is p.
  Eigen::MatrixXd CenterOfMassJacobian(const KindState& s) const override;

  double KineticEnergy(const KindState& s) const override;
  double GravityEnergy(const KindState& s, const Eigen::Vector3d& gravity) const override;
  Eigen::Vector3d LinearMomentum(const KindState& s) const override;
  Eigen::Vector3d AngularMomentum(const KindState& s) const override;
  Eigen::Vector3d CenterOfMass(const KindState& s) const override { return s.x.head<3>(); }
  Eigen::Vector3d CenterOfMassVelocity(const KindState& s) const override {
    return s.v.head<3>();
  }
  Aabb Bounds(const Eigen::VectorXd& q) const override;

  /// Colliding: the body's surface samples, on its own pose (δ's two blocks).
  int NumSampleBodies() const override { return model_.samples.empty() ? 0 : 1; }
  const RigidBodyModel* SampleBody(int /*b*/) const override { return &model_; }
  RigidPose SampleBodyPose(int /*b*/, const Eigen::VectorXd& q) const override { return PoseOf(q); }
  void SampleBodyDofs(int /*b*/, int dof[2]) const override {
    dof[0] = 0;
    dof[1] = 3;
  }
  const RigidCollider* Collider() const override;
  KindFrame ColliderFrame(const Eigen::VectorXd& q) const override;

 private:
  RigidBodyModel model_;
  RigidBodyState initial_;
};

}  // namespace superdex
