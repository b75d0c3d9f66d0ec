#include "core/eval_params.h"

namespace superdex {

std::string Validate(const ExperimentalEvalParams& p, const std::string& prefix) {
  if (p.explicitNormals && p.implicitNormalForceForDissipation)
    return prefix +
           "explicit_normals, implicit_normal_force_for_dissipation: the combination "
           "(true, true) is unsupported";
  return "";
}

}  // namespace superdex
