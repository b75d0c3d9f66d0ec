// The diagonal blocks of a problem's dofs, as data: what a block preconditioner
// (optim/block_jacobi.h) inverts. A stage problem reports it (StageProblem::BlockLayout), the
// linear solvers take it (SymmetricSolver / UnsymmetricSolver::SetBlockLayout).
#pragma once

namespace superdex {

/// Dofs [0, 6 blocksOfSix) form `blocksOfSix` blocks of 6 coupled dofs; the rest, blocks of 3.
/// Where that does not tile the n dofs (6 blocksOfSix > n, or n − 6 blocksOfSix not a multiple of
/// 3) a preconditioner falls back to 1×1 blocks. The default: blocks of 3 throughout.
struct DofBlockLayout {
  int blocksOfSix = 0;
};

}  // namespace superdex
