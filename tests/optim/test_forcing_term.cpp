// The Eisenstat–Walker forcing terms of the inexact Newton solves (optim/forcing_term.h).
#include <catch2/catch.hpp>

#include <cmath>

#include "optim/forcing_term.h"

using namespace superdex;

TEST_CASE("forcing terms: loose far from the solution, the floor in the quadratic phase",
          "[optim]") {
  ForcingTerm forcing(1e-8, -1);  // no converged solve before: η_0 = η_max
  CHECK(forcing.Next(10.0) == ForcingTerm::kEtaMax);  // no history: η_max
  CHECK(forcing.Next(9.0) == ForcingTerm::kEtaMax);   // slow decrease: capped at η_max
  // ‖F‖ 9 → 0.9: η = 0.9 · 0.1² = 9e-3.
  CHECK(forcing.Next(0.9) == Approx(0.9 * 0.01).epsilon(1e-15));
  // Quadratic convergence 0.9 → 8.1e-3 → 6.6e-5: η = 0.9 · (9e-3)² = 7.29e-5, then 0.9 · (8.1e-3)²
  // = 5.9e-5.
  CHECK(forcing.Next(8.1e-3) == Approx(0.9 * 9e-3 * 9e-3).epsilon(1e-12));
  CHECK(forcing.Next(6.561e-5) == Approx(0.9 * 8.1e-3 * 8.1e-3).epsilon(1e-12));
  // A tiny ratio: the floor.
  CHECK(forcing.Next(1e-12) == 1e-8);
  // A growing norm: capped at η_max again.
  CHECK(forcing.Next(1.0) == ForcingTerm::kEtaMax);
  // Non-finite norms give η_max and do not poison the next ratio.
  CHECK(forcing.Next(NAN) == ForcingTerm::kEtaMax);
  CHECK(forcing.Next(1.0) == ForcingTerm::kEtaMax);
  CHECK(forcing.Next(0.1) == Approx(0.9 * 0.01).epsilon(1e-15));
  // The floor wins over a looser η_max.
  ForcingTerm tight(0.5, -1);
  CHECK(tight.Next(1.0) == 0.5);
  // After a solve that converged within kTightStartIterations iterations the first solve is
  // exact (η_0 = floor), the later ones follow the ratio; after a longer one, η_0 = η_max.
  ForcingTerm quick(1e-8, ForcingTerm::kTightStartIterations);
  CHECK(quick.Next(1.0) == 1e-8);
  CHECK(quick.Next(0.5) == ForcingTerm::kEtaMax);
  ForcingTerm slow(1e-8, ForcingTerm::kTightStartIterations + 1);
  CHECK(slow.Next(1.0) == ForcingTerm::kEtaMax);
}
