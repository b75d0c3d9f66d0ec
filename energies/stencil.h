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

}  // namespace superdex
