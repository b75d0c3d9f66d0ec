#include "core/model/eval_params.h"

namespace superdex {

const char* ToString(DissipationMode mode) {
  switch (mode) {
    case DissipationMode::ExplicitNormals: return "ExplicitNormals";
    case DissipationMode::ReconstructedLoad: return "ReconstructedLoad";
    case DissipationMode::ImplicitLoad: return "ImplicitLoad";
  }
  return "Unknown";
}

std::string Validate(const ExperimentalEvalParams& p, const std::string& prefix) {
  if (p.explicitNormals && p.implicitNormalForceForDissipation)
    return prefix +
           "explicit_normals, implicit_normal_force_for_dissipation: the combination "
           "(true, true) is unsupported";
  return "";
}

}  // namespace superdex
