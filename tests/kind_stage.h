// A stage problem's data built by hand, as Scene::MakeSoftStage builds it from states: rigid
// actors as RigidKinds with a chosen iterate, stage start x⁰ (= x_n) and inertial target, soft
// actors with their stage targets, and the contact pipeline configured over them. The vector
// iterate holds the soft actors' positions, then the kinds' configurations; the stage dofs are the
// kinds' free dofs in order (6 per dynamic rigid actor), then the soft actors' free nodes.
#pragma once

#include <memory>
#include <vector>

#include <catch2/catch.hpp>

#include "core/dynamics/scene_stage.h"
#include "core/model/rigid_kind.h"

namespace superdex::test {

/// A rigid configuration q = [p, R column-major] (RigidKind::Pack).
inline Eigen::VectorXd RigidQ(const RigidPose& pose) {
  RigidBodyState s;
  s.p = pose.p;
  s.R = pose.R;
  return RigidKind::Pack(s).x;
}

struct HandStage {
  double dt = 0.01;  ///< Δt_i [s]
  double time = 0.0;  ///< the stage's time [s] (applied loads)
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.81);
  std::vector<std::unique_ptr<RigidKind>> kinds;
  std::vector<SoftBodyModel> soft;
  std::vector<Eigen::VectorXd> softX;  ///< the soft actors' positions (before Finish)
  SoftStage stage;
  std::vector<Eigen::VectorXd> x;  ///< the iterate (after Finish)
  ContactPipeline pipeline;
  int numDofs = 0;

  /// A rigid actor at `pose`, its stage starting at `start` (x⁰ = x_n) with the inertial
  /// target `hat` (p̂, R̂).
  RigidKind& AddRigid(const RigidActorDesc& d, const RigidPose& pose, const RigidPose& start,
                      const RigidPose& hat) {
    Error e;
    std::unique_ptr<RigidKind> k = RigidKind::Build(d, &e);
    INFO(e.message);
    REQUIRE(k);
    KindStageData data;
    data.dt = dt;
    data.time = time;
    data.gravity = gravity;
    data.qHat = RigidQ(hat);
    data.q0 = RigidQ(start);
    data.qLast = data.q0;
    stage.kinds.data.push_back(data);
    stage.kinds.q0.push_back(data.q0);
    stage.kinds.qLast.push_back(data.qLast);
    kindQ_.push_back(RigidQ(pose));
    kinds.push_back(std::move(k));
    return *kinds.back();
  }
  /// A soft actor at positions x with its stage target t (PrepareSoftDamping applied here).
  void AddSoft(const SoftBodyModel& m, SoftStageTarget t, const Eigen::VectorXd& at) {
    PrepareSoftDamping(m, &t);
    soft.push_back(m);
    stage.targets.push_back(t);
    stage.x0.push_back(t.x0);
    stage.xLast.push_back(t.xLast);
    softX.push_back(at);
  }
  /// Numbers the stage dofs (a kind's prescribed dofs: −1) and configures the pipeline; the
  /// actors' contact indices are the kinds' in order, then the soft actors'.
  void Finish() {
    kindPtrs_.clear();
    stage.kinds.stageDof.clear();
    numDofs = 0;
    for (const auto& k : kinds) {
      kindPtrs_.push_back(k.get());
      std::vector<int> dof(k->NumTangentDofs());
      for (int i = 0; i < k->NumTangentDofs(); ++i) dof[i] = k->IsPrescribed(i) ? -1 : numDofs++;
      stage.kinds.stageDof.push_back(dof);
    }
    stage.kinds.kinds = &kindPtrs_;
    stage.models = &soft;
    stage.dofOffset.clear();
    for (const SoftBodyModel& m : soft) {
      stage.dofOffset.push_back(numDofs);
      numDofs += 3 * m.numFree;
    }
    x = softX;
    x.insert(x.end(), kindQ_.begin(), kindQ_.end());
    std::vector<int> kindActor, softActor;
    for (size_t k = 0; k < kinds.size(); ++k) kindActor.push_back(static_cast<int>(k));
    for (size_t s = 0; s < soft.size(); ++s)
      softActor.push_back(static_cast<int>(kinds.size() + s));
    pipeline.Configure(nullptr, &soft, softActor, &kindPtrs_, kindActor);
  }
  /// Rigid actor k's pose in an iterate.
  RigidPose Pose(const std::vector<Eigen::VectorXd>& at, size_t k) const {
    const Eigen::VectorXd& q = at[soft.size() + k];
    return {q.head<3>(), Eigen::Map<const Eigen::Matrix3d>(q.data() + 3)};
  }

 private:
  std::vector<const ActorKind*> kindPtrs_;
  std::vector<Eigen::VectorXd> kindQ_;
};

}  // namespace superdex::test
