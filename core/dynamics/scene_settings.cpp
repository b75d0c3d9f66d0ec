#include "core/dynamics/scene_settings.h"

#include <cctype>

namespace superdex {

SUPERDEX_ENUM_NAMES(
    StageSolverKind,
    {StageSolverKind::Newton, "newton", "projected Newton (potential stages), residual Newton"},
    {StageSolverKind::Ipopt, "ipopt", "potential stages only; a dense check for small scenes"},
    {StageSolverKind::Ceres, "ceres", "a dense check for small scenes"})

bool ParseName(const std::string& name, StageSolverKind* kind) {
  std::string lower = name;
  if (!lower.empty())
    lower[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(lower[0])));
  return Parse(lower, kind);
}

DissipationMode ModeOf(const ExperimentalEvalParams& e) {
  if (e.explicitNormals) return DissipationMode::ExplicitNormals;
  return e.implicitNormalForceForDissipation ? DissipationMode::ImplicitLoad
                                             : DissipationMode::ReconstructedLoad;
}

}  // namespace superdex
