// A body of lumped-mass nodes in the generic actor layer (core/model/actor_kind.h): q = the node
// positions x (3 per node, [m]), v their velocities, a vector kind. What every such kind reports
// the same way is written here once: kinetic and gravity energy, momenta and centre of mass from
// the node masses m_a (Σ_a m_a = M), and the sensitivities' groups (one per node, so that nodes
// far apart are differenced in one run; Position and Velocity move every node alike, there is no
// AngularVelocity; c = Σ m_a x_a / M exactly). Soft (tet) and shell actors are node bodies.
#pragma once

#include <functional>
#include <vector>

#include "core/model/actor_kind.h"

namespace superdex {

class NodeBodyKind : public ActorKind {
 public:
  int NumNodes() const { return static_cast<int>(NodeMasses().size()); }
  /// The lumped node masses m_a [kg] and their total M [kg] (as the model accumulated it).
  virtual const Eigen::VectorXd& NodeMasses() const = 0;
  virtual double TotalMass() const = 0;

  /// ½ Σ m_a |v_a|², −Σ m_a g·x_a [J].
  double KineticEnergy(const KindState& s) const override;
  double GravityEnergy(const KindState& s, const Eigen::Vector3d& gravity) const override;
  Eigen::Vector3d LinearMomentum(const KindState& s) const override;
  Eigen::Vector3d AngularMomentum(const KindState& s) const override;
  Eigen::Vector3d CenterOfMass(const KindState& s) const override;
  Eigen::Vector3d CenterOfMassVelocity(const KindState& s) const override;
  /// A group per node: its x and v, its free tangent dofs.
  void DifferenceGroups(const KindState& s, std::vector<KindDifferenceGroup>* groups) const override;
  /// Position and Velocity: the nodes' unweighted mean, moved by moving every node alike.
  bool MotionParameter(KindMotion motion, int component, const KindState& s, double* value,
                       Eigen::VectorXd* direction) const override;
  Eigen::MatrixXd CenterOfMassJacobian(const KindState& s) const override;
  /// The nodes' bounds.
  Aabb Bounds(const Eigen::VectorXd& q) const override { return SoftBounds(q); }

 protected:
  /// A colliding sample on triangle F of the nodes at q: y = Σ_a b_a x_a (a Face map on the
  /// three nodes' dofs, their positions in faceNodes), weight w [m²], the face's index; no
  /// colliding normal (a kind with one adds it).
  static KindSample TriangleSample(const Eigen::Vector3i& F, const Eigen::Vector3d& bary,
                                   double weight, int face, const Eigen::VectorXd& q);
  /// ForEachSampleNear over triangles whose samples are grouped face by face (those of face f
  /// at [sampleBegin[f], sampleBegin[f+1])): a face is visited when keep accepts the larger of
  /// its balls at q and qLast (TriangleBall).
  static void VisitTriangleSamplesNear(
      const std::vector<Eigen::Vector3i>& faces, const std::vector<int>& sampleBegin,
      const Eigen::VectorXd& q, const Eigen::VectorXd& qLast,
      const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&, double)>& keep,
      const std::function<void(int, int)>& visit);
};

}  // namespace superdex
