// The diagonal blocks of a problem's dofs, as data: what a block preconditioner
// (optim/block_jacobi.h) inverts. A stage problem reports it (StageProblem::BlockLayout), the
// linear solvers take it (SymmetricSolver / UnsymmetricSolver::SetBlockLayout).
#pragma once

#include <vector>

namespace superdex {

/// The sizes of consecutive blocks of coupled dofs from dof 0 on (each 3 or 6: a node's position,
/// a rigid body's [δp, δθ]); dofs after the listed blocks form blocks of 3. Where that does not
/// tile the n dofs (the sizes sum to more than n, a size is neither 3 nor 6, or the rest is not a
/// multiple of 3) a preconditioner falls back to 1×1 blocks. The default: blocks of 3 throughout.
struct DofBlockLayout {
  std::vector<int> sizes;
  /// `count` blocks of 6 first, then blocks of 3.
  static DofBlockLayout LeadingSix(int count) {
    DofBlockLayout layout;
    layout.sizes.assign(count > 0 ? count : 0, 6);
    return layout;
  }
  bool operator==(const DofBlockLayout& o) const { return sizes == o.sizes; }
};

}  // namespace superdex
