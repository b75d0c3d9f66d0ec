#include "core/model/eval_params.h"

namespace superdex {

SUPERDEX_ENUM_NAMES(DissipationMode,
    {DissipationMode::ExplicitNormals, "ExplicitNormals"},
    {DissipationMode::ReconstructedLoad, "ReconstructedLoad"},
    {DissipationMode::ImplicitLoad, "ImplicitLoad"})

std::string Validate(const ExperimentalEvalParams& p, const std::string& prefix) {
  if (std::string m = ValidateFields(kExperimentalEvalFields, p, prefix); !m.empty()) return m;
  if (p.explicitNormals && p.implicitNormalForceForDissipation)
    return prefix +
           "explicit_normals, implicit_normal_force_for_dissipation: the combination "
           "(true, true) is unsupported";
  return "";
}

}  // namespace superdex
