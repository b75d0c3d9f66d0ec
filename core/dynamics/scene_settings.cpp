#include "core/dynamics/scene_settings.h"

namespace superdex {

std::string Validate(const SceneSettings& s, const std::string& prefix) {
  if (!s.gravity.allFinite()) return prefix + "gravity: must be finite";
  if (std::string m = Validate(s.solver); !m.empty()) return prefix + "solver." + m;
  if (std::string m = Validate(s.eval); !m.empty()) return prefix + "experimental_eval_params." + m;
  IntegrationMethod check;
  if (!Parse(ToString(s.integrator), &check))
    return prefix + "integrator: must be one of " + AllNames(s.integrator);
  return "";
}

const char* ToString(StageSolverKind kind) {
  switch (kind) {
    case StageSolverKind::Newton: return "newton";
    case StageSolverKind::Ipopt: return "ipopt";
    case StageSolverKind::Ceres: return "ceres";
  }
  return "unknown";
}

bool ParseStageSolver(const std::string& name, StageSolverKind* kind) {
  if (name == "newton" || name == "Newton") *kind = StageSolverKind::Newton;
  else if (name == "ipopt" || name == "Ipopt") *kind = StageSolverKind::Ipopt;
  else if (name == "ceres" || name == "Ceres") *kind = StageSolverKind::Ceres;
  else return false;
  return true;
}

DissipationMode ModeOf(const ExperimentalEvalParams& e) {
  if (e.explicitNormals) return DissipationMode::ExplicitNormals;
  return e.implicitNormalForceForDissipation ? DissipationMode::ImplicitLoad
                                             : DissipationMode::ReconstructedLoad;
}

}  // namespace superdex
