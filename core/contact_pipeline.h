// The contact pipeline over rigid actors (spec: "Contact Pipeline"): broad phase over actor
// bounding boxes, narrow phase of colliding samples against collider fields, response into the
// stage's gradient and Hessian.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "core/rigid_body.h"
#include "core/rigid_contact.h"
#include "optim/stage_problem.h"

namespace superdex {

/// What the last evaluation saw.
struct ContactStats {
  int candidatePairs = 0;      ///< ordered pairs after broad phase and role/filter checks
  int activePairs = 0;         ///< pairs with at least one sample below its threshold
  int activeSamples = 0;       ///< samples with φ < δ
  double minSignedDistance = INFINITY;  ///< smallest φ over tested samples [m]
  double energy = 0.0;         ///< Σ Π_{A,B} [J]
};

/// Ordered pair (A colliding, B collider) with its combined parameters.
struct ContactPair {
  int colliding = -1;
  int collider = -1;
  PairContactParams params;
};

class ContactPipeline {
 public:
  /// Precomputes per-actor data. `models` must outlive the pipeline's use.
  void Configure(const std::vector<RigidBodyModel>* models);

  /// Π = Σ over eligible ordered pairs of the penalty energy at the given poses. order 0: value;
  /// 1: also adds the gradient into *gradient (dofs at dofOffset[i], −1 for static actors);
  /// 2: also appends Hessian triplets, with each pair's 6×6 or 12×12 block projected per
  /// `projection`. Pairs are evaluated in parallel; results are reduced in a fixed order, so the
  /// output does not depend on the number of threads.
  double Evaluate(const std::vector<RigidPose>& poses, const std::vector<int>& dofOffset,
                  int order, PsdProjection projection, Eigen::VectorXd* gradient,
                  std::vector<Eigen::Triplet<double>>* triplets, ContactStats* stats);

  /// The ordered pairs found by the last evaluation.
  const std::vector<ContactPair>& Pairs() const { return pairs_; }

 private:
  void FindPairs(const std::vector<RigidPose>& poses);

  const std::vector<RigidBodyModel>* models_ = nullptr;
  std::vector<double> inflation_;  // per actor: its collider reach padding [m]
  std::vector<Aabb> boxes_;
  std::vector<std::pair<int, int>> overlaps_;
  std::vector<ContactPair> pairs_;
  std::vector<RigidPairPenalty> results_;
};

}  // namespace superdex
