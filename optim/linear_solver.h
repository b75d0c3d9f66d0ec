// Sparse linear solves of the stage solvers: direct (CHOLMOD Cholesky, supernodal or simplicial by
// CHOLMOD's rule, with Eigen's SimplicialLDLT as fallback; KLU or UMFPACK LU) or Krylov (block-
// Jacobi-preconditioned conjugate gradients; BiCGSTAB) with the direct solve as fallback.
// See docs/solver.md; measurements behind the choices: docs/optim-notes.md.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>

#include "optim/block_layout.h"
#include "optim/field_table.h"

namespace superdex {

/// How a stage's linear systems are solved.
enum class LinearSolverKind {
  /// Iterative from kAutoIterativeUnknowns unknowns up, Direct below (docs/optim-notes.md).
  Auto,
  Direct,     ///< sparse Cholesky (symmetric) / LU (unsymmetric) on every system
  /// Block-Jacobi-preconditioned (optim/block_jacobi.h) conjugate gradients (symmetric) / BiCGSTAB
  /// (unsymmetric) to the relative residual `tolerance`; a system not solved within
  /// `maxIterations` falls back to Direct.
  Iterative,
};
/// "auto", "direct", "iterative".
EnumNames<LinearSolverKind> NamesOf(LinearSolverKind);
inline bool ParseLinearSolverKind(const std::string& name, LinearSolverKind* kind) {
  return Parse(name, kind);
}

/// Auto uses the iterative solvers from this many unknowns up.
constexpr Eigen::Index kAutoIterativeUnknowns = 3000;

struct LinearSolverSettings {
  LinearSolverKind kind = LinearSolverKind::Direct;
  /// Krylov: stop at ‖b − A x‖₂ <= tolerance ‖b‖₂ [-], in (0, 1). The Newton solvers loosen it
  /// per iteration to their forcing term η_k >= tolerance (optim/forcing_term.h): the iterations
  /// in Newton's quadratic phase are solved to `tolerance` itself.
  double tolerance = 1e-8;
  int maxIterations = 500;  ///< Krylov iterations before the direct fallback, >= 1
  bool operator==(const LinearSolverSettings& o) const {
    return kind == o.kind && tolerance == o.tolerance && maxIterations == o.maxIterations;
  }
};
/// The fields (optim/field_table.h), named as the scene file's settings.solver keys.
inline constexpr auto kLinearSolverFields = std::make_tuple(
    MakeField("linear_solver", &LinearSolverSettings::kind, "", NoRule(),
              "How each Newton iteration solves its linear system"),
    MakeField("linear_tolerance", &LinearSolverSettings::tolerance, "-", InOpen(0, 1),
              "Krylov relative residual tolerance"),
    MakeField("linear_max_iterations", &LinearSolverSettings::maxIterations, "",
              AtLeast(1, 100000000), "Krylov iterations before the direct fallback"));

/// The table of Validate (optim/field_table.h).
constexpr const auto& FieldsOf(const LinearSolverSettings&) { return kLinearSolverFields; }

/// What the last solve did.
struct LinearSolveInfo {
  bool iterative = false;     ///< a Krylov solve was run
  int iterations = 0;         ///< its iterations
  bool fellBack = false;      ///< it did not converge and the direct solve was used
};

/// What both solvers below share: the settings, the block layout of the Krylov solves'
/// preconditioner, the last solve's report. Not copyable (a solver owns its factors).
class LinearSolverBase {
 public:
  LinearSolverBase(const LinearSolverBase&) = delete;
  LinearSolverBase& operator=(const LinearSolverBase&) = delete;

  /// Direct by default.
  void SetSettings(const LinearSolverSettings& settings) { settings_ = settings; }
  /// The Krylov solves' block-Jacobi layout (optim/block_jacobi.h); blocks of 3 by default.
  void SetBlockLayout(const DofBlockLayout& layout) { layout_ = layout; }
  const LinearSolveInfo& LastSolve() const { return info_; }

 protected:
  LinearSolverBase() = default;
  ~LinearSolverBase() = default;

  LinearSolverSettings settings_;
  DofBlockLayout layout_;
  mutable LinearSolveInfo info_;  // written by the solves (SymmetricSolver's are const)
};

/// Solves H x = b for symmetric H (full storage, compressed column). Keeps the symbolic analysis
/// while the sparsity pattern stays the same between calls.
class SymmetricSolver : public LinearSolverBase {
 public:
  SymmetricSolver();
  ~SymmetricSolver();

  /// Factorizes H (only its lower triangle is read). Returns false if H is not positive definite
  /// for both backends, is empty or non-square, or has non-finite entries. Iterative: keeps a copy
  /// of H and its diagonal (the preconditioner); false if a diagonal entry is <= 0.
  bool Factorize(const Eigen::SparseMatrix<double>& H);
  /// Solves H x = b with the last factorization; all NaN if the last Factorize returned false
  /// (a failed attempt overwrites the previous factors). Iterative: conjugate gradients from
  /// x = 0; a direction of non-positive curvature (H is not positive definite) gives all NaN, as
  /// a failed Cholesky would; no convergence within maxIterations: the direct solve.
  Eigen::VectorXd Solve(const Eigen::VectorXd& b) const;
  /// The same into *x (resized only when its size differs: no allocation in a Newton loop on the
  /// dense and iterative backends; CHOLMOD allocates its own result).
  void Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const;
  /// "dense" (<= 48 unknowns), "cholmod", "ldlt" or "pcg": the backend of the last
  /// factorization; "none" if it failed.
  const char* Backend() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Solves J x = b for a general square J (compressed column): UMFPACK LU with the symmetric
/// strategy and a METIS ordering (for structurally symmetric matrices, nearly symmetric in value),
/// or KLU (Backend), a dense partial-pivoting LU up to 48 unknowns. Keeps the symbolic analysis while
/// the sparsity pattern stays the same between calls.
class UnsymmetricSolver : public LinearSolverBase {
 public:
  UnsymmetricSolver();
  ~UnsymmetricSolver();

  /// Factorizes J. Returns false if J is (numerically) singular. Iterative: keeps a copy of J and
  /// the block-Jacobi preconditioner; false only for non-finite entries.
  bool Factorize(const Eigen::SparseMatrix<double>& J);
  /// Solves with the last factorization. Iterative: BiCGSTAB from x = 0; no convergence within
  /// maxIterations (or a breakdown): the LU solve.
  Eigen::VectorXd Solve(const Eigen::VectorXd& b);
  /// The same into *x (resized only when its size differs; UMFPACK allocates its own workspace).
  void Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x);
  /// Solves Jᵀ x = b with the LU factors of the last factorization (made now if the last
  /// Factorize prepared the iterative solver); all NaN if J is singular.
  Eigen::VectorXd SolveTransposed(const Eigen::VectorXd& b);
  /// "dense" (<= 48 unknowns), "klu" or "umfpack" (KLU where its analysis estimates fewer than
  /// 40 flops per factor entry, UMFPACK where the factors fill in), "bicgstab" (iterative, not
  /// fallen back): the backend of the last factorization or solve.
  const char* Backend() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace superdex
