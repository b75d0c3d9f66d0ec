// A tree of links joined by joints in reduced coordinates: forward kinematics and its first and
// second derivatives in the joint coordinates, for the articulated actor (its inertia through
// the links' material points, and contact on its links through the generic assembler).
//
// Link l has one joint to its parent link (parent −1: the world). Its frame is the joint frame
// moved by the joint's motion (as in URDF, the child link's frame is the joint's frame):
//   T_l = T_parent(l) · origin_l · Motion_l(q_l),
// origin_l the joint frame in the parent's frame at zero motion. Motions and coordinates:
//   Fixed      none                                    q: 0 entries   δ: 0
//   Revolute   rotation by θ about the unit axis a     q: θ [rad]     δ: δθ
//   Prismatic  translation by s along the unit axis a  q: s [m]       δ: δs
//   Spherical  a rotation R_rel                        q: vec R_rel   δ: δφ ∈ R³, R_rel ← exp([δφ]×) R_rel
//   Free       a pose (p_rel, R_rel)                   q: [p_rel, vec R_rel]
//                                                      δ: [δp, δφ], p_rel ← p_rel + δp, R_rel ← exp([δφ]×) R_rel
// (vec column-major; δφ and δp in the joint's frame origin_l at zero motion, "the pre-frame").
// Revolute and prismatic coordinates move additively; spherical and free rotations as rigid
// rotations do.
//
// Derivatives. At a configuration, every tangent dof k moves the world by a twist (ω_k, v_k): a
// material point x of a link that has k among its ancestor dofs moves by
//   ∂x/∂δ_k = ω_k × x + v_k                                                 [m per unit of δ_k]
// (revolute: ω = axis, v = o × ω with o the joint origin; prismatic: ω = 0, v = axis; spherical
// and free rotation: ω = the pre-frame's axis e_c, about the joint origin; free translation: ω = 0,
// v = the pre-frame's e_c). The pose after a step δ is the product of the world exponentials of
// these twists, root group outermost, where a group is the dofs that share one exponential (a
// spherical joint's three rotations, a free joint's three translations or its three rotations;
// a 1-dof joint is a group of one). Hence, for dofs j and k of groups G_j, G_k, both ancestors of
// the link:
//   ∂²x/∂δ_j∂δ_k = ω_j × ∂x/∂δ_k                        G_j outer of G_k
//                = ½ (ω_j × ∂x/∂δ_k + ω_k × ∂x/∂δ_j)     G_j = G_k
// and the link's rotation R_l = exp([φ]×) R_l(0) about its own point has
//   ∂φ/∂δ_k = ω_k,   ∂²φ/∂δ_j∂δ_k = ½ ω_j × ω_k (G_j outer of G_k; 0 within a group).
// A link's rigid chart (c + δc, exp([δφ]×) R) about a point c (its centre of mass) therefore
// moves by A δ + ½ δᵀ C δ with A's columns [ω_k × c + v_k; ω_k] (LinkChartJacobian), and an
// energy E of the link's pose with chart gradient (f, τ) and chart Hessian H_E has, in δ,
//   ∇ = Aᵀ (f, τ),   ∇² = Aᵀ H_E A + Σ_jk (f · ∂²c/∂δ_j∂δ_k + τ · ∂²φ/∂δ_j∂δ_k)   (AddLinkChartCurvature).
// Units: lengths in m, angles in rad.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/model/rigid_body.h"
#include "optim/field_table.h"

namespace superdex {

enum class JointType { Fixed, Revolute, Prismatic, Spherical, Free };
EnumNames<JointType> NamesOf(JointType);  ///< "Fixed", "Revolute", "Prismatic", "Spherical", "Free"

/// One link's joint to its parent.
struct KinematicJoint {
  JointType type = JointType::Revolute;
  int parent = -1;                                   ///< parent link, −1: the world
  RigidPose origin;                                  ///< joint frame in the parent's frame
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();   ///< unit axis in the joint frame
};

/// The number of configuration entries and tangent dofs of a joint type.
int JointCoordinates(JointType type);
int JointTangentDofs(JointType type);
/// Where a joint's rotation starts among its coordinates and among its tangent dofs (the same
/// place in both: 0 for Spherical, 3 for Free, after the translation); −1 without one.
int JointRotationOffset(JointType type);

/// The world twist of one tangent dof: ∂x/∂δ = ω × x + v.
struct JointTwist {
  Eigen::Vector3d w = Eigen::Vector3d::Zero();  ///< ω [rad per unit of δ]
  Eigen::Vector3d v = Eigen::Vector3d::Zero();  ///< v [m per unit of δ]
};

/// The kinematics at one configuration: every link's world pose and every tangent dof's twist.
struct KinematicFrames {
  std::vector<RigidPose> link;
  std::vector<JointTwist> twist;
};

class KinematicTree {
 public:
  KinematicTree() = default;
  /// Links in order, each joint's parent earlier (checked by Validate).
  explicit KinematicTree(std::vector<KinematicJoint> joints);

  /// Empty when the tree is valid; else a message naming the joint and the rule (a parent that is
  /// not an earlier link, an axis that is not unit length, a free joint that is not at a root, an
  /// origin rotation that is not a rotation).
  std::string Validate() const;

  int NumLinks() const { return static_cast<int>(joints_.size()); }
  const KinematicJoint& Joint(int l) const { return joints_[l]; }
  int NumCoordinates() const { return numCoordinates_; }
  int NumTangentDofs() const { return numTangent_; }
  /// Link l's joint entries in q and in δ.
  int CoordinateOffset(int l) const { return coordinateOffset_[l]; }
  int TangentOffset(int l) const { return tangentOffset_[l]; }
  /// Link l's joint rotation (JointRotationOffset) in q and in δ; −1 without one.
  int RotationCoordinate(int l) const {
    const int r = JointRotationOffset(joints_[l].type);
    return r < 0 ? -1 : coordinateOffset_[l] + r;
  }
  int RotationTangent(int l) const {
    const int r = JointRotationOffset(joints_[l].type);
    return r < 0 ? -1 : tangentOffset_[l] + r;
  }
  /// The tangent dofs that move link l (its joint's and its ancestors'), root first; and the
  /// exponential group of a tangent dof (groups are numbered root first along every path).
  const std::vector<int>& AncestorDofs(int l) const { return ancestorDofs_[l]; }
  int GroupOf(int dof) const { return group_[dof]; }

  using ConstRef = Eigen::Ref<const Eigen::VectorXd>;

  /// The zero configuration: every angle and offset 0, every rotation the identity.
  Eigen::VectorXd ZeroConfiguration() const;
  /// out = q ⊕ δ (the joints' own rules above); out has NumCoordinates entries and may not alias q.
  void Retract(ConstRef q, ConstRef delta, Eigen::Ref<Eigen::VectorXd> out) const;
  void Retract(ConstRef q, ConstRef delta, Eigen::VectorXd* out) const {
    out->resize(numCoordinates_);
    Retract(q, delta, Eigen::Ref<Eigen::VectorXd>(*out));
  }
  /// The tangent step from `from` to `to` (the inverse of Retract; rotations by their logarithm).
  void TangentBetween(ConstRef from, ConstRef to, Eigen::VectorXd* delta) const;
  /// Forward kinematics at q: link poses and dof twists.
  void Evaluate(ConstRef q, KinematicFrames* frames) const;

  /// ∂x/∂δ (3 × NumTangentDofs, zero outside AncestorDofs(l)) of the world point x of link l.
  void PointJacobian(const KinematicFrames& frames, int l, const Eigen::Vector3d& x,
                     Eigen::MatrixXd* J) const;
  /// Adds Σ_jk f·∂²x/∂δ_j∂δ_k into *H (NumTangentDofs square) for the world point x of link l.
  void AddPointCurvature(const KinematicFrames& frames, int l, const Eigen::Vector3d& x,
                         const Eigen::Vector3d& f, Eigen::MatrixXd* H) const;
  /// A (6 × NumTangentDofs): the rigid chart [δc; δφ] of link l about the world point c per δ.
  void LinkChartJacobian(const KinematicFrames& frames, int l, const Eigen::Vector3d& c,
                         Eigen::MatrixXd* A) const;
  /// A δ without forming A: the chart's move (δc, δφ) of link l about the world point c for the
  /// tangent step (or rate) δ.
  void LinkChartStep(const KinematicFrames& frames, int l, const Eigen::Vector3d& c,
                     const Eigen::VectorXd& delta, Eigen::Vector3d* dc,
                     Eigen::Vector3d* dphi) const;
  /// Adds Σ_jk (f·∂²c/∂δ_j∂δ_k + τ·∂²φ/∂δ_j∂δ_k) into *H for link l's chart about c.
  void AddLinkChartCurvature(const KinematicFrames& frames, int l, const Eigen::Vector3d& c,
                             const Eigen::Vector3d& f, const Eigen::Vector3d& tau,
                             Eigen::MatrixXd* H) const;

 private:
  std::vector<KinematicJoint> joints_;
  std::vector<int> coordinateOffset_, tangentOffset_, group_;
  std::vector<std::vector<int>> ancestorDofs_;
  int numCoordinates_ = 0;
  int numTangent_ = 0;
};

}  // namespace superdex
