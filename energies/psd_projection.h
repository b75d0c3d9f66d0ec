// Projection of local (stencil) Hessians to positive semi-definite matrices.
#pragma once

#include "energies/stencil.h"

namespace superdex {

/// Replaces the negative eigenvalues of the symmetric matrix *H by zero, or by their absolute
/// values when `useAbsoluteValues`; eigenvectors are kept, so null spaces (e.g. rigid translation
/// invariance of a contact pair) are preserved. Skips the decomposition when H is already PSD by
/// a cheap test (a successful LDLT with non-negative pivots).
void ProjectToPsd(StencilMatrix* H, bool useAbsoluteValues);
void ProjectToPsd(SmallStencilMatrix* H, bool useAbsoluteValues);

}  // namespace superdex
