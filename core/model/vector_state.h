// The state of an actor whose configuration is a plain vector (soft actors' node positions, and
// every kind of the generic actor layer, core/model/actor_kind.h): the integrators combine such
// states affinely, entry by entry.
#pragma once

#include <Eigen/Core>

namespace superdex {

/// Configuration x (soft actors: node positions [m], 3 per node; a kind: its q) and velocity
/// v = ẋ (same size).
struct VectorState {
  Eigen::VectorXd x;
  Eigen::VectorXd v;
};

}  // namespace superdex
