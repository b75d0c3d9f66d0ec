// Symmetric solves: a dense Cholesky for small systems (<= 48 unknowns); otherwise CHOLMOD LLᵀ
// (supernodal or simplicial by CHOLMOD's own flop-count rule) first, Eigen's SimplicialLDLT as the
// fallback; or (LinearSolverKind) block-Jacobi-preconditioned conjugate gradients with those as the
// fallback. Unsymmetric: KLU or UMFPACK (by KLU's fill estimate), or Eigen's BiCGSTAB with the same
// preconditioner and that LU as the fallback.
//
// Both backends read only the lower triangle of H (the full symmetric matrix is stored). The
// symbolic analysis (fill-reducing ordering, elimination tree, supernode structure) depends only
// on the sparsity pattern, so it is redone only when the compressed-column index arrays differ from
// those of the last analysis; the numeric factorization is redone on every call.
#include "optim/linear_solver.h"

#include "optim/bicgstab.h"
#include "optim/block_jacobi.h"
#include "optim/row_operator.h"

#include <klu.h>
#include <malloc.h>

#include <mutex>
#include <sstream>

#include <Eigen/Cholesky>
#include <Eigen/CholmodSupport>
#include <Eigen/LU>
#include <Eigen/UmfPackSupport>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <limits>
#include <vector>

namespace superdex {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

enum class BackendKind { None, Dense, Dense6, Cholmod, Ldlt, Pcg };
SUPERDEX_ENUM_NAMES(BackendKind,
    {BackendKind::None, "none"},
    {BackendKind::Dense, "dense"},
    {BackendKind::Dense6, "dense"},  // the same dense solve, on a 6 x 6 system
    {BackendKind::Cholmod, "cholmod"},
    {BackendKind::Ldlt, "ldlt"},
    {BackendKind::Pcg, "pcg"})

bool UseIterative(const LinearSolverSettings& s, Eigen::Index n) {
  return s.kind == LinearSolverKind::Iterative ||
         (s.kind == LinearSolverKind::Auto && n >= kAutoIterativeUnknowns);
}

// Below this size a dense Cholesky is cheaper than CHOLMOD's setup (a single rigid body: 6 dofs).
constexpr Eigen::Index kDenseLimit = 48;
// A pivot below this fraction of H's largest diagonal entry marks H as singular.
constexpr double kSingularPivot = 1e-12;

// The dense backends' factorization of H into their kept copy: true if positive definite.
template <typename Matrix, typename Llt>
bool FactorizeDense(const SparseMatrix& H, Matrix* copy, Llt* llt) {
  *copy = H;
  llt->compute(*copy);
  return llt->info() == Eigen::Success;
}

}  // namespace

/// CHOLMOD's LLᵀ with the factor's pivots readable: CHOLMOD chooses a supernodal or a simplicial
/// factorization by its own flop-count rule (CholmodAuto: supernodal from 40 flops per factor
/// entry), LLᵀ in both (final_ll, so that an indefinite matrix fails). The contact graphs of rigid
/// heaps have little fill and go simplicial: a 1000-sphere pile's Hessian (6000 unknowns)
/// factorizes in 0.7 ms there against 3.9 ms supernodal (whose BLAS calls and OpenMP region per
/// small supernode dominate); a 10k-tet soft body's goes supernodal (136 ms, against 276 ms).
class CholmodLlt : public Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> {
 public:
  CholmodLlt() {
    // A matrix that is not positive definite is an expected outcome here (the Newton solver
    // shifts it and retries): no CHOLMOD warning for each one.
    cholmod().print = 0;
    setMode(Eigen::CholmodAuto);
    cholmod().final_ll = 1;
  }
  /// min_j L_jj² of the last successful factorization (the pivots of H = L Lᵀ).
  double MinPivot() const {
    const cholmod_factor* L = m_cholmodFactor;
    const double* x = static_cast<const double*>(L->x);
    double least = std::numeric_limits<double>::infinity();
    if (L->is_super) {
      const auto* super = static_cast<const int*>(L->super);
      const auto* pi = static_cast<const int*>(L->pi);
      const auto* px = static_cast<const int*>(L->px);
      for (size_t s = 0; s < L->nsuper; ++s) {
        const int columns = super[s + 1] - super[s], rows = pi[s + 1] - pi[s];
        for (int j = 0; j < columns; ++j) {
          const double d = x[px[s] + j * rows + j];
          least = std::min(least, d * d);
        }
      }
    } else {
      const auto* p = static_cast<const int*>(L->p);
      for (size_t j = 0; j < L->n; ++j) least = std::min(least, x[p[j]] * x[p[j]]);
    }
    return least;
  }
};

struct SymmetricSolver::Impl {
  CholmodLlt cholmod;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt;
  Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> dense;
  Eigen::MatrixXd denseMatrix;   // the dense backend's copy of H (kept: no allocation per call)
  // One rigid body (6 unknowns: the drop, the incline, a tumbling body): the same Cholesky with
  // compile-time sizes, about a quarter of the dynamic-size factorization's instructions.
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  Eigen::LLT<Matrix6, Eigen::Lower> dense6;
  Matrix6 dense6Matrix;
  // Pattern (rows, outer and inner index arrays) of the last symbolic analysis.
  Eigen::Index rows = -1;
  std::vector<SparseMatrix::StorageIndex> outer, inner;
  bool cholmodAnalyzed = false;  // cholmod holds a valid analysis of the stored pattern
  bool ldltAnalyzed = false;     // ldlt holds a valid analysis of the stored pattern
  BackendKind backend = BackendKind::None;
  SparseMatrix compressed;       // scratch copy when the caller passes an uncompressed matrix
  // Conjugate gradients: the matrix, its block-Jacobi preconditioner, the iteration's vectors.
  SparseMatrix matrix;
  BlockJacobi preconditioner;
  RowOperator op;  // the matrix's products, parallel over rows
  Eigen::VectorXd r, z, p, q;

  bool SamePattern(const SparseMatrix& H) const {
    if (H.rows() != rows || static_cast<Eigen::Index>(outer.size()) != H.outerSize() + 1 ||
        static_cast<Eigen::Index>(inner.size()) != H.nonZeros())
      return false;
    return std::equal(outer.begin(), outer.end(), H.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), H.innerIndexPtr());
  }

  void StorePattern(const SparseMatrix& H) {
    rows = H.rows();
    outer.assign(H.outerIndexPtr(), H.outerIndexPtr() + H.outerSize() + 1);
    inner.assign(H.innerIndexPtr(), H.innerIndexPtr() + H.nonZeros());
    cholmodAnalyzed = ldltAnalyzed = false;
  }

  bool FactorizeCholmod(const SparseMatrix& H) {
    if (!cholmodAnalyzed) {
      cholmod.analyzePattern(H);
      // A failed analysis (e.g. out of memory) leaves no symbolic factor to factorize into.
      if (cholmod.cholmod().status < CHOLMOD_OK) return false;
      cholmodAnalyzed = true;
    }
    // CHOLMOD stops at the first non-positive pivot and reports it through L->minor < n, which
    // Eigen maps to NumericalIssue. The symbolic factor stays valid for the next call.
    cholmod.factorize(H);
    if (cholmod.cholmod().status < CHOLMOD_OK || cholmod.info() != Eigen::Success) return false;
    return cholmod.MinPivot() > kSingularPivot * LargestDiagonal(H);
  }

  /// A singular positive semi-definite H can come out with a pivot that is positive only by
  /// rounding (a graph Laplacian's last pivot, ~1e-16 of its diagonal): pivots up to
  /// kSingularPivot times H's largest diagonal entry are rejected like non-positive ones. Stage
  /// Hessians keep theirs far above that (the inertia M/Δt² on every rigid and soft dof).
  static double LargestDiagonal(const SparseMatrix& H) {
    double largest = 0.0;
    for (Eigen::Index k = 0; k < H.outerSize(); ++k)
      for (SparseMatrix::InnerIterator e(H, k); e; ++e)
        if (e.row() == e.col()) largest = std::max(largest, std::abs(e.value()));
    return largest;
  }

  bool FactorizeLdlt(const SparseMatrix& H) {
    if (!ldltAnalyzed) {
      ldlt.analyzePattern(H);
      ldltAnalyzed = true;
    }
    ldlt.factorize(H);
    // H = P^T L D L^T P with unit lower L is positive definite iff every D_ii > 0 (and singular
    // to rounding where one is that small).
    return ldlt.info() == Eigen::Success &&
           (ldlt.vectorD().array() > kSingularPivot * LargestDiagonal(H)).all();
  }
};

SymmetricSolver::SymmetricSolver() : impl_(new Impl) {}

SymmetricSolver::~SymmetricSolver() = default;

bool SymmetricSolver::Factorize(const Eigen::SparseMatrix<double>& H) {
  Impl& s = *impl_;
  s.backend = BackendKind::None;
  if (H.rows() != H.cols() || H.rows() == 0) return false;
  const SparseMatrix* A = &H;
  if (!H.isCompressed()) {
    s.compressed = H;
    s.compressed.makeCompressed();
    A = &s.compressed;
  }
  // A non-finite entry cannot be factorized meaningfully by either backend.
  if (!Eigen::Map<const Eigen::VectorXd>(A->valuePtr(), A->nonZeros()).allFinite()) return false;
  if (UseIterative(settings_, A->rows()) && A->rows() > kDenseLimit) {
    s.matrix = *A;
    s.preconditioner.SetLayout(layout_);
    s.preconditioner.compute(s.matrix);
    if (!s.preconditioner.PositiveDefinite()) return false;  // neither is the matrix
    s.op.Set(s.matrix);
    s.backend = BackendKind::Pcg;
    return true;
  }
  if (A->rows() <= kDenseLimit) {
    const bool six = A->rows() == 6;
    if (six ? FactorizeDense(*A, &s.dense6Matrix, &s.dense6)
            : FactorizeDense(*A, &s.denseMatrix, &s.dense)) {
      s.backend = six ? BackendKind::Dense6 : BackendKind::Dense;
      return true;
    }
    // Not positive definite: fall through to the sparse backends, which report the same.
  }
  if (!s.SamePattern(*A)) s.StorePattern(*A);
  if (s.FactorizeCholmod(*A)) {
    s.backend = BackendKind::Cholmod;
    return true;
  }
  if (s.FactorizeLdlt(*A)) {
    s.backend = BackendKind::Ldlt;
    return true;
  }
  return false;
}

Eigen::VectorXd SymmetricSolver::Solve(const Eigen::VectorXd& b) const {
  Eigen::VectorXd x;
  Solve(b, &x);
  return x;
}

void SymmetricSolver::Solve(const Eigen::VectorXd& b, Eigen::VectorXd* out) const {
  Impl& s = *impl_;
  info_ = LinearSolveInfo();
  Eigen::VectorXd& x = *out;
  if (s.backend == BackendKind::Pcg) {
    // Preconditioned conjugate gradients (M: the block-Jacobi blocks of H), x₀ = 0.
    const Eigen::Index n = b.size();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    info_.iterative = true;
    x.setZero(n);
    const double bNorm = b.norm();
    if (bNorm == 0.0) return;
    s.r = b;
    s.preconditioner.Apply(s.r, &s.z);
    s.p = s.z;
    double rz = s.r.dot(s.z);
    const double stop = settings_.tolerance * bNorm;
    for (int k = 0; k < settings_.maxIterations; ++k) {
      s.q.resize(n);
      s.op.Multiply(s.p.data(), s.q.data());  // q = H p, as Eigen's product forms it, in parallel
      const double curvature = s.p.dot(s.q);
      info_.iterations = k + 1;
      // pᵀHp <= 0: H is not positive definite (what a failed Cholesky reports).
      if (!(curvature > 0.0)) {
        x.setConstant(nan);
        return;
      }
      const double a = rz / curvature;
      x += a * s.p;
      s.r -= a * s.q;
      if (s.r.norm() <= stop) return;
      s.preconditioner.Apply(s.r, &s.z);
      const double rzNext = s.r.dot(s.z);
      s.p = s.z + (rzNext / rz) * s.p;
      rz = rzNext;
    }
    // Not converged: the direct solve of the same matrix.
    info_.fellBack = true;
    if (!s.SamePattern(s.matrix)) s.StorePattern(s.matrix);
    if (s.FactorizeCholmod(s.matrix)) {
      x = s.cholmod.solve(b);
    } else if (s.FactorizeLdlt(s.matrix)) {
      x = s.ldlt.solve(b);
    } else {
      x.setConstant(nan);
    }
    return;
  }
  switch (impl_->backend) {
    case BackendKind::Dense: x = impl_->dense.solve(b); return;
    case BackendKind::Dense6: x = impl_->dense6.solve(b); return;
    case BackendKind::Cholmod: x = impl_->cholmod.solve(b); return;
    case BackendKind::Ldlt: x = impl_->ldlt.solve(b); return;
    case BackendKind::Pcg:
    case BackendKind::None: break;
  }
  // No valid factorization (never factorized, or the last Factorize failed and overwrote it).
  x.setConstant(b.size(), std::numeric_limits<double>::quiet_NaN());
}

const char* SymmetricSolver::Backend() const { return ToString(impl_->backend); }

// Eigen's UMFPACK wrapper solves with J only; the adjoint pass needs Jᵀ x = b from the same
// factors (UMFPACK_At).
class UmfPackLUWithTranspose : public Eigen::UmfPackLU<SparseMatrix> {
 public:
  bool SolveTransposed(const Eigen::VectorXd& b, Eigen::VectorXd* x) {
    x->resize(b.size());
    const SparseMatrix& A = mp_matrix;
    return umfpack_di_solve(UMFPACK_At, A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(),
                            x->data(), b.data(), m_numeric, m_control.data(),
                            m_umfpackInfo.data()) == UMFPACK_OK;
  }
};

/// KLU's analysis, factors and settings, freed with it. KLU (left-looking LU with partial pivoting,
/// no BLAS) is the LU of systems with little fill: a rigid heap's contact Jacobian (1000-sphere
/// pile, 6000 unknowns: factorization 1.85 ms against UMFPACK's 5.1 ms, analysis 0.9 against 3.3
/// ms; 75-sphere pile 0.21 against 0.73 ms). UMFPACK's multifrontal BLAS kernels win where the
/// factors fill in (a 10k-tet soft body: 155 against 911 ms).
class KluLu {
 public:
  KluLu() { klu_defaults(&common_); }
  ~KluLu() { Clear(); }
  KluLu(const KluLu&) = delete;
  KluLu& operator=(const KluLu&) = delete;
  /// Orders A's pattern (BTF, then AMD per block); false if KLU cannot (out of memory).
  bool Analyze(SparseMatrix& A) {
    Clear();
    symbolic_ = klu_analyze(static_cast<int>(A.rows()), A.outerIndexPtr(), A.innerIndexPtr(),
                            &common_);
    return symbolic_ != nullptr;
  }
  /// KLU's estimate of the factorization's flops per entry of the factors (its fill measure).
  double FlopsPerFactorEntry() const {
    return symbolic_->est_flops / std::max(1.0, symbolic_->lnz + symbolic_->unz);
  }
  /// Factorizes A (the analyzed pattern); false if A is singular.
  bool Factorize(SparseMatrix& A) {
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    numeric_ = klu_factor(A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(), symbolic_, &common_);
    return numeric_ != nullptr && common_.status == KLU_OK;
  }
  /// x = A⁻¹ b (transposed: A⁻ᵀ b) with the last factors.
  bool Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x, bool transposed) {
    *x = b;
    const int n = static_cast<int>(b.size());
    return transposed ? klu_tsolve(symbolic_, numeric_, n, 1, x->data(), &common_) == 1
                      : klu_solve(symbolic_, numeric_, n, 1, x->data(), &common_) == 1;
  }

 private:
  void Clear() {
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    if (symbolic_) klu_free_symbolic(&symbolic_, &common_);
  }
  klu_common common_;
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
};

struct UnsymmetricSolver::Impl {
  /// Below this size a dense partial-pivoting LU is cheaper than UMFPACK's setup.
  static constexpr Eigen::Index kDenseLimit = 48;
  /// KLU below this many estimated flops per factor entry, UMFPACK from it (CHOLMOD's own
  /// supernodal switch; contact heaps measure about 10, tet meshes 100–600).
  static constexpr double kKluFlopsPerEntry = 40.0;
  UmfPackLUWithTranspose lu;
  KluLu klu;
  bool useKlu = false;  // the analyzed pattern is KLU's (else UMFPACK's)
  Eigen::PartialPivLU<Eigen::MatrixXd> denseLu;
  Eigen::MatrixXd denseMatrix;  // the dense backend's copy of J (kept: no allocation per call)
  bool dense = false;
  std::vector<SparseMatrix::StorageIndex> outer, inner;
  // UMFPACK's solve reads the matrix again (iterative refinement) and Eigen's wrapper keeps a
  // reference to it: the solver owns a copy, so that factors outlive the caller's matrix.
  SparseMatrix matrix;
  bool iterative = false;  // the last Factorize prepared BiCGSTAB, not the LU
  bool luValid = false;    // lu holds the factors of `matrix`
  // BiCGSTAB (optim/bicgstab.h) on the matrix's parallel products, block-Jacobi preconditioned.
  RowOperator op;
  BlockJacobi preconditioner;
  BiCgStabWorkspace krylov;

  bool FactorizeLu() {
    const bool same = SamePattern(matrix);
    if (!same) {
      // KLU's analysis decides (it is the cheaper one): KLU where the factors stay sparse.
      useKlu = klu.Analyze(matrix) && klu.FlopsPerFactorEntry() < kKluFlopsPerEntry;
      if (!useKlu) lu.analyzePattern(matrix);
      outer.assign(matrix.outerIndexPtr(), matrix.outerIndexPtr() + matrix.outerSize() + 1);
      inner.assign(matrix.innerIndexPtr(), matrix.innerIndexPtr() + matrix.nonZeros());
    }
    if (useKlu) {
      luValid = klu.Factorize(matrix);
    } else {
      lu.factorize(matrix);
      luValid = lu.info() == Eigen::Success;
    }
    return luValid;
  }

  /// x = J⁻¹ b (or J⁻ᵀ b) with the valid LU factors.
  bool SolveLu(const Eigen::VectorXd& b, Eigen::VectorXd* x, bool transposed) {
    if (useKlu) return klu.Solve(b, x, transposed);
    if (transposed) return lu.SolveTransposed(b, x);
    *x = lu.solve(b);
    return true;
  }

  bool SamePattern(const SparseMatrix& J) const {
    return static_cast<Eigen::Index>(outer.size()) == J.outerSize() + 1 &&
           static_cast<Eigen::Index>(inner.size()) == J.nonZeros() &&
           std::equal(outer.begin(), outer.end(), J.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), J.innerIndexPtr());
  }
};

namespace {

// UMFPACK allocates its numeric factors afresh at every factorization. glibc serves blocks above
// its mmap threshold (128 KB, adapting up to 32 MB) by mmap and returns them by munmap, so each
// factorization paid page faults, zeroing and TLB shootdowns: measured 4x the factorization
// itself on a 64-node soft cube (192 unknowns). Keeping such blocks on the heap (a threshold of
// 1 GiB for both mmap and trimming) lets the next factorization reuse them. Process-wide, once,
// and only where the UMFPACK solver is used.
void KeepLargeBlocksOnHeap() {
  static std::once_flag once;
  std::call_once(once, [] {
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
  });
}

}  // namespace

UnsymmetricSolver::UnsymmetricSolver() : impl_(new Impl) {
  KeepLargeBlocksOnHeap();
  // The stage Jacobians are structurally symmetric (the contact graph) and nearly symmetric in
  // value: UMFPACK's symmetric strategy (ordering of A + Aᵀ, diagonal pivots preferred) with a
  // nested-dissection ordering keeps the fill of 3D contact heaps down.
  impl_->lu.umfpackControl()(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
  impl_->lu.umfpackControl()(UMFPACK_ORDERING) = UMFPACK_ORDERING_METIS;
  // Allocate the numeric factor at its full estimated size: the default (0.7 of it) made every
  // factorization of a 10k-tet soft body grow its workspace and garbage-collect.
  impl_->lu.umfpackControl()(UMFPACK_ALLOC_INIT) = 1.0;
  // No iterative refinement: its (up to) two steps made a solve cost as much as half a
  // factorization (a 1000-sphere pile's Jacobian, 6000 unknowns: 2.35 ms against 0.15 ms), for a
  // residual that Newton's own iteration corrects anyway (‖Jx − b‖ 4.4e-12 with it, 5.4e-12 without).
  impl_->lu.umfpackControl()(UMFPACK_IRSTEP) = 0;
}

UnsymmetricSolver::~UnsymmetricSolver() = default;

bool UnsymmetricSolver::Factorize(const Eigen::SparseMatrix<double>& J) {
  Impl& s = *impl_;
  s.dense = J.rows() <= Impl::kDenseLimit;
  if (s.dense) {
    s.denseMatrix = J;
    s.denseLu.compute(s.denseMatrix);
    // PartialPivLU does not report singularity: check the pivots.
    const auto pivots = s.denseLu.matrixLU().diagonal().cwiseAbs();
    return pivots.minCoeff() > 1e-14 * std::max(pivots.maxCoeff(), 1e-300);
  }
  s.matrix = J;
  s.matrix.makeCompressed();
  s.luValid = false;
  s.iterative = UseIterative(settings_, J.rows());
  if (s.iterative) {
    if (!Eigen::Map<const Eigen::VectorXd>(s.matrix.valuePtr(), s.matrix.nonZeros()).allFinite())
      return false;
    s.op.Set(s.matrix);
    s.preconditioner.SetLayout(layout_);
    s.preconditioner.compute(s.matrix);
    return true;
  }
  return s.FactorizeLu();
}

const char* UnsymmetricSolver::Backend() const {
  const Impl& s = *impl_;
  if (s.dense) return "dense";
  if (s.iterative && !s.luValid) return "bicgstab";
  return s.useKlu ? "klu" : "umfpack";
}

Eigen::VectorXd UnsymmetricSolver::Solve(const Eigen::VectorXd& b) {
  Eigen::VectorXd x;
  Solve(b, &x);
  return x;
}

void UnsymmetricSolver::Solve(const Eigen::VectorXd& b, Eigen::VectorXd* out) {
  Impl& s = *impl_;
  info_ = LinearSolveInfo();
  Eigen::VectorXd& x = *out;
  if (s.dense) {
    x = s.denseLu.solve(b);
    return;
  }
  if (s.iterative && !s.luValid) {
    info_.iterative = true;
    // From x = 0, converged when the relative residual estimate is within the tolerance.
    const BiCgStabResult result = SolveBiCgStab(s.op, s.preconditioner, b, settings_.tolerance,
                                                settings_.maxIterations, &x, &s.krylov);
    info_.iterations = result.iterations;
    if (result.relativeResidual <= settings_.tolerance && x.allFinite()) return;
    // Not converged, or broken down: the LU of the same matrix (kept for further solves).
    info_.fellBack = true;
    if (!s.FactorizeLu()) {
      x.setConstant(b.size(), std::numeric_limits<double>::quiet_NaN());
      return;
    }
  }
  if (!s.SolveLu(b, &x, false)) x.setConstant(b.size(), std::numeric_limits<double>::quiet_NaN());
}

Eigen::VectorXd UnsymmetricSolver::SolveTransposed(const Eigen::VectorXd& b) {
  Impl& s = *impl_;
  info_ = LinearSolveInfo();
  if (s.dense) return s.denseLu.transpose().solve(b);
  Eigen::VectorXd x;
  if ((s.luValid || s.FactorizeLu()) && s.SolveLu(b, &x, true)) return x;
  return Eigen::VectorXd::Constant(b.size(), std::numeric_limits<double>::quiet_NaN());
}

SUPERDEX_ENUM_NAMES(LinearSolverKind,
    {LinearSolverKind::Auto, "auto", "iterative from 3000 unknowns up, direct below"},
    {LinearSolverKind::Direct, "direct", "sparse Cholesky / LU on every system"},
    {LinearSolverKind::Iterative, "iterative", "block-Jacobi CG / BiCGSTAB, direct fallback"})

}  // namespace superdex
