// ExperimentalEvalParams (spec: "Stage-Discrete Dissipation"): time levels of the dissipative terms.
#pragma once

#include <string>

namespace superdex {

/// The three supported dissipation evaluations (ExperimentalEvalParams), by the stage's
/// incremental-potential status: ExplicitNormals is an exact potential, the other two are not.
enum class DissipationMode { ExplicitNormals, ReconstructedLoad, ImplicitLoad };
const char* ToString(DissipationMode mode);

/// | explicitNormals | implicitNormalForceForDissipation | incremental-potential status        |
/// | true            | false                             | exact gradient of Δt_i R_i          |
/// | false (default) | false (default)                   | not a potential (residual solve)    |
/// | false           | true                              | not a potential (residual solve)    |
/// | true            | true                              | unsupported (Validate refuses it)   |
struct ExperimentalEvalParams {
  bool explicitNormals = false;                  ///< stage-start normals, alignment, plane, load
  bool implicitNormalForceForDissipation = false;///< current normal load scales dissipation
  bool fadeFriction = true;                      ///< alignment-based attenuation a = (m−s)/(m+1)
};

/// "" when supported; otherwise a message naming the fields and the rule.
std::string Validate(const ExperimentalEvalParams& params, const std::string& prefix = "");

}  // namespace superdex
