#include "scenes/fit.h"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/sensitivity/adjoint.h"
#include "geometry/number_text.h"
#include "scenes/json_text.h"
#include "scenes/limits.h"
#include "scenes/scene_writer.h"

namespace superdex {
namespace {

using json = nlohmann::json;

// Records why a fit or gradient failed; returns false for `return Failed(...)`.
bool Failed(FitFailure* failure, FitFailure kind) {
  if (failure) *failure = kind;
  return false;
}

// A simulation's failure: a stage that did not converge, or bad input.
FitFailure SimulationFailure(const Error& e) {
  return e.message.find("converge") != std::string::npos ? FitFailure::Simulation
                                                         : FitFailure::Input;
}

// One observed centre of mass: at step `step`, actor `actor`.
struct Observation {
  int step = 0;
  ActorHandle actor;
  Eigen::Vector3d position;
};

// Simulates the scene with parameters θ and fills the residuals (simulated − observed, 3 per
// observation) and, when J is given, their Jacobian from the forward sensitivities.
class TrajectoryProblem {
 public:
  TrajectoryProblem(const Scene& base, std::vector<SceneParameter> params,
                    std::vector<Observation> obs, double dt, int steps)
      : base_(base), params_(std::move(params)), obs_(std::move(obs)), dt_(dt), steps_(steps) {}

  int NumResiduals() const { return 3 * static_cast<int>(obs_.size()); }

  bool Simulate(const std::vector<double>& theta, double* residuals, Eigen::MatrixXd* J,
                Error* error) {
    ++simulations_;
    Scene scene = base_;
    for (size_t j = 0; j < params_.size(); ++j)
      if (!SetParameterValue(&scene, params_[j], theta[j], error)) return false;
    ForwardSensitivity sens;
    if (J && !sens.Begin(&scene, params_, error)) return false;
    size_t next = 0;
    for (int n = 0; n <= steps_; ++n) {
      if (n > 0) {
        StepReport rep;
        if (J) {
          if (!sens.Step(dt_, &rep, error)) return false;
        } else {
          if (!scene.Step(dt_, &rep, error)) return false;
          if (rep.status != StageStatus::Converged)
            return Fail(error, "step " + std::to_string(n) + ": a stage did not converge (" +
                                   rep.message + ")");
        }
      }
      for (; next < obs_.size() && obs_[next].step == n; ++next) {
        const Observation& o = obs_[next];
        Eigen::Map<Eigen::Vector3d>(residuals + 3 * next) = scene.CenterOfMass(o.actor) - o.position;
        if (J) J->middleRows(3 * next, 3) = sens.CenterOfMassJacobian(o.actor);
      }
    }
    return true;
  }
  int Simulations() const { return simulations_; }
  const std::string& LastError() const { return lastError_; }
  void SetLastError(const std::string& e) { lastError_ = e; }

 private:
  const Scene& base_;
  std::vector<SceneParameter> params_;
  std::vector<Observation> obs_;
  double dt_;
  int steps_;
  int simulations_ = 0;
  std::string lastError_;
};

class TrajectoryCost : public ceres::CostFunction {
 public:
  explicit TrajectoryCost(TrajectoryProblem* problem, int numParams) : problem_(problem) {
    set_num_residuals(problem->NumResiduals());
    for (int j = 0; j < numParams; ++j) mutable_parameter_block_sizes()->push_back(1);
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const int P = static_cast<int>(parameter_block_sizes().size());
    std::vector<double> theta(P);
    for (int j = 0; j < P; ++j) theta[j] = parameters[j][0];
    Eigen::MatrixXd J;
    if (jacobians) J.resize(num_residuals(), P);
    Error error;
    if (!problem_->Simulate(theta, residuals, jacobians ? &J : nullptr, &error)) {
      problem_->SetLastError(error.message);
      return false;  // Ceres rejects the step and shrinks its trust region
    }
    if (!Eigen::Map<Eigen::VectorXd>(residuals, num_residuals()).allFinite() ||
        (jacobians && !J.allFinite())) {
      problem_->SetLastError("non-finite residuals or Jacobian");
      return false;
    }
    if (jacobians)
      for (int j = 0; j < P; ++j)
        if (jacobians[j])
          for (int r = 0; r < num_residuals(); ++r) jacobians[j][r] = J(r, j);
    return true;
  }

 private:
  TrajectoryProblem* problem_;
};

}  // namespace

namespace {

// One frame line of an observed trajectory into *f; "" or the defect.
std::string ReadFrame(const json& j, size_t actors, ObservedFrame* f) {
  if (!j.is_object() || !j.contains("t") || !j["t"].is_number())
    return "a frame needs a number \"t\" [s]";
  if (!j.contains("actors") || !j["actors"].is_array() || j["actors"].size() != actors)
    return "a frame needs \"actors\" with one entry per header actor (" + std::to_string(actors) +
           ")";
  f->time = j["t"].get<double>();
  for (const json& a : j["actors"]) {
    if (a.is_object() && a.contains("p")) {
      const json& p = a["p"];
      if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() ||
          !p[2].is_number())
        return "actors[].p: expected [x, y, z] in m";
      f->position.emplace_back(
          Eigen::Vector3d(p[0].get<double>(), p[1].get<double>(), p[2].get<double>()));
    } else {
      f->position.emplace_back(std::nullopt);
    }
  }
  return "";
}

}  // namespace

bool ReadObservedTrajectory(const std::string& path, ObservedTrajectory* out, Error* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Fail(error, "observed: cannot read \"" + path + "\"");
  *out = ObservedTrajectory();
  std::string line;
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    const bool unterminated = in.eof();  // the file ends without a newline after this line
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = path + ":" + std::to_string(lineNo) + ": ";
    json j;
    std::string why;
    if (!ParseJsonText(line, &j, &why)) {
      if (unterminated && !out->actors.empty()) {  // a killed writer's last, partial line
        out->notes.push_back(where + "the last line is truncated (no newline, not valid JSON): "
                                     "skipped");
        break;
      }
      return Fail(error, where + why);
    }
    if (out->actors.empty()) {
      if (!j.is_object() || !j.contains("actors") || !j["actors"].is_array())
        return Fail(error, where + "the header line needs \"actors\": [{\"name\": …}, …]");
      for (const json& a : j["actors"]) {
        if (!a.is_object() || !a.contains("name") || !a["name"].is_string())
          return Fail(error, where + "header actors[]: every entry needs a string \"name\"");
        out->actors.push_back(a["name"].get<std::string>());
      }
      if (out->actors.empty()) return Fail(error, where + "the header names no actors");
      continue;
    }
    ObservedFrame f;
    if (std::string m = ReadFrame(j, out->actors.size(), &f); !m.empty())
      return Fail(error, where + m);
    out->frames.push_back(std::move(f));
  }
  if (in.bad()) return Fail(error, "observed: reading \"" + path + "\" failed");
  if (out->actors.empty()) return Fail(error, "observed: \"" + path + "\" is empty");
  if (out->frames.empty()) return Fail(error, "observed: \"" + path + "\" has no frames");
  return true;
}

namespace {

// The parameters and the observations on the step grid, from the user's input.
struct FitSetup {
  std::vector<SceneParameter> params;
  std::vector<Observation> obs;  // sorted by step
  double dt = 0.0;
  int steps = 0;
};

bool PrepareFit(const SceneFile& file, const ObservedTrajectory& observed,
                const FitOptions& options, FitSetup* setup, Error* error) {
  const Scene& base = *file.scene;
  const double dt = options.dt.value_or(file.dt);
  if (!(dt > 0 && std::isfinite(dt)))
    return Fail(error, "dt: must be > 0 and finite, got " + NumberText(dt));
  if (options.parameters.empty()) return Fail(error, "params: name at least one parameter");
  if (options.maxIterations < 1) return Fail(error, "max_iterations: must be >= 1");
  std::vector<SceneParameter> params(options.parameters.size());
  for (size_t j = 0; j < params.size(); ++j)
    if (!ParseSceneParameter(base, options.parameters[j], &params[j], error)) return false;
  // Observations on the step grid.
  std::vector<Observation> obs;
  int steps = 0;
  for (size_t k = 0; k < observed.frames.size(); ++k) {
    const ObservedFrame& f = observed.frames[k];
    const double n = std::round(f.time / dt);
    if (f.time >= 0 && !(n <= limits::kMaxFitSteps))  // checked in double, before any cast
      return Fail(error, "observed frame " + std::to_string(k) + ": t = " + NumberText(f.time) +
                             " s is step " + NumberText(n) + " at dt = " + NumberText(dt) +
                             " s, beyond the limit of " + NumberText(limits::kMaxFitSteps) +
                             " steps per fit (the adjoint keeps every step: about " +
                             NumberText(n * limits::kBytesPerFitStep / 1e9) + " GB)");
    if (f.time < 0 || std::abs(n * dt - f.time) > 1e-9 * std::max(1.0, f.time))
      return Fail(error, "observed frame " + std::to_string(k) + ": t = " + std::to_string(f.time) +
                             " s is not a multiple of dt = " + std::to_string(dt) + " s");
    for (size_t a = 0; a < f.position.size(); ++a) {
      if (!f.position[a]) continue;
      const ActorHandle h = base.FindActor(observed.actors[a]);
      if (!h.IsValid())
        return Fail(error, "observed: actor '" + observed.actors[a] + "' is not in the scene");
      obs.push_back({static_cast<int>(n), h, *f.position[a]});
      steps = std::max(steps, static_cast<int>(n));
    }
  }
  if (obs.empty()) return Fail(error, "observed: no actor position in any frame");
  std::stable_sort(obs.begin(), obs.end(),
                   [](const Observation& a, const Observation& b) { return a.step < b.step; });
  *setup = {std::move(params), std::move(obs), dt, steps};
  return true;
}

// The cost ½ Σ r² and its gradient in θ by one simulation and one adjoint pass.
bool AdjointCost(const Scene& base, const FitSetup& setup, const std::vector<double>& theta,
                 double* cost, Eigen::VectorXd* gradient, TrajectoryGradient* stats,
                 Error* error, FitFailure* failure) {
  Scene scene = base;
  for (size_t j = 0; j < setup.params.size(); ++j)
    if (!SetParameterValue(&scene, setup.params[j], theta[j], error))
      return Failed(failure, FitFailure::Input);
  AdjointSensitivity adjoint;
  if (!adjoint.Run(&scene, std::vector<double>(setup.steps, setup.dt), nullptr, error))
    return Failed(failure, SimulationFailure(*error));
  // First observation of each step, and each observed actor's centre-of-mass map.
  std::vector<size_t> first(setup.steps + 2, setup.obs.size());
  for (size_t k = setup.obs.size(); k-- > 0;) first[setup.obs[k].step] = k;
  for (int n = setup.steps; n >= 0; --n) first[n] = std::min(first[n], first[n + 1]);
  std::vector<Eigen::SparseMatrix<double>> com(scene.NumActors());
  for (const Observation& o : setup.obs)
    if (com[o.actor.index].cols() == 0) com[o.actor.index] = CenterOfMassMap(scene, o.actor);
  *cost = 0.0;
  const auto loss = [&](int n, Scene& s, Eigen::VectorXd* dL) {
    for (size_t k = first[n]; k < first[n + 1]; ++k) {
      const Observation& o = setup.obs[k];
      const Eigen::Vector3d r = s.CenterOfMass(o.actor) - o.position;
      *cost += 0.5 * r.squaredNorm();
      *dL += com[o.actor.index].transpose() * r;
    }
  };
  if (!adjoint.Gradient(setup.params, loss, gradient, error))
    return Failed(failure, SimulationFailure(*error));
  if (!std::isfinite(*cost) || !gradient->allFinite()) {
    Fail(error, "the cost (" + NumberText(*cost) + " m^2) or its gradient is not finite: the " +
                    "simulated or observed positions, or the parameter values, are beyond " +
                    "double precision");
    return Failed(failure, FitFailure::NonFinite);
  }
  if (stats) {
    stats->simulationSeconds = adjoint.RunSeconds();
    stats->gradientSeconds = adjoint.GradientSeconds();
    stats->colors = adjoint.MaxColors();
    stats->runsPerStep = double(adjoint.InjectRuns()) / std::max(1, setup.steps);
  }
  return true;
}

// L-BFGS variables: u = log(θ/θ₀) for model parameters (positive), u = θ − θ₀ for initial states.
class AdjointCostFunction : public ceres::FirstOrderFunction {
 public:
  AdjointCostFunction(const Scene& base, const FitSetup& setup, std::vector<double> theta0)
      : base_(base), setup_(setup), theta0_(std::move(theta0)) {}
  int NumParameters() const override { return static_cast<int>(theta0_.size()); }
  std::vector<double> Theta(const double* u) const {
    std::vector<double> theta(theta0_.size());
    for (size_t j = 0; j < theta.size(); ++j)
      theta[j] = setup_.params[j].IsInitialState() ? theta0_[j] + u[j]
                                                   : theta0_[j] * std::exp(u[j]);
    return theta;
  }
  bool Evaluate(const double* u, double* cost, double* gradient) const override {
    ++evaluations_;
    const std::vector<double> theta = Theta(u);
    Eigen::VectorXd g;
    Error error;
    if (!AdjointCost(base_, setup_, theta, cost, &g, nullptr, &error, nullptr)) {
      lastError_ = error.message;
      return false;
    }
    if (gradient)
      for (size_t j = 0; j < theta.size(); ++j)
        gradient[j] = setup_.params[j].IsInitialState() ? g[j] : g[j] * theta[j];
    return true;
  }
  int Evaluations() const { return evaluations_; }
  const std::string& LastError() const { return lastError_; }

 private:
  const Scene& base_;
  const FitSetup& setup_;
  std::vector<double> theta0_;
  mutable int evaluations_ = 0;
  mutable std::string lastError_;
};

// FitOptions::iteration as a Ceres callback; `values` gives θ at the current iterate.
class ProgressCallback : public ceres::IterationCallback {
 public:
  ProgressCallback(const FitOptions& options, std::function<std::vector<double>()> values,
                   bool* interrupted)
      : options_(options), values_(std::move(values)), interrupted_(interrupted) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    if (!options_.iteration) return ceres::SOLVER_CONTINUE;
    const FitProgress p{summary.iteration, values_(), summary.cost};
    if (options_.iteration(p)) return ceres::SOLVER_CONTINUE;
    *interrupted_ = true;
    return ceres::SOLVER_ABORT;
  }

 private:
  const FitOptions& options_;
  std::function<std::vector<double>()> values_;
  bool* interrupted_;
};

// The fit by L-BFGS with adjoint gradients (FitMethod::Lbfgs) from θ = result->initial.
bool FitLbfgs(const Scene& base, const FitSetup& setup, const FitOptions& options,
              FitResult* result, Error* error, FitFailure* failure) {
  const int P = static_cast<int>(setup.params.size());
  // The start is checked first, so that its error is the user's message.
  double cost = 0.0;
  Eigen::VectorXd g;
  if (!AdjointCost(base, setup, result->initial, &cost, &g, nullptr, error, failure))
    return false;
  auto* function = new AdjointCostFunction(base, setup, result->initial);
  ceres::GradientProblem gp(function);  // owns the function
  std::vector<double> u(P, 0.0);
  ProgressCallback progress(options, [&] { return function->Theta(u.data()); },
                            &result->interrupted);
  ceres::GradientProblemSolver::Options go;
  go.line_search_direction_type = ceres::LBFGS;
  go.max_num_iterations = options.maxIterations;
  go.function_tolerance = 1e-12;
  go.parameter_tolerance = 1e-10;
  go.gradient_tolerance = 1e-12;
  go.update_state_every_iteration = true;
  go.callbacks.push_back(&progress);
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(go, gp, u.data(), &summary);
  result->fitted = function->Theta(u.data());
  result->initialCost = summary.initial_cost;
  result->finalCost = summary.final_cost;
  result->iterations = static_cast<int>(summary.iterations.size()) - 1;
  result->converged = summary.termination_type == ceres::CONVERGENCE;
  result->message = summary.message;
  if (!function->LastError().empty() && !result->converged)
    result->message += " (last failed simulation: " + function->LastError() + ")";
  result->rmsResidual = std::sqrt(2.0 * summary.final_cost / result->residuals);
  result->standardError.assign(P, NAN);
  result->simulations = 1 + function->Evaluations();
  return true;
}

// One-sigma standard errors from the Jacobian J at the solution (residuals r).
std::vector<double> StandardErrors(const std::vector<double>& r, const Eigen::MatrixXd& J) {
  const int P = static_cast<int>(J.cols());
  const double cost = 0.5 * Eigen::Map<const Eigen::VectorXd>(r.data(), r.size()).squaredNorm();
  const int dof = static_cast<int>(r.size()) - P;
  std::vector<double> out(P, NAN);
  if (dof <= 0) return out;
  const Eigen::MatrixXd JtJ = J.transpose() * J;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(JtJ);
  if (ldlt.info() == Eigen::Success && ldlt.isPositive()) {
    const Eigen::MatrixXd cov = (2.0 * cost / dof) * ldlt.solve(Eigen::MatrixXd::Identity(P, P));
    for (int j = 0; j < P; ++j) out[j] = std::sqrt(std::max(0.0, cov(j, j)));
  }
  return out;
}

// The fit by Levenberg–Marquardt with forward sensitivities (FitMethod::LevenbergMarquardt).
bool FitLevenbergMarquardt(const Scene& base, const FitSetup& setup, const FitOptions& options,
                           FitResult* result, Error* error, FitFailure* failure) {
  const int P = static_cast<int>(setup.params.size());
  TrajectoryProblem problem(base, setup.params, setup.obs, setup.dt, setup.steps);
  std::vector<double> theta = result->initial;
  std::vector<double> r(problem.NumResiduals());
  Eigen::MatrixXd J(problem.NumResiduals(), P);
  // Check the start before handing it to Ceres, so that its error is the user's message.
  if (!problem.Simulate(theta, r.data(), &J, error))
    return Failed(failure, SimulationFailure(*error));
  if (!Eigen::Map<Eigen::VectorXd>(r.data(), r.size()).allFinite() || !J.allFinite()) {
    Fail(error, "the residuals or their Jacobian are not finite at the start: the simulated or "
                "observed positions, or the parameter values, are beyond double precision");
    return Failed(failure, FitFailure::NonFinite);
  }
  ceres::Problem cp;
  std::vector<double*> blocks;
  for (int j = 0; j < P; ++j) blocks.push_back(&theta[j]);
  cp.AddResidualBlock(new TrajectoryCost(&problem, P), nullptr, blocks);
  for (int j = 0; j < P; ++j)
    if (!setup.params[j].IsInitialState())  // physical coefficients stay positive
      cp.SetParameterLowerBound(&theta[j], 0, 1e-6 * theta[j]);
  ProgressCallback progress(options, [&] { return theta; }, &result->interrupted);
  ceres::Solver::Options so;
  so.max_num_iterations = options.maxIterations;
  so.linear_solver_type = ceres::DENSE_QR;
  so.function_tolerance = 1e-12;
  so.parameter_tolerance = 1e-10;
  so.gradient_tolerance = 1e-14;
  so.num_threads = 1;
  so.update_state_every_iteration = true;
  so.callbacks.push_back(&progress);
  ceres::Solver::Summary summary;
  ceres::Solve(so, &cp, &summary);
  result->fitted = theta;
  result->initialCost = summary.initial_cost;
  result->finalCost = summary.final_cost;
  result->iterations = static_cast<int>(summary.iterations.size()) - 1;
  result->converged = summary.termination_type == ceres::CONVERGENCE;
  result->message = summary.message;
  if (!problem.LastError().empty() && !result->converged)
    result->message += " (last failed simulation: " + problem.LastError() + ")";
  result->standardError.assign(P, NAN);
  result->rmsResidual = std::sqrt(2.0 * summary.final_cost / r.size());
  if (!result->interrupted) {  // standard errors from the Jacobian at the solution
    if (!problem.Simulate(theta, r.data(), &J, error))
      return Failed(failure, SimulationFailure(*error));
    const double cost = 0.5 * Eigen::Map<Eigen::VectorXd>(r.data(), r.size()).squaredNorm();
    result->rmsResidual = std::sqrt(2.0 * cost / r.size());
    result->standardError = StandardErrors(r, J);
  }
  result->simulations = problem.Simulations();
  return true;
}

}  // namespace

SUPERDEX_ENUM_NAMES(FitMethod,
    {FitMethod::LevenbergMarquardt, "lm",
     "Levenberg-Marquardt, Jacobian from forward sensitivities, standard errors (for a few "
     "parameters)"},
    {FitMethod::Lbfgs, "lbfgs", "L-BFGS with adjoint gradients (for many parameters)"})

bool ComputeTrajectoryGradient(const SceneFile& file, const ObservedTrajectory& observed,
                               const FitOptions& options, TrajectoryGradient* result,
                               Error* error, FitFailure* failure) {
  if (failure) *failure = FitFailure::None;
  FitSetup setup;
  if (!PrepareFit(file, observed, options, &setup, error))
    return Failed(failure, FitFailure::Input);
  *result = TrajectoryGradient();
  std::vector<double> theta;
  for (const SceneParameter& p : setup.params) {
    theta.push_back(ParameterValue(*file.scene, p));
    result->names.push_back(ToString(*file.scene, p));
  }
  result->values = theta;
  Eigen::VectorXd g;
  if (!AdjointCost(*file.scene, setup, theta, &result->cost, &g, result, error, failure))
    return false;
  result->gradient.assign(g.data(), g.data() + g.size());
  result->residuals = 3 * static_cast<int>(setup.obs.size());
  result->steps = setup.steps;
  return true;
}

bool FitSceneParameters(const SceneFile& file, const ObservedTrajectory& observed,
                        const FitOptions& options, FitResult* result, Error* error,
                        FitFailure* failure) {
  if (failure) *failure = FitFailure::None;
  const auto t0 = std::chrono::steady_clock::now();
  const Scene& base = *file.scene;
  FitSetup setup;
  if (!PrepareFit(file, observed, options, &setup, error))
    return Failed(failure, FitFailure::Input);
  *result = FitResult();
  for (const SceneParameter& p : setup.params) {
    result->names.push_back(ToString(base, p));
    result->initial.push_back(ParameterValue(base, p));
  }
  result->residuals = 3 * static_cast<int>(setup.obs.size());
  const bool ok = options.method == FitMethod::Lbfgs
                      ? FitLbfgs(base, setup, options, result, error, failure)
                      : FitLevenbergMarquardt(base, setup, options, result, error, failure);
  result->wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return ok;
}

bool WriteFitJson(const std::string& path, const FitResult& r, const std::string& status,
                  Error* error) {
  json j;
  j["parameters"] = json::object();
  for (size_t k = 0; k < r.names.size(); ++k) {
    const double fitted = k < r.fitted.size() ? r.fitted[k] : r.initial[k];
    const double se = k < r.standardError.size() ? r.standardError[k] : NAN;
    j["parameters"][r.names[k]] = {{"initial", r.initial[k]}, {"fitted", fitted},
                                   {"standard_error", std::isfinite(se) ? json(se) : json()}};
  }
  j["final_cost"] = r.finalCost;
  j["rms_residual"] = r.rmsResidual;
  j["iterations"] = r.iterations;
  j["converged"] = r.converged;
  j["status"] = status;
  // A complete file or none: written to a temporary name, then renamed into place.
  const std::string part = path + ".part";
  errno = 0;
  std::FILE* f = std::fopen(part.c_str(), "w");
  bool ok = f != nullptr;
  if (ok) {
    const std::string text = j.dump(2) + "\n";
    ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    ok = std::fclose(f) == 0 && ok;
    ok = ok && std::rename(part.c_str(), path.c_str()) == 0;
  }
  if (ok) return true;
  const std::string why = errno ? std::strerror(errno) : "write error";
  if (f) std::remove(part.c_str());
  return Fail(error, "--out: cannot write \"" + path + "\": " + why);
}

bool ApplyParameterValues(Scene* scene, const std::vector<std::string>& names,
                          const std::vector<double>& values, Error* error) {
  if (names.size() != values.size())
    return Fail(error, "values: one per parameter (" + std::to_string(names.size()) + "), got " +
                           std::to_string(values.size()));
  for (size_t j = 0; j < names.size(); ++j) {
    SceneParameter p;
    if (!ParseSceneParameter(*scene, names[j], &p, error) ||
        !SetParameterValue(scene, p, values[j], error))
      return false;
  }
  return true;
}

bool WriteFittedScene(const SceneFile& file, const FitResult& result, const std::string& path,
                      Error* error) {
  Scene fitted = *file.scene;
  if (!ApplyParameterValues(&fitted, result.names, result.fitted, error)) return false;
  SceneWriteOptions options;
  options.dt = file.dt;
  options.duration = file.duration;
  options.description = file.description;
  options.output = file.output;
  options.penetrationBound = file.penetrationBound;
  return WriteSceneFile(fitted, path, options, error);
}

}  // namespace superdex
