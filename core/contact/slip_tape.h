// The slips of a stage's dissipative samples at its recorded solution, for the sensitivities
// (core/sensitivity/sensitivity.h, core/sensitivity/step_linearization.h).
//
// Both derivative schemes difference the stage residual in its inputs (stage-start and last
// configurations, inertial targets, parameters) about the recorded solution. The dissipative
// force is only C¹ in the sample velocity: its Coulomb slope ρ'(V_t)/V_t has a kink at V_t = 0,
// where resting and sticking contacts sit (energies/contact_dissipation.h, SlipReference), and a
// central difference that straddles or nears it is O(η/V_f) off, for any step the rounding of
// the stage velocities allows (measured on a box spinning under a resting one: 1.3e-2 relative in
// a trajectory's derivative at the default step). So the recorded solution's slip of every
// sample (direction t* and branch) is kept, and the differenced runs evaluate the force about it
// (SlipReference): the same value and first derivatives at the recorded point, smooth around it,
// so that the differences converge at their design order.
//
// A sample is named by its pair (kind, colliding, collider) and its index in the colliding
// actor's sample list; a sample without a record (not dissipative at the recorded solution)
// evaluates the exact force.
#pragma once

#include <utility>
#include <vector>

#include "energies/contact_dissipation.h"

namespace superdex {

/// One pair's recorded slips by sample key, sorted.
struct PairSlips {
  std::vector<std::pair<int, SlipReference>> samples;
  const SlipReference* Find(int key) const;
};

/// How one pair's dissipation treats slips: record every sample's into `slips`, read them from
/// it (linearize), or neither (null: the exact force).
struct PairSlipUse {
  PairSlips* slips = nullptr;
  bool record = false;
};

/// One stage's record of the contact pipeline's pairs, named by its kind indices (colliding,
/// collider), sorted by them.
class StageSlips {
 public:
  void Clear() { pairs_.clear(); }
  /// Adds a pair's record (its samples are sorted here); call Seal after the last.
  void Add(int colliding, int collider, PairSlips slips);
  void Seal();
  /// The pair's record, or null.
  PairSlips* Find(int colliding, int collider);
  size_t Samples() const;

 private:
  struct Entry {
    int colliding, collider;
    PairSlips slips;
  };
  std::vector<Entry> pairs_;
};

/// R's density at one sample (EvaluateDissipation) under the pair's slip use: exact (and its slip
/// recorded under `key`), about the recorded slip of `key`, or exact.
DissipationDensity EvaluateSampleDissipation(double lambdaHat, const Eigen::Vector3d& N,
                                             const Eigen::Vector3d& V,
                                             const DissipationCoefficients& c,
                                             DissipationHessian hessian, const PairSlipUse& use,
                                             int key);

}  // namespace superdex
