#include <catch2/catch.hpp>
#include <cmath>

#include "core/model/contact_params.h"

using namespace superdex;

TEST_CASE("contact parameter combination follows the spec's rules", "[core]") {
  ContactParams a, b;
  a.penaltyCoefficient = 4e8;
  b.penaltyCoefficient = 9e8;
  a.frictionFalloffVel = 0.01;
  b.frictionFalloffVel = 0.04;
  a.coulombFrictionCoefficient = 0.25;
  b.coulombFrictionCoefficient = 1.0;
  a.viscousFrictionCoefficient = 2.0;
  b.viscousFrictionCoefficient = 8.0;
  a.normalViscousDampingCoefficient = 0.0;
  b.normalViscousDampingCoefficient = 3.0;
  a.penaltySmoothingHalfDistance = 0.1;
  b.penaltySmoothingHalfDistance = 0.002;
  a.penaltyThresholdDefault = 0.5;
  b.penaltyThresholdDefault = 0.003;
  b.penaltyThresholdExtraPadding = 0.004;
  a.collidingPenaltyLengthScale = 7.0;
  b.maxAlignmentNormals = -0.5;
  SECTION("both dynamic: geometric means of k and V_f") {
    const PairContactParams p = CombineContactParams(a, b, false, false);
    CHECK(p.penaltyCoefficient == Approx(6e8));
    CHECK(p.frictionFalloffVel == Approx(0.02));
    CHECK(p.coulombFrictionCoefficient == Approx(0.5));
    CHECK(p.viscousFrictionCoefficient == Approx(4.0));
    CHECK(p.normalViscousDampingCoefficient == 0.0);
    CHECK(p.smoothingHalfDistance == 0.002);
    CHECK(p.threshold == 0.003);
    CHECK(p.maxAlignmentNormals == -0.5);
    CHECK(p.collidingPenaltyLengthScale == 7.0);
  }
  SECTION("static collider: k and V_f from the colliding actor") {
    const PairContactParams p = CombineContactParams(a, b, true, false);
    CHECK(p.penaltyCoefficient == 4e8);
    CHECK(p.frictionFalloffVel == 0.01);
    CHECK(p.coulombFrictionCoefficient == Approx(0.5));
  }
  SECTION("colliding actor without a collider: the collider's extra padding joins delta") {
    const PairContactParams p = CombineContactParams(a, b, false, true);
    CHECK(p.threshold == Approx(0.007));
  }
  SECTION("validation names the field and the rule") {
    ContactParams c;
    c.frictionFalloffVel = 0.0;
    CHECK(Validate(c, "x.") == "x.friction_falloff_vel: must be > 0, got 0");
    c = ContactParams();
    c.maxAlignmentNormals = -1.5;
    CHECK(Validate(c) == "max_alignment_normals: must be in [-1, 1], got -1.5");
    CHECK(Validate(ContactParams()).empty());
  }
}
