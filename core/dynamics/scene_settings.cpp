#include "core/dynamics/scene_settings.h"

#include <cctype>

namespace superdex {

std::string Validate(const SceneSettings& s, const std::string& prefix) {
  if (!s.gravity.allFinite()) return prefix + "gravity: must be finite";
  if (std::string m = Validate(s.solver); !m.empty()) return prefix + "solver." + m;
  if (std::string m = Validate(s.eval); !m.empty()) return prefix + "experimental_eval_params." + m;
  if (!IsNamed(s.integrator)) return prefix + "integrator: must be one of " + AllNames(s.integrator);
  return "";
}

namespace {
constexpr EnumName<StageSolverKind> kStageSolvers[] = {
    {StageSolverKind::Newton, "newton", "projected Newton (potential stages), residual Newton"},
    {StageSolverKind::Ipopt, "ipopt", "potential stages only; a dense check for small scenes"},
    {StageSolverKind::Ceres, "ceres", "a dense check for small scenes"}};
}  // namespace

EnumNames<StageSolverKind> NamesOf(StageSolverKind) { return kStageSolvers; }

bool ParseStageSolver(const std::string& name, StageSolverKind* kind) {
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
