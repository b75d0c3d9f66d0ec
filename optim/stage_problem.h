// The abstract problem the stage solvers work on: a scalar objective over a manifold of states,
// stepped by tangent vectors. optim/ knows nothing of physics: what the core's stage problem puts
// behind these hooks is in docs/optim-notes.md.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "optim/block_layout.h"
#include "optim/field_table.h"

namespace superdex {

/// How local (per-element) Hessians are made positive semi-definite before assembly. A projected
/// Hessian is a model for globalization, not the exact one: a problem may also replace a convex
/// term's exact Hessian by a majorizing one there. None asks for the exact Hessian.
enum class PsdProjection {
  None,   ///< exact Hessian (may be indefinite)
  Clamp,  ///< negative eigenvalues set to zero
  Abs,    ///< negative eigenvalues replaced by their absolute value
};
EnumNames<PsdProjection> NamesOf(PsdProjection);


/// How the objective of one evaluation splits into independent parts (StageProblem::LastSplit).
/// The dofs are grouped into units (e.g. a block of dofs); f is the sum of the units' shares, and
/// the only terms that couple units are those listed in `joins`: every term that was nonzero at
/// that state and involves two units. Units not linked through `joins` were independent there:
/// f's Hessian (the residual's Jacobian) has no entry between them. A unit may own no dof (an
/// actor without stage unknowns); its share is then constant and it takes no step.
struct StageSplit {
  std::vector<int> unitOfDof;                ///< per dof: its unit, 0 … units − 1
  int units = 0;
  std::vector<double> share;                 ///< per unit: its share of f at that state [J]
  std::vector<std::pair<int, int>> joins;    ///< units coupled by a term nonzero there
};

/// An objective f over states s of a manifold. The problem keeps a current state s; a tangent step
/// d in R^n moves it by the problem's retraction s ⊕ d (s + d on a vector space).
class StageProblem {
 public:
  virtual ~StageProblem() = default;

  /// Dimension n of the tangent space.
  virtual int NumDofs() const = 0;

  /// f(s ⊕ d) without changing s. Returns +infinity where f is undefined (e.g. inverted elements).
  virtual double Value(const Eigen::VectorXd& d) = 0;

  /// f(s), its gradient g = ∂f(s ⊕ d)/∂d at d = 0, and optionally the Hessian (full symmetric,
  /// compressed column) with local Hessians projected as `projection` says. hessian may be null.
  virtual double Evaluate(Eigen::VectorXd* gradient, Eigen::SparseMatrix<double>* hessian,
                          PsdProjection projection) = 0;

  /// s ← s ⊕ d.
  virtual void Commit(const Eigen::VectorXd& d) = 0;

  /// True when the stage is the minimization of Value: Evaluate's gradient is ∇f and the stage
  /// solves ∇f = 0. False for stages whose residual r is not a gradient (Value is then only a
  /// diagnostic, and the residual solvers use EvaluateResidual / Residual).
  virtual bool IsPotential() const { return true; }

  /// r(s ⊕ d) without changing s (the gradient, for a potential). Default: not provided.
  virtual void Residual(const Eigen::VectorXd& d, Eigen::VectorXd* r);

  /// r(s) and its Jacobian J = ∂r(s ⊕ δ)/∂δ at δ = 0 (compressed column; not symmetric in
  /// general). Default: not provided.
  virtual void EvaluateResidual(Eigen::VectorXd* r, Eigen::SparseMatrix<double>* J);

  /// r and J at s ⊕ d without changing s, entry for entry what EvaluateResidual returns after
  /// Commit(d) (so a solver that accepts the trial step d need not evaluate the new state again).
  /// Returns false when the problem does not provide it (the default).
  virtual bool EvaluateResidualAtStep(const Eigen::VectorXd& /*d*/, Eigen::VectorXd* /*r*/,
                                      Eigen::SparseMatrix<double>* /*J*/) {
    return false;
  }

  /// f, g and H at s ⊕ d without changing s, entry for entry what Evaluate returns after
  /// Commit(d); false when the problem does not provide it (the default).
  virtual bool EvaluateAtStep(const Eigen::VectorXd& /*d*/, double* /*value*/,
                              Eigen::VectorXd* /*gradient*/, Eigen::SparseMatrix<double>* /*hessian*/,
                              PsdProjection /*projection*/) {
    return false;
  }

  // --- Chart interface, for general-purpose solvers (Ipopt, Ceres) that iterate on a vector d of
  // a fixed chart s = s₀ ⊕ d. The chart's derivatives follow from the local ones by the tangent
  // map T(d), defined by s₀ ⊕ (d + ε) = (s₀ ⊕ d) ⊕ (T(d) ε) + O(ε²):
  //   ∇_d f = Tᵀ g,   ∂r/∂d = J T,   ∇²_d f = Tᵀ H T + (terms proportional to g, which vanish at
  //   a stationary point).

  /// Whether SetChartOrigin / MoveInChart / ChartTangentMap are provided.
  virtual bool SupportsChart() const { return false; }
  /// s₀ ← s.
  virtual void SetChartOrigin() {}
  /// s ← s₀ ⊕ d.
  virtual void MoveInChart(const Eigen::VectorXd& /*d*/) {}
  /// T(d) as a dense matrix (n × n; identity for vector spaces).
  virtual Eigen::MatrixXd ChartTangentMap(const Eigen::VectorXd& d) const {
    return Eigen::MatrixXd::Identity(d.size(), d.size());
  }

  /// Newton's global phase: may shorten the step d blockwise where the problem knows that its
  /// local model is unreliable (e.g. a constraint about to be crossed far deeper than the model
  /// sees). Returns true if d was changed. The solvers use the shortened step only when it is
  /// still a descent direction, and test convergence on the unshortened one. Default: no change.
  virtual bool LimitStep(Eigen::VectorXd* /*d*/) { return false; }

  /// Newton's trust region: may shorten a Newton correction d blockwise so that no part of the
  /// state moves farther in one iteration than the problem's local models can be trusted.
  /// Applied before LimitStep, to Newton corrections only (not to a warm start). Returns true if
  /// d was changed; the solvers then treat the step as LimitStep's. Default: no change.
  virtual bool TrustStep(Eigen::VectorXd* /*d*/) { return false; }

  /// The split (above) of the evaluation just made — Value, Evaluate, EvaluateAtStep, Residual,
  /// EvaluateResidual or EvaluateResidualAtStep — read before any other call. False (the
  /// default): the problem does not split, and the solvers treat it as one part.
  virtual bool LastSplit(StageSplit* /*split*/) { return false; }

  /// A norm of a step [m], used for the step convergence test. Default: max-norm.
  virtual double StepNorm(const Eigen::VectorXd& d) const { return d.lpNorm<Eigen::Infinity>(); }

  /// The diagonal blocks of the dofs (optim/block_layout.h), which the Krylov solves'
  /// block-Jacobi preconditioner inverts, into *layout (its storage reused). Default: blocks of
  /// 3 throughout.
  virtual void BlockLayout(DofBlockLayout* layout) const { layout->sizes.clear(); }
};

}  // namespace superdex
