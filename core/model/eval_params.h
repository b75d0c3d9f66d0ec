// ExperimentalEvalParams (spec: "Stage-Discrete Dissipation"): time levels of the dissipative terms.
#pragma once

#include <string>

#include "optim/field_table.h"

namespace superdex {

/// The three supported dissipation evaluations (ExperimentalEvalParams), by the stage's
/// incremental-potential status: ExplicitNormals is an exact potential, the other two are not.
enum class DissipationMode { ExplicitNormals, ReconstructedLoad, ImplicitLoad };
EnumNames<DissipationMode> NamesOf(DissipationMode);

/// | explicitNormals | implicitNormalForceForDissipation | incremental-potential status        |
/// | true            | false                             | exact gradient of Δt_i R_i          |
/// | false (default) | false (default)                   | not a potential (residual solve)    |
/// | false           | true                              | not a potential (residual solve)    |
/// | true            | true                              | unsupported (Validate refuses it)   |
struct ExperimentalEvalParams {
  bool explicitNormals = false;
  bool implicitNormalForceForDissipation = false;
  bool fadeFriction = true;
};

inline constexpr auto kExperimentalEvalFields = std::make_tuple(
    MakeField("explicit_normals", &ExperimentalEvalParams::explicitNormals, "", NoRule(),
              "Stage-start normals, alignment, friction plane and load"),
    MakeField("implicit_normal_force_for_dissipation",
              &ExperimentalEvalParams::implicitNormalForceForDissipation, "", NoRule(),
              "Scale dissipation by the current normal load"),
    MakeField("fade_friction", &ExperimentalEvalParams::fadeFriction, "", NoRule(),
              "Alignment-based attenuation a = (m − s)/(m + 1) of dissipation"));

/// "" when supported; otherwise a message naming the fields and the rule.
std::string Validate(const ExperimentalEvalParams& params, const std::string& prefix = "");

}  // namespace superdex
