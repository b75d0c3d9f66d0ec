// Trajectory sensitivities dS/dθ of the discrete step map, for fitting physical parameters.
//
// A step maps the dynamic state S_n (Scene::PackState: poses, velocities and, for BDF methods, the
// history a step reads) to S_{n+1}. Inside it each implicit stage solves r(q; inputs, θ) = 0,
// where the inputs (inertial targets, stage-start and last configurations) are smooth functions
// of S_n and of earlier stages. By the implicit function theorem
//     dq = −J⁻¹ (∂r/∂inputs · d inputs + ∂r/∂θ dθ),   J = ∂r/∂q at the converged q,
// with J the stage Jacobian in the stage's own dissipation mode (the exact Hessian with explicit
// normals, the residual Jacobian otherwise), evaluated and LU-factorized at the accepted solution.
//
// How the products are formed: for each parameter direction j the step is replayed at
// S_n ± η dS_j, θ_j ± η with every stage solve replaced by the single Newton step
// q(η) = q* − J⁻¹ r(q*; inputs(η), θ(η)) from the recorded solution q* with the recorded factors,
// and every explicit part of the step (integrator combinations, DIRK rotation rules, node paths)
// run as in the step itself. Then dS_{n+1}/dθ_j = (S₊ − S₋)/(2η) + O(η²): the IFT derivative of
// the discrete map, with no solver tolerance in it (the residual left by the solve cancels in the
// difference), and a truncation error O(η²) from the curvature of r in its inputs (η ≈ 1e-6
// relative; measured agreement with the linearity of r in k, μ, c_t, c_n, E and ρ in
// tests/core/test_sensitivity.cpp). The partials ∂r/∂inputs are therefore not formed
// symbolically: the method is exact in the IFT and second-order accurate in those partials.
//
// The friction force is only C¹ in the slip velocity (kinks of its Jacobian at V_t = 0, where
// resting and sticking samples sit, and at V_t = V_f): differences across them would be O(η/V_f)
// off, so every replay evaluates the force about the slips recorded at the solution (the same
// value and first derivatives there, smooth around it; core/contact/slip_tape.h).
// Non-smooth points of the discrete map, handled as they fall: the contact set (samples within
// δ) changes smoothly through the C² penalty ramp; the alignment and contact-set decisions taken
// at the stage start (explicit normals) and the fallback of a failed residual solve to explicit
// normals are not differentiable — a step that crosses one gives the derivative of the branch it
// took. The pair value of μ, c_t and c_n is √(c_A c_B),
// not differentiable at 0: those parameters are differentiated at positive values only.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/scene.h"
#include "core/sensitivity/stage_tape.h"

namespace superdex {

enum class SceneParameterKind {
  PenaltyCoefficient,            ///< contact.penalty_coefficient k [Pa/m]
  CoulombFrictionCoefficient,    ///< μ [-]
  ViscousFrictionCoefficient,    ///< c_t [s/m]
  NormalViscousDampingCoefficient,  ///< c_n [s/m]
  FrictionFalloffVel,            ///< V_f [m/s]
  YoungsModulus,                 ///< soft actors: E [Pa]
  Density,                       ///< soft and dynamic rigid actors: ρ [kg/m³] (rigid: m / V)
  Mass,                          ///< dynamic rigid actors: m [kg] (J scales with it)
  LinkMass,        ///< articulated actors: link_mass.LINK [kg] (its second moment scales with it)
  DriveStiffness,  ///< articulated actors: drive_stiffness.LINK, its joint's k_p [N·m/rad, N/m]
  DriveDamping,    ///< articulated actors: drive_damping.LINK, its joint's k_d [N·m·s/rad, N·s/m]
  Position,         ///< initial position, one component [m] (soft: every node; a kind: its
                    ///< ActorKind::MotionParameter)
  Velocity,         ///< initial velocity, one component [m/s] (soft: every node; a kind: ditto)
  AngularVelocity,  ///< rigid and kinds that have one: initial angular velocity, one component
                    ///< [rad/s]
};

/// One differentiable parameter: "ACTOR.NAME" with NAME one of SceneParameterNames(): the contact
/// and material kinds by their field names (kContactParamsFields, kSoftMaterialFields),
/// link_mass.LINK, drive_stiffness.LINK, drive_damping.LINK (an articulated actor's link by
/// name), or position.x|y|z, velocity.x|y|z, angular_velocity.x|y|z (the initial state).
struct SceneParameter {
  ActorHandle actor;
  SceneParameterKind kind = SceneParameterKind::CoulombFrictionCoefficient;
  int component = 0;  ///< x, y, z for the initial-state kinds; the link for the link kinds
  bool IsInitialState() const { return kind >= SceneParameterKind::Position; }
  bool IsLinkParameter() const {
    return kind >= SceneParameterKind::LinkMass && kind <= SceneParameterKind::DriveDamping;
  }
};

/// Parses "ACTOR.NAME" against the scene; false with a message naming the part that is wrong.
bool ParseSceneParameter(const Scene& scene, const std::string& text, SceneParameter* parameter,
                         Error* error);
std::string ToString(const Scene& scene, const SceneParameter& parameter);
/// "penalty_coefficient, ..., angular_velocity.x|y|z": every NAME, for help and messages.
std::string SceneParameterNames();
/// The parameter's current value (for initial-state kinds: of the current state).
double ParameterValue(const Scene& scene, const SceneParameter& parameter);
/// Sets the value (validated as the actor's description is). Initial-state kinds change the
/// current state (rigid: p, v or ω; soft: every node's position or velocity component).
bool SetParameterValue(Scene* scene, const SceneParameter& parameter, double value, Error* error);

/// Whether p can be differentiated at the scene's current state: a valid actor; a model
/// parameter at a positive value (the pair value √(c_A c_B) is not differentiable at 0); an
/// initial-state parameter only before the first step. `index` names it in the message.
bool CheckDifferentiable(Scene& scene, const SceneParameter& p, int index, Error* error);
/// ∂S/∂θ of the current packed state (Scene::PackState) for an initial-state parameter: unit
/// entries (soft: every node's component), Ṙ = [e_c]× R for an angular velocity, a kind's
/// ActorKind::MotionParameter direction; zero for a model parameter.
Eigen::VectorXd InitialStateDirection(Scene& scene, const SceneParameter& p);
/// C with centre of mass of actor a = C S for the packed state S (3 × StateSize; soft: the node
/// masses' weights; a kind: its ActorKind::CenterOfMassJacobian at the current state; all zero
/// for a static rigid actor).
Eigen::SparseMatrix<double> CenterOfMassMap(Scene& scene, ActorHandle a);
/// The state step η of the central differences of the step map [m] (velocities: η/dt [m/s]):
/// 0.024 V_f min Δt_i, smallest V_f over the actors, smallest stage step of the method.
double DifferenceStateStep(const Scene& scene, double dt);

/// Forward sensitivities for a few parameters, carried along a simulation. With 4 or more
/// parameters and no soft actors the parameters' replays run in parallel, each thread on its own
/// copy of the scene made at its first replay: the scene's parameters must not change between
/// Begin and the last Step.
class ForwardSensitivity {
 public:
  /// Starts at the scene's current state with dS/dθ = ∂S/∂θ of that state (unit directions for
  /// the initial-state kinds, zero otherwise). False (with the reason) for a parameter that cannot
  /// be differentiated there (μ, c_t, c_n at 0; an initial-state parameter after the first step).
  bool Begin(Scene* scene, const std::vector<SceneParameter>& parameters, Error* error);
  /// Steps the scene by dt and the sensitivities with it. A stage that does not converge makes
  /// the derivative meaningless: the step is reported in *report and false returned with an
  /// error saying so.
  bool Step(double dt, StepReport* report, Error* error);
  /// dS/dθ: one column per parameter, rows as Scene::PackState.
  const Eigen::MatrixXd& StateJacobian() const { return dS_; }
  /// d(centre of mass of actor a)/dθ, 3 × P (soft: mass-weighted over the nodes).
  Eigen::MatrixXd CenterOfMassJacobian(ActorHandle a) const;  // = CenterOfMassMap · dS/dθ
  /// Wall seconds in the nominal steps and in the replays, since Begin.
  double StepSeconds() const { return stepSeconds_; }
  double TangentSeconds() const { return tangentSeconds_; }

 private:
  Scene* scene_ = nullptr;
  std::vector<SceneParameter> parameters_;
  Eigen::MatrixXd dS_;
  StepTape tape_;
  struct Replicas;  // per-thread copies of the scene for parallel replays, kept across steps
  std::shared_ptr<Replicas> replicas_;
  double stepSeconds_ = 0.0, tangentSeconds_ = 0.0;
};

}  // namespace superdex
