// Forward kinematics of a link tree and its derivatives (kinematic_tree.h has the formulas).
#include "core/model/kinematic_tree.h"

#include <cmath>
#include <sstream>
#include <utility>

#include <Eigen/Geometry>

#include "core/model/rigid_math.h"

namespace superdex {
namespace {

Eigen::Matrix3d RotationAt(const Eigen::Ref<const Eigen::VectorXd>& q, int offset) {
  return Matrix3At(q, offset);
}

RigidPose Compose(const RigidPose& a, const RigidPose& b) {
  RigidPose c;
  c.R = a.R * b.R;
  c.p = a.p + a.R * b.p;
  return c;
}

}  // namespace

SUPERDEX_ENUM_NAMES(JointType,
    {JointType::Fixed, "Fixed", "no relative motion"},
    {JointType::Revolute, "Revolute", "rotation about an axis (1 dof, rad)"},
    {JointType::Prismatic, "Prismatic", "translation along an axis (1 dof, m)"},
    {JointType::Spherical, "Spherical", "any rotation about the joint origin (3 dofs)"},
    {JointType::Free, "Free", "any pose (6 dofs); a root's joint only"})

int JointCoordinates(JointType type) {
  switch (type) {
    case JointType::Fixed: return 0;
    case JointType::Revolute:
    case JointType::Prismatic: return 1;
    case JointType::Spherical: return 9;
    case JointType::Free: return 12;
  }
  return 0;
}

int JointTangentDofs(JointType type) {
  switch (type) {
    case JointType::Fixed: return 0;
    case JointType::Revolute:
    case JointType::Prismatic: return 1;
    case JointType::Spherical: return 3;
    case JointType::Free: return 6;
  }
  return 0;
}

int JointRotationOffset(JointType type) {
  return type == JointType::Spherical ? 0 : type == JointType::Free ? 3 : -1;
}

KinematicTree::KinematicTree(std::vector<KinematicJoint> joints) : joints_(std::move(joints)) {
  const int n = NumLinks();
  coordinateOffset_.resize(n);
  tangentOffset_.resize(n);
  ancestorDofs_.resize(n);
  int groups = 0;
  for (int l = 0; l < n; ++l) {
    const KinematicJoint& j = joints_[l];
    coordinateOffset_[l] = numCoordinates_;
    tangentOffset_[l] = numTangent_;
    numCoordinates_ += JointCoordinates(j.type);
    const int dofs = JointTangentDofs(j.type);
    for (int k = 0; k < dofs; ++k) {
      // A free joint's translations (its first three dofs) are one group, its rotations the next.
      const bool nextGroup = k == 0 || (j.type == JointType::Free && k == 3);
      if (nextGroup) ++groups;
      group_.push_back(groups - 1);
    }
    numTangent_ += dofs;
    if (j.parent >= 0 && j.parent < l) ancestorDofs_[l] = ancestorDofs_[j.parent];
    for (int k = 0; k < dofs; ++k) ancestorDofs_[l].push_back(tangentOffset_[l] + k);
  }
}

std::string KinematicTree::Validate() const {
  for (int l = 0; l < NumLinks(); ++l) {
    const KinematicJoint& j = joints_[l];
    std::ostringstream s;
    s << "joint of link " << l << ": ";
    if (j.parent < -1 || j.parent >= l) {
      s << "parent must be −1 (the world) or an earlier link, got " << j.parent;
      return s.str();
    }
    if (j.type == JointType::Free && j.parent != -1) {
      s << "a Free joint must join a root link to the world, its parent is link " << j.parent;
      return s.str();
    }
    const bool axial = j.type == JointType::Revolute || j.type == JointType::Prismatic;
    if (axial && !(std::abs(j.axis.norm() - 1.0) <= 1e-9)) {
      s << "axis must be a unit vector, has length " << j.axis.norm();
      return s.str();
    }
    const Eigen::Matrix3d& R = j.origin.R;
    if (!j.origin.p.allFinite() || !R.allFinite() ||
        !((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() <= 1e-9 &&
          R.determinant() > 0.0)) {
      s << "origin must be a finite pose with a rotation matrix";
      return s.str();
    }
  }
  return {};
}

Eigen::VectorXd KinematicTree::ZeroConfiguration() const {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(numCoordinates_);
  for (int l = 0; l < NumLinks(); ++l) {
    if (RotationCoordinate(l) >= 0) Matrix3At(&q, RotationCoordinate(l)).setIdentity();
  }
  return q;
}

void KinematicTree::Retract(ConstRef q, ConstRef delta, Eigen::Ref<Eigen::VectorXd> out) const {
  out = q;
  for (int l = 0; l < NumLinks(); ++l) {
    const int o = coordinateOffset_[l], t = tangentOffset_[l];
    switch (joints_[l].type) {
      case JointType::Fixed: break;
      case JointType::Revolute:
      case JointType::Prismatic: out[o] += delta[t]; break;
      case JointType::Spherical:
        Matrix3At(&out, o) = ExpSo3(delta.segment<3>(t)) * RotationAt(q, o);
        break;
      case JointType::Free:
        out.segment<3>(o) += delta.segment<3>(t);
        Matrix3At(&out, o + 3) = ExpSo3(delta.segment<3>(t + 3)) * RotationAt(q, o + 3);
        break;
    }
  }
}

void KinematicTree::TangentBetween(ConstRef from, ConstRef to, Eigen::VectorXd* delta) const {
  delta->setZero(numTangent_);
  for (int l = 0; l < NumLinks(); ++l) {
    const int o = coordinateOffset_[l], t = tangentOffset_[l];
    switch (joints_[l].type) {
      case JointType::Fixed: break;
      case JointType::Revolute:
      case JointType::Prismatic: (*delta)[t] = to[o] - from[o]; break;
      case JointType::Spherical:
        delta->segment<3>(t) = LogSo3(RotationAt(to, o) * RotationAt(from, o).transpose());
        break;
      case JointType::Free:
        delta->segment<3>(t) = to.segment<3>(o) - from.segment<3>(o);
        delta->segment<3>(t + 3) =
            LogSo3(RotationAt(to, o + 3) * RotationAt(from, o + 3).transpose());
        break;
    }
  }
}

void KinematicTree::Evaluate(ConstRef q, KinematicFrames* frames) const {
  frames->link.resize(NumLinks());
  frames->twist.assign(numTangent_, JointTwist());
  for (int l = 0; l < NumLinks(); ++l) {
    const KinematicJoint& j = joints_[l];
    const RigidPose pre = j.parent < 0 ? j.origin : Compose(frames->link[j.parent], j.origin);
    const int o = coordinateOffset_[l], t = tangentOffset_[l];
    RigidPose motion;
    JointTwist* tw = frames->twist.data() + t;
    switch (j.type) {
      case JointType::Fixed: break;
      case JointType::Revolute:
        motion.R = Eigen::AngleAxisd(q[o], j.axis).toRotationMatrix();
        tw[0].w = pre.R * j.axis;
        tw[0].v = pre.p.cross(tw[0].w);
        break;
      case JointType::Prismatic:
        motion.p = q[o] * j.axis;
        tw[0].v = pre.R * j.axis;
        break;
      case JointType::Spherical:
        motion.R = RotationAt(q, o);
        for (int c = 0; c < 3; ++c) {
          tw[c].w = pre.R.col(c);
          tw[c].v = pre.p.cross(tw[c].w);
        }
        break;
      case JointType::Free: {
        motion.p = q.segment<3>(o);
        motion.R = RotationAt(q, o + 3);
        const Eigen::Vector3d origin = pre.p + pre.R * motion.p;  // the link's origin
        for (int c = 0; c < 3; ++c) {
          tw[c].v = pre.R.col(c);
          tw[3 + c].w = pre.R.col(c);
          tw[3 + c].v = origin.cross(tw[3 + c].w);
        }
        break;
      }
    }
    frames->link[l] = Compose(pre, motion);
  }
}

void KinematicTree::PointJacobian(const KinematicFrames& frames, int l, const Eigen::Vector3d& x,
                                  Eigen::MatrixXd* J) const {
  J->setZero(3, numTangent_);
  for (int k : ancestorDofs_[l]) J->col(k) = frames.twist[k].w.cross(x) + frames.twist[k].v;
}

void KinematicTree::AddPointCurvature(const KinematicFrames& frames, int l,
                                      const Eigen::Vector3d& x, const Eigen::Vector3d& f,
                                      Eigen::MatrixXd* H) const {
  const std::vector<int>& dofs = ancestorDofs_[l];
  const int m = static_cast<int>(dofs.size());
  // f·(ω_j × ∂_k x) = ∂_k x · (f × ω_j): one cross product per dof and one dot per pair.
  Eigen::Matrix3Xd d(3, m), fw(3, m);
  for (int a = 0; a < m; ++a) {
    const JointTwist& tw = frames.twist[dofs[a]];
    d.col(a) = tw.w.cross(x) + tw.v;
    fw.col(a) = f.cross(tw.w);
  }
  for (int a = 0; a < m; ++a) {
    for (int b = a; b < m; ++b) {  // dofs are root first: a's group is outer of or equal to b's
      const bool same = group_[dofs[a]] == group_[dofs[b]];
      const double v = same ? 0.5 * (d.col(b).dot(fw.col(a)) + d.col(a).dot(fw.col(b)))
                            : d.col(b).dot(fw.col(a));
      (*H)(dofs[a], dofs[b]) += v;
      if (b != a) (*H)(dofs[b], dofs[a]) += v;
    }
  }
}

void KinematicTree::LinkChartJacobian(const KinematicFrames& frames, int l,
                                      const Eigen::Vector3d& c, Eigen::MatrixXd* A) const {
  A->setZero(6, numTangent_);
  for (int k : ancestorDofs_[l]) {
    A->block<3, 1>(0, k) = frames.twist[k].w.cross(c) + frames.twist[k].v;
    A->block<3, 1>(3, k) = frames.twist[k].w;
  }
}

void KinematicTree::LinkChartStep(const KinematicFrames& frames, int l, const Eigen::Vector3d& c,
                                  const Eigen::VectorXd& delta, Eigen::Vector3d* dc,
                                  Eigen::Vector3d* dphi) const {
  dc->setZero();
  dphi->setZero();
  for (int k : ancestorDofs_[l]) {
    *dc += (frames.twist[k].w.cross(c) + frames.twist[k].v) * delta[k];
    *dphi += frames.twist[k].w * delta[k];
  }
}

void KinematicTree::AddLinkChartCurvature(const KinematicFrames& frames, int l,
                                          const Eigen::Vector3d& c, const Eigen::Vector3d& f,
                                          const Eigen::Vector3d& tau, Eigen::MatrixXd* H) const {
  AddPointCurvature(frames, l, c, f, H);
  const std::vector<int>& dofs = ancestorDofs_[l];
  const int m = static_cast<int>(dofs.size());
  for (int a = 0; a < m; ++a) {
    const Eigen::Vector3d tw = tau.cross(frames.twist[dofs[a]].w);  // τ·(ω_a × ω_b) = ω_b·(τ × ω_a)
    for (int b = a + 1; b < m; ++b) {
      if (group_[dofs[a]] == group_[dofs[b]]) continue;  // one exponential: no rotation curvature
      const double v = 0.5 * frames.twist[dofs[b]].w.dot(tw);
      (*H)(dofs[a], dofs[b]) += v;
      (*H)(dofs[b], dofs[a]) += v;
    }
  }
}

}  // namespace superdex
