// Small dense vectors and matrices over the degrees of freedom an energy term touches.
#pragma once

#include <Eigen/Core>

namespace superdex {

/// Largest stencil an energy term may touch (a soft triangle's 9 plus a soft collider tet's 12,
/// rounded up). Stencil objects live on the stack: no heap allocation in the inner loops.
constexpr int kMaxStencil = 24;

using StencilVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxStencil, 1>;
using StencilMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxStencil, kMaxStencil>;

/// Stencils of up to two rigid bodies (12 dofs). A scene keeps one per candidate contact pair, so
/// their storage is sized for 12, not kMaxStencil: a quarter of the memory the contact sweeps
/// touch (4.6 kB → 1.2 kB per matrix).
constexpr int kMaxSmallStencil = 12;
using SmallStencilVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSmallStencil, 1>;
using SmallStencilMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxSmallStencil, kMaxSmallStencil>;

}  // namespace superdex
