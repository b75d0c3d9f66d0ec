// The recorded slips of core/contact/slip_tape.h: lookup by pair and sample, and the three ways a sample's
// force is evaluated (exact, recorded, about the record).
#include <catch2/catch.hpp>

#include "core/contact/slip_tape.h"

using namespace superdex;

namespace {

DissipationCoefficients Coefficients() {
  DissipationCoefficients c;
  c.mu = 0.5;
  c.ct = 0.2;
  c.cn = 1.0;
  c.vf = 0.01;
  return c;
}

}  // namespace

TEST_CASE("Slip tape: pairs and samples are found by their names, missing ones are not",
          "[core][sensitivity]") {
  StageSlips stage;
  PairSlips a, b;
  a.samples = {{7, SlipReference()}, {2, SlipReference()}, {5, SlipReference()}};
  a.samples[0].second.sliding = true;  // key 7
  b.samples = {{0, SlipReference()}};
  stage.Add(4, 1, a);  // kind 4's samples on kind 1's field, added before (0, 3)
  stage.Add(0, 3, b);
  stage.Seal();
  CHECK(stage.Samples() == 4);
  PairSlips* found = stage.Find(4, 1);
  REQUIRE(found);
  // Sorted by key on Add: 2, 5, 7.
  CHECK(found->samples[0].first == 2);
  CHECK(found->samples[2].first == 7);
  REQUIRE(found->Find(7));
  CHECK(found->Find(7)->sliding);
  CHECK_FALSE(found->Find(5)->sliding);
  CHECK(found->Find(3) == nullptr);
  CHECK(found->Find(8) == nullptr);
  CHECK(stage.Find(1, 4) == nullptr);  // ordered pairs
  CHECK(stage.Find(0, 1) == nullptr);
  REQUIRE(stage.Find(0, 3));
  CHECK(stage.Find(0, 3)->samples.size() == 1);
  stage.Clear();
  CHECK(stage.Samples() == 0);
  CHECK(stage.Find(4, 1) == nullptr);
}

TEST_CASE("Slip tape: a sample's force is recorded, then evaluated about the record",
          "[core][sensitivity]") {
  const DissipationCoefficients c = Coefficients();
  const Eigen::Vector3d N(0, 0, 1);
  const Eigen::Vector3d V(3e-4, -1e-4, -0.02);  // in the stick band: |V_t| = 3.2e-4 < V_f
  const double lambda = 2e4;
  PairSlips slips;
  const DissipationDensity exact = EvaluateDissipation(lambda, N, V, c, DissipationHessian::None);
  // No use: exact.
  const DissipationDensity plain =
      EvaluateSampleDissipation(lambda, N, V, c, DissipationHessian::None, PairSlipUse(), 4);
  CHECK(plain.gradient == exact.gradient);
  // Recording: exact, and the slip kept under the key.
  const DissipationDensity recorded = EvaluateSampleDissipation(
      lambda, N, V, c, DissipationHessian::None, PairSlipUse{&slips, true}, 4);
  CHECK(recorded.gradient == exact.gradient);
  REQUIRE(slips.samples.size() == 1);
  CHECK(slips.samples[0].first == 4);
  CHECK_FALSE(slips.samples[0].second.sliding);
  CHECK((slips.samples[0].second.direction - Eigen::Vector3d(3, -1, 0).normalized()).norm() <
        1e-15);
  // Reading at a moved velocity: the force about the record, not the exact one.
  const Eigen::Vector3d moved = V + Eigen::Vector3d(-2e-4, 1e-4, 0);
  const DissipationDensity about = EvaluateSampleDissipation(
      lambda, N, moved, c, DissipationHessian::None, PairSlipUse{&slips, false}, 4);
  const DissipationDensity reference = EvaluateDissipation(
      lambda, N, moved, c, DissipationHessian::None, &slips.samples[0].second);
  const DissipationDensity exactMoved =
      EvaluateDissipation(lambda, N, moved, c, DissipationHessian::None);
  CHECK(about.gradient == reference.gradient);
  CHECK((about.gradient - exactMoved.gradient).norm() > 1e-6 * exactMoved.gradient.norm());
  // A key without a record: exact.
  const DissipationDensity other = EvaluateSampleDissipation(
      lambda, N, moved, c, DissipationHessian::None, PairSlipUse{&slips, false}, 5);
  CHECK(other.gradient == exactMoved.gradient);
}
