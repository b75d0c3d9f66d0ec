// A stage problem's data built by hand, as Scene::MakeStage builds it from states: rigid actors
// as RigidKinds and soft actors as SoftKinds, each with a chosen iterate, stage start x⁰, last
// configuration x_n and inertial target, and the contact pipeline configured over them. The
// iterate holds the actors' configurations in the order they were added; the stage dofs are
// their free tangent dofs in that order (6 per dynamic rigid actor, 3 per free soft node).
#pragma once

#include <memory>
#include <vector>

#include <catch2/catch.hpp>

#include "core/dynamics/scene_stage.h"
#include "core/model/rigid_kind.h"
#include "core/model/soft_kind.h"

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
  std::vector<std::unique_ptr<ActorKind>> kinds;
  KindStage stage;
  std::vector<Eigen::VectorXd> x;  ///< the iterate
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
    RigidKind& kind = *k;
    Add(std::move(k), RigidQ(pose), RigidQ(hat), RigidQ(start), RigidQ(start));
    return kind;
  }
  /// A soft actor (model m, created at `initial`) at positions x with the stage target t (its
  /// x̂, x⁰ and x_n).
  SoftKind& AddSoft(const SoftBodyModel& m, const SoftBodyState& initial,
                    const SoftStageTarget& t, const Eigen::VectorXd& at) {
    auto k = std::make_unique<SoftKind>(m, initial);
    SoftKind& kind = *k;
    Add(std::move(k), at, t.xHat, t.x0, t.xLast);
    return kind;
  }
  /// Actor k as the rigid actor it was added as.
  const RigidKind& Rigid(size_t k) const { return static_cast<const RigidKind&>(*kinds[k]); }
  /// Numbers the stage dofs (prescribed dofs: −1) and configures the pipeline; the actors'
  /// contact indices are their order of addition.
  void Finish() {
    kindPtrs_.clear();
    stage.stageDof.clear();
    numDofs = 0;
    std::vector<int> actor;
    for (const auto& k : kinds) {
      actor.push_back(static_cast<int>(kindPtrs_.size()));
      kindPtrs_.push_back(k.get());
      std::vector<int> dof(k->NumTangentDofs());
      for (int i = 0; i < k->NumTangentDofs(); ++i) dof[i] = k->IsPrescribed(i) ? -1 : numDofs++;
      stage.stageDof.push_back(dof);
    }
    stage.kinds = &kindPtrs_;
    pipeline.Configure(nullptr, &kindPtrs_, actor);
  }
  /// Rigid actor k's pose in an iterate.
  RigidPose Pose(const std::vector<Eigen::VectorXd>& at, size_t k) const {
    const Eigen::VectorXd& q = at[k];
    return {q.head<3>(), Eigen::Map<const Eigen::Matrix3d>(q.data() + 3)};
  }

 private:
  void Add(std::unique_ptr<ActorKind> k, const Eigen::VectorXd& q, const Eigen::VectorXd& qHat,
           const Eigen::VectorXd& q0, const Eigen::VectorXd& qLast) {
    KindStageData data;
    data.dt = dt;
    data.time = time;
    data.gravity = gravity;
    data.qHat = qHat;
    data.q0 = q0;
    data.qLast = qLast;
    k->PrepareStage(&data);
    stage.data.push_back(std::move(data));
    stage.q0.push_back(q0);
    stage.qLast.push_back(qLast);
    x.push_back(q);
    kinds.push_back(std::move(k));
  }
  std::vector<const ActorKind*> kindPtrs_;
};

}  // namespace superdex::test
