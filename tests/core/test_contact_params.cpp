#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "core/model/collider_params.h"
#include "core/model/contact_params.h"
#include "core/model/eval_params.h"
#include "core/model/soft_body.h"

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

TEST_CASE("soft material validation names the field and the rule", "[core][soft]") {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto check = [](double E, double nu, double rho, double beta = 0.0) {
    SoftMaterial m;
    m.youngsModulus = E;
    m.poissonRatio = nu;
    m.density = rho;
    m.stiffnessDamping = beta;
    return Validate(m);
  };
  CHECK(check(1e6, 0.3, 1000.0).empty());
  CHECK(check(1e6, -0.99, 1000.0).empty());
  CHECK(check(1e6, 0.499, 1000.0).empty());
  for (double E : {0.0, -1.0, inf, nan})
    CHECK(check(E, 0.3, 1000.0).rfind("youngs_modulus: must be finite and > 0, got ", 0) == 0);
  for (double nu : {0.5, -1.0, 0.7, nan, inf})
    CHECK(check(1e6, nu, 1000.0).rfind("poisson_ratio: must be in (-1, 0.5), got ", 0) == 0);
  for (double rho : {0.0, -5.0, inf, nan})
    CHECK(check(1e6, 0.3, rho).rfind("density: must be finite and > 0, got ", 0) == 0);
  CHECK(check(1e6, 0.3, 1000.0, -1.0) == "stiffness_damping: must be >= 0 and finite, got -1");
  CHECK(check(1e6, 0.5, 1000.0) == "poisson_ratio: must be in (-1, 0.5), got 0.5");
}

TEST_CASE("collider and evaluation parameters: validation messages", "[core]") {
  GridSdfParams g;
  CHECK(Validate(g).empty());
  g.minGridResolution = 1;
  CHECK(Validate(g, "grid_sdf.") == "grid_sdf.min_grid_resolution: must be >= 2, got 1");
  g = GridSdfParams();
  g.boundaryPaddingDist = -0.5;
  CHECK(Validate(g) == "boundary_padding_dist: must be >= 0, got -0.5");
  g = GridSdfParams();
  g.resolutionMode = static_cast<GridSdfResolutionMode>(7);
  CHECK(Validate(g) == "resolution_mode: must be MeanEdgeLength or BoundingExtent, got 7");
  PointCloudColliderParams p;
  CHECK(Validate(p).empty());
  p.spatialHashLoadFactor = 0.0;
  CHECK(Validate(p) == "spatial_hash_load_factor: must be > 0, got 0");
  ExperimentalEvalParams e;
  CHECK(Validate(e).empty());
  e.explicitNormals = e.implicitNormalForceForDissipation = true;
  CHECK(Validate(e, "x.") == "x.explicit_normals, implicit_normal_force_for_dissipation: the "
                             "combination (true, true) is unsupported");
  CHECK(std::string(ToString(GridSdfResolutionMode::BoundingExtent)) == "BoundingExtent");
  CHECK(std::string(ToString(DissipationMode::ImplicitLoad)) == "ImplicitLoad");
}
