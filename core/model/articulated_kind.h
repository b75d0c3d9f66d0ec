// An articulated actor: rigid links joined by joints in reduced coordinates (KinematicTree),
// written against the generic actor layer (core/model/actor_kind.h).
//
// Configuration in material-point form, as a rigid body's (DESIGN "Degrees of freedom"):
//   q = [q_J, c_1, vec R_1, …, c_L, vec R_L] ∈ R^(n_J + 12 L),   v = q̇,
// q_J the joint coordinates (kinematic_tree.h), c_l the centre of mass of link l and R_l its
// rotation (world). The links' entries are their forward kinematics of q_J wherever the stage
// solver or a step ends (the retraction writes them), and the integrators' affine combinations
// of them are those of the links' material points: a stage's inertial target (ĉ_l, R̂_l) is the
// material points' own, exactly as for a rigid body. The stage unknowns are the joint
// coordinates' tangent step δ (kinematic_tree.h); joints hold exactly by construction.
// Stage energy, over the links of mass m_l > 0 with second moment J_l about the centre of mass:
//   Φ(q_J) = Σ_l [ 1/(2Δt_i²) (m_l ‖c_l − ĉ_l‖² + tr((R_l − R̂_l) J_l (R_l − R̂_l)ᵀ)) − m_l g·c_l ]
//            + Σ_joints [ U_limit(x) + c/(2Δt_i) (x − x⁰)² + U_drive(x) ]                    [J]
// (energies/rigid_inertia.h per link; a 1-dof joint's coordinate x with its stage start x⁰: the
// limits' penalty, viscous damping as the incremental potential of ½ c ẋ², and the PD drive's
// implicit potential, energies/joint_energies.h), with its exact gradient and Hessian in δ: each link's
// chart gradient (f, τ) and Hessian carried through its chart Jacobian A_l plus the forward
// kinematics' curvature (KinematicTree::AddLinkChartCurvature). The exact Hessian is indefinite
// at speed even at the stage start (the curvature −m ẋ·∂²x/Δt_i against M/Δt_i²: a spinning
// 5-link chain at Δt = 1e-2 has an eigenvalue −89 where M/Δt² has 77), and clamping it made the
// Newton model singular. Where the solver asks for a projection, the model is the Gauss–Newton
// part Σ_l A_lᵀ H_l A_l, each link's chart Hessian H_l projected (its rotation block, when it
// does not factorize): positive definite wherever M is; the local phase's exact iterations
// converge quadratically.
// DIRK stages follow the rigid body's three rules generalized to the tree: (1) a stage's link
// velocities are replaced by the tangent velocity u with the same generalized momentum,
// M(Q) u = Σ_l A_lᵀ [m_l V_c; L_l(V_R)] (a spherical or free joint's rotation rate with them; a
// 1-dof joint's coordinate keeps its stage rate (x − x⁰)/Δt_i, which its damping and drive
// read); (2) the step ends at the last stage (stiffly accurate
// methods), else at the joint coordinates x_n + h Σ b_i V_i (rotations to their nearest) and their
// forward kinematics; (3) each link's linear momentum P_l and angular momentum about the world
// origin c_l × P_l + L_l are integrated with the rates its tangent slopes K_i give, and the end
// velocity is the u with M u = Σ_l A_lᵀ [P_l; L_l] (L_l the spin about the end centre): a
// free-floating tree keeps its total linear and angular momentum exactly. Rule (3) must take the
// rates from the tangent slopes: the raw stage velocities differ from them by O(Δt²) along the
// joints' constraint directions, an O(Δt) error in each link's force, and the 90° pendulum then
// lost 3 % of its energy over 9.5 s at Δt = 1e-3 (first order) instead of 4e-7.
// Units: SI (m, kg, s, rad).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/model/actor_kind.h"
#include "core/model/attached_body_kind.h"
#include "core/model/error.h"
#include "core/model/joint_params.h"
#include "core/model/kinematic_tree.h"

namespace superdex {

/// One link: its joint to its parent and its mass properties (as URDF's <inertial>).
struct ArticulatedLinkDesc {
  std::string name;
  KinematicJoint joint;
  double mass = 1.0;                                         ///< [kg], >= 0
  Eigen::Vector3d centerOfMass = Eigen::Vector3d::Zero();    ///< link frame [m]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();     ///< about the centre of mass, link frame [kg·m²]
  /// Limits, damping and a drive of the joint's coordinate (Revolute and Prismatic joints).
  JointParams jointParams;
  /// Collision shapes (none: the link does not collide), each an attached actor of the
  /// articulation (BuildLinkShapes, Scene::AddArticulatedActor).
  std::vector<LinkShapeDesc> shapes;
};

struct ArticulatedActorDesc {
  std::string name = "articulation";
  std::vector<ArticulatedLinkDesc> links;
  /// Joint coordinates (KinematicTree layout); empty: the zero configuration.
  Eigen::VectorXd jointPositions;
  /// Joint velocities as a tangent step rate (KinematicTree tangent layout) [rad/s, m/s]; empty: 0.
  Eigen::VectorXd jointVelocities;
};

class ArticulatedKind;

/// One collision shape of an articulation as its attached actor: the link and the kind.
struct LinkShape {
  int link = -1;
  std::unique_ptr<AttachedBodyKind> kind;
};

/// The attached actors of every link's shapes, in link order, each on its link's frame (the
/// link's centre of mass, ArticulatedKind::NumCarriedFrames), named after `desc.name` and the
/// link ("arm/finger", "arm/finger#1" for a link's second shape) unless the shape has a name;
/// false, with *error naming the link, the shape and the rule, on bad input.
bool BuildLinkShapes(const ArticulatedActorDesc& desc, std::vector<LinkShape>* shapes,
                     Error* error);

class ArticulatedKind : public ActorKind {
 public:
  /// Builds the kind; null with *error naming the link, the field and the rule on bad input.
  static std::unique_ptr<ArticulatedKind> Build(const ArticulatedActorDesc& desc, Error* error);

  const KinematicTree& Tree() const { return tree_; }
  int NumLinks() const { return tree_.NumLinks(); }
  /// The joint coordinates q_J of a configuration, every link's world pose (its frame; one
  /// forward kinematics of q_J), and link l's centre of mass as q holds it [m].
  Eigen::VectorXd JointPositions(const Eigen::VectorXd& q) const {
    return q.head(tree_.NumCoordinates());
  }
  std::vector<RigidPose> LinkPoses(const Eigen::VectorXd& q) const;
  Eigen::Vector3d LinkCenter(const Eigen::VectorXd& q, int l) const {
    return q.segment<3>(LinkOffset(l));
  }
  /// Link l's mass [kg], name and RMS radius √(tr J / m) [m] (0 for a massless link).
  double LinkMass(int l) const { return links_[l].mass; }
  /// Link l's index by name (−1: none) and its joint's limits, damping and drive.
  int FindLink(const std::string& name) const;
  const JointParams& LinkJointParams(int l) const { return links_[l].joint; }
  /// Replaces link l's mass [kg] (> 0, the link massive already): its second moment scales with
  /// it (the same shape, uniformly denser). Empty, or why not.
  std::string SetLinkMass(int l, double mass);
  /// Replaces link l's joint parameters (validated as Build does). Empty, or why not.
  std::string SetLinkJointParams(int l, const JointParams& params);
  const std::string& LinkName(int l) const { return links_[l].name; }
  double LinkRadius(int l) const { return links_[l].radius; }
  /// The joint velocities u (tangent layout) of a state: M u = Σ_l A_lᵀ [m_l ċ_l; L_l], exact for
  /// a state the kind wrote (its link velocities are then A_l u).
  Eigen::VectorXd JointVelocities(const KindState& s) const;
  /// The state of joint coordinates qJ (NumCoordinates, rotations valid) moving with joint
  /// velocities u (NumTangentDofs): the links' poses and velocities written from them.
  KindState StateAt(const Eigen::VectorXd& qJ, const Eigen::VectorXd& u) const;
  /// The drive forces (tangent layout; 0 where no drive) of state s at time t [s]:
  /// F = −k_p (x − x*(t)) − k_d (ẋ − v*(t)), capped at the force limit [N·m or N].
  Eigen::VectorXd DriveForces(const KindState& s, double t) const;

  std::string KindName() const override { return "articulated"; }
  std::unique_ptr<ActorKind> Clone() const override;
  int NumDofs() const override { return tree_.NumCoordinates() + 12 * NumLinks(); }
  int NumTangentDofs() const override { return tree_.NumTangentDofs(); }
  KindState InitialState() const override { return initial_; }

  double StageEnergy(const KindStageData& stage, const Eigen::VectorXd& q, int order,
                     PsdProjection projection, Eigen::VectorXd* g,
                     std::vector<Eigen::Triplet<double>>* H) const override;

  void Retract(const Eigen::VectorXd& q, const Eigen::VectorXd& delta,
               Eigen::VectorXd* out) const override;
  void TangentBetween(const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                      Eigen::VectorXd* delta) const override;
  /// −½[τ]× on each spherical joint's and free joint's rotation block (as a rigid body's).
  void AddResidualJacobianCorrection(const Eigen::VectorXd& q, const Eigen::VectorXd& residual,
                                     std::vector<Eigen::Triplet<double>>* J) const override;
  /// I, with the left Jacobian of SO(3) on each rotation block.
  Eigen::MatrixXd ChartTangentMap(const Eigen::VectorXd& delta) const override;
  /// max over links of max(‖δc_l‖∞, ‖δφ_l‖ ρ_l) [m], ρ_l the link's RMS radius.
  double StepLength(const Eigen::VectorXd& q, const Eigen::VectorXd& delta) const override;
  void DirkStageSlope(const Eigen::VectorXd& x, const KindState& start, double dt,
                      KindSlope* out) const override;
  void DirkStepEnd(const KindState& start, const Eigen::VectorXd& lastStage, bool stifflyAccurate,
                   const std::vector<KindSlope>& slopes, const std::vector<double>& hb,
                   KindState* end) const override;
  /// The warm start's prediction: the tree moved from q_n by the tangent step
  /// δ = τ (u_n + ½ τ a), u the joint velocities, a = (u_n − u_{n−1})/h_{n−1} (0 without history),
  /// τ the stage's time after t_n.
  void PredictStage(const KindState& current, const KindState* previous, double hPrevious,
                    double tau, const Eigen::VectorXd& stageStart, double stageDt,
                    Eigen::VectorXd* q) const override;
  /// Over the links, the change of |c̈| + ρ ‖R̈‖ (ρ the link's RMS radius) over the last two steps
  /// [m/s²]: the material points' acceleration change.
  double ForceChange(const KindState& current, const KindState& previous, double hPrevious,
                     const KindState& before, double hBefore) const override;

  /// Carried frames: the links, each at its centre of mass c_l with its rotation R_l (the
  /// links' entries of q); their chart Jacobians and curvature from one forward kinematics of
  /// q's joint coordinates (KinematicTree::LinkChartJacobian, AddLinkChartCurvature).
  int NumCarriedFrames() const override { return NumLinks(); }
  int CarriedFrameOffset(int l) const override { return LinkOffset(l); }
  int CarriedFrameParent(int l) const override { return tree_.Joint(l).parent; }
  void CarriedFrameJacobians(const Eigen::VectorXd& q, const std::vector<FramePoint>& points,
                             std::vector<Eigen::MatrixXd>* A) const override;
  void AddCarriedFrameCurvature(const Eigen::VectorXd& q, const std::vector<FramePoint>& points,
                                const std::vector<Eigen::Matrix<double, 6, 1>>& loads,
                                Eigen::MatrixXd* H) const override;

  double KineticEnergy(const KindState& s) const override;
  double GravityEnergy(const KindState& s, const Eigen::Vector3d& gravity) const override;
  Eigen::Vector3d LinearMomentum(const KindState& s) const override;
  Eigen::Vector3d AngularMomentum(const KindState& s) const override;
  Eigen::Vector3d CenterOfMass(const KindState& s) const override;
  Eigen::Vector3d CenterOfMassVelocity(const KindState& s) const override;
  Aabb Bounds(const Eigen::VectorXd& q) const override;

 private:
  struct Link {
    double mass = 0.0;
    Eigen::Vector3d com = Eigen::Vector3d::Zero();          ///< link frame
    Eigen::Matrix3d secondMoment = Eigen::Matrix3d::Zero(); ///< J = ∫ X Xᵀ dm about the com
    double radius = 0.0;                                    ///< RMS radius √(tr J / m)
    JointParams joint;
    std::string name;
  };
  ArticulatedKind() = default;
  int LinkOffset(int l) const { return tree_.NumCoordinates() + 12 * l; }
  /// Writes every link's (c_l, vec R_l) of the joint coordinates in q into q.
  void WriteLinks(Eigen::VectorXd* q, KinematicFrames* frames) const;
  /// The link velocities and joint-coordinate rates of the tangent velocity u at q (links
  /// written, frames at q) into *v.
  void WriteVelocity(const Eigen::VectorXd& q, const KinematicFrames& frames,
                     const Eigen::VectorXd& u, Eigen::VectorXd* v) const;
  /// M(q) and Σ_l A_lᵀ [P_l; L_l] for link momenta (P, L) (6 per link), frames at q.
  void GeneralizedMomentum(const KinematicFrames& frames, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& linkMomenta, Eigen::MatrixXd* M,
                           Eigen::VectorXd* p) const;
  /// Σ of the joints' limit, damping and drive terms at q (derivatives into g and H's diagonal).
  double JointTerms(const KindStageData& stage, const Eigen::VectorXd& q, int order,
                    Eigen::VectorXd* g, Eigen::MatrixXd* H) const;
  /// Link momenta [m ċ; L] (6 per link) of the link velocities in (q, v).
  Eigen::VectorXd LinkMomenta(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;

  KinematicTree tree_;
  std::vector<Link> links_;
  KindState initial_;
};

}  // namespace superdex
