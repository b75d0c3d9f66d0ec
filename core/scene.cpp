#include "core/scene.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/dynamics/integrators.h"
#include "core/model/rigid_math.h"
#include "core/dynamics/scene_stage.h"
#include "core/dynamics/warm_start.h"
#include "energies/rigid_inertia.h"
#include "optim/ceres_stage_solver.h"
#include "optim/ipopt_stage_solver.h"
#include "optim/residual_newton.h"

namespace superdex {
namespace {

// Whether a stage's contact statistics show an active sample (penalty or dissipation).
bool InContact(const ContactStats& c) { return c.activeSamples > 0 || c.dissipativeSamples > 0; }

// a·x + b·y over every field (poses as matrices: the result's R need not be a rotation).
RigidBodyState Affine(double a, const RigidBodyState& x, double b, const RigidBodyState& y) {
  RigidBodyState s;
  s.p = a * x.p + b * y.p;
  s.R = a * x.R + b * y.R;
  s.v = a * x.v + b * y.v;
  s.Rdot = a * x.Rdot + b * y.Rdot;
  return s;
}

DissipationMode ModeOf(const ExperimentalEvalParams& e) {
  if (e.explicitNormals) return DissipationMode::ExplicitNormals;
  return e.implicitNormalForceForDissipation ? DissipationMode::ImplicitLoad
                                             : DissipationMode::ReconstructedLoad;
}

// Adds sign × the work counters and times of one solve to another's statistics.
void AddSolverWork(const SolverStats& from, SolverStats* to, int sign = 1) {
  to->iterations += sign * from.iterations;
  to->lineSearchSteps += sign * from.lineSearchSteps;
  to->regularizations += sign * from.regularizations;
  to->limitedSteps += sign * from.limitedSteps;
  to->assemblySeconds += sign * from.assemblySeconds;
  to->factorizationSeconds += sign * from.factorizationSeconds;
  to->lineSearchSeconds += sign * from.lineSearchSeconds;
  to->krylovIterations += sign * from.krylovIterations;
  to->krylovFallbacks += sign * from.krylovFallbacks;
}

// Replaces the work counters and times of *to by those of `from` (the rest of *to stays).
void CopySolverWork(const SolverStats& from, SolverStats* to) {
  const SolverStats own = *to;
  AddSolverWork(own, to, -1);
  AddSolverWork(from, to);
}

int Severity(StageStatus s) {
  return s == StageStatus::Converged ? 0 : s == StageStatus::Stopped ? 1 : 2;
}

}  // namespace

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

Scene::Scene(const SceneSettings& settings)
    : settings_(settings), settingsError_(Validate(settings)) {}

bool Scene::SetStageSolver(StageSolverKind kind, Error* error) {
  if (kind == StageSolverKind::Ipopt && HasDissipation() && !settings_.eval.explicitNormals)
    return Fail(error, "stage_solver: ipopt minimizes potential stages only, and this scene's "
                       "dissipation is not a potential (explicit_normals = false); use newton or "
                       "ceres, or set experimental_eval_params.explicit_normals = true");
  settings_.stageSolver = kind;
  settingsError_ = Validate(settings_);
  return true;
}

ActorHandle Scene::AddRigidActor(const RigidActorDesc& desc, Error* error, ActorHandle parent) {
  if (parent.index >= NumActors()) {
    Fail(error, "parent: invalid actor handle " + std::to_string(parent.index));
    return {};
  }
  RigidBodyModel model;
  RigidBodyState state;
  if (!BuildRigidBody(desc, "", &model, &state, error)) return {};
  if (!model.samples.empty()) {
    // One buffer for the samples of identical shapes (a grid of spheres).
    const std::size_t hash = SamplesHash(model);
    bool shared = false;
    for (auto [it, end] = sampleSets_.equal_range(hash); it != end && !shared; ++it)
      shared = ShareSamples(models_[it->second], &model);
    if (!shared) sampleSets_.emplace(hash, static_cast<int>(models_.size()));
  }
  filter_.AddActor(desc.contactLayer, parent.index);
  actors_.push_back({false, static_cast<int>(models_.size())});
  models_.push_back(std::move(model));
  states_.push_back(state);
  prepared_ = false;
  ClearHistory();
  return {NumActors() - 1};
}

ActorHandle Scene::AddSoftActor(const SoftActorDesc& desc, Error* error, ActorHandle parent) {
  if (parent.index >= NumActors()) {
    Fail(error, "parent: invalid actor handle " + std::to_string(parent.index));
    return {};
  }
  SoftBodyModel model;
  SoftBodyState state;
  if (!BuildSoftBody(desc, "", &model, &state, error)) return {};
  filter_.AddActor(desc.contactLayer, parent.index);
  actors_.push_back({true, static_cast<int>(softModels_.size())});
  softModels_.push_back(std::move(model));
  softInitial_.push_back(state.x);
  softStates_.push_back(std::move(state));
  prepared_ = false;
  ClearHistory();
  return {NumActors() - 1};
}

std::vector<ActorHandle> Scene::RigidActors() const {
  std::vector<ActorHandle> out;
  for (int i = 0; i < NumActors(); ++i)
    if (!actors_[i].soft) out.push_back({i});
  return out;
}

Eigen::Vector3d Scene::CenterOfMass(ActorHandle a) const {
  const ActorRef& r = actors_[a.index];
  if (!r.soft) return states_[r.local].p;
  const SoftBodyModel& m = softModels_[r.local];
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i = 0; i < m.NumNodes(); ++i) c += m.nodeMass[i] * softStates_[r.local].x.segment<3>(3 * i);
  return c / m.mass;
}

Eigen::Vector3d Scene::CenterOfMassVelocity(ActorHandle a) const {
  const ActorRef& r = actors_[a.index];
  if (!r.soft) return states_[r.local].v;
  const SoftBodyModel& m = softModels_[r.local];
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i = 0; i < m.NumNodes(); ++i) c += m.nodeMass[i] * softStates_[r.local].v.segment<3>(3 * i);
  return c / m.mass;
}

std::vector<ActorHandle> Scene::SoftActors() const {
  std::vector<ActorHandle> out;
  for (int i = 0; i < NumActors(); ++i)
    if (actors_[i].soft) out.push_back({i});
  return out;
}

namespace {
bool ValidHandle(ActorHandle a, int n, const char* field, Error* error) {
  if (a.index >= 0 && a.index < n) return true;
  return Fail(error, std::string(field) + ": invalid actor handle " + std::to_string(a.index));
}
}  // namespace

bool Scene::SetContactLayer(ActorHandle actor, const std::string& layer, Error* error) {
  if (!ValidHandle(actor, NumActors(), "actor", error)) return false;
  filter_.SetLayer(actor.index, layer);
  if (actors_[actor.index].soft) {
    softModels_[actors_[actor.index].local].contactLayer = layer;
  } else {
    models_[actors_[actor.index].local].contactLayer = layer;
  }
  return true;
}

const std::string& Scene::ContactLayer(ActorHandle actor) const {
  return filter_.Layer(actor.index);
}

bool Scene::EnableLayerContactAsymmetric(const std::string& layerA, const std::string& layerB,
                                         bool enable, Error*) {
  filter_.EnableLayer(layerA, layerB, enable);
  return true;
}

bool Scene::EnableLayerContactSymmetric(const std::string& layerA, const std::string& layerB,
                                        bool enable, Error*) {
  filter_.EnableLayer(layerA, layerB, enable);
  filter_.EnableLayer(layerB, layerA, enable);
  return true;
}

bool Scene::EnableActorContactAsymmetric(ActorHandle a, ActorHandle b, bool enable,
                                         IncludeNestedActors nested, Error* error) {
  if (!ValidHandle(a, NumActors(), "A", error) || !ValidHandle(b, NumActors(), "B", error))
    return false;
  filter_.EnableActors(a.index, b.index, enable, nested == IncludeNestedActors::Yes);
  return true;
}

bool Scene::EnableActorContactSymmetric(ActorHandle a, ActorHandle b, bool enable,
                                        IncludeNestedActors nested, Error* error) {
  if (!ValidHandle(a, NumActors(), "A", error) || !ValidHandle(b, NumActors(), "B", error))
    return false;
  filter_.EnableActors(a.index, b.index, enable, nested == IncludeNestedActors::Yes);
  filter_.EnableActors(b.index, a.index, enable, nested == IncludeNestedActors::Yes);
  return true;
}

void Scene::DisableAdjacentContact(ActorHandle a, ActorHandle b) {
  filter_.EnableActors(a.index, b.index, false, false);
  filter_.EnableActors(b.index, a.index, false, false);
}

bool Scene::ContactAllowed(ActorHandle a, ActorHandle b) const {
  return filter_.Allowed(a.index, b.index);
}

bool Scene::SetIntegrator(IntegrationMethod method, Error* error) {
  SceneSettings s = settings_;
  s.integrator = method;
  if (std::string m = Validate(s); !m.empty()) return Fail(error, m);
  settings_ = s;
  settingsError_.clear();
  ClearHistory();
  return true;
}

bool Scene::SetSolverParams(const NonlinearSolverParams& params, Error* error) {
  SceneSettings s = settings_;
  s.solver = params;
  if (std::string m = Validate(s); !m.empty()) return Fail(error, m);
  settings_ = s;
  settingsError_.clear();
  return true;
}

bool Scene::SetState(ActorHandle a, const RigidBodyState& state, Error* error) {
  if (a.index < 0 || a.index >= NumActors()) return Fail(error, "actor: invalid handle");
  if (actors_[a.index].soft) return Fail(error, "actor: a soft actor has no rigid state");
  if (!state.p.allFinite() || !state.R.allFinite() || !state.v.allFinite() ||
      !state.Rdot.allFinite())
    return Fail(error, "state: must be finite");
  if ((state.R.transpose() * state.R - Eigen::Matrix3d::Identity()).norm() > 1e-9 ||
      state.R.determinant() <= 0)
    return Fail(error, "state.R: must be a rotation matrix");
  states_[actors_[a.index].local] = state;
  ClearHistory();
  return true;
}

void Scene::Prepare() {
  if (prepared_) return;
  dofOffset_.assign(models_.size(), -1);
  numDofs_ = 0;
  for (size_t i = 0; i < models_.size(); ++i)
    if (models_[i].dynamic) {
      dofOffset_[i] = numDofs_;
      numDofs_ += 6;
    }
  // Soft free nodes after every rigid dof (the stage's step norm relies on this order).
  softDofOffset_.assign(softModels_.size(), 0);
  for (size_t s = 0; s < softModels_.size(); ++s) {
    softDofOffset_[s] = numDofs_;
    numDofs_ += 3 * softModels_[s].numFree;
  }
  std::vector<int> rigidActor, softActor;
  for (int i = 0; i < NumActors(); ++i) (actors_[i].soft ? softActor : rigidActor).push_back(i);
  pipeline_.Configure(&models_, &filter_, &softModels_, rigidActor, softActor);
  hasDissipation_ = HasDissipation();  // actors' contact parameters are fixed once added
  prepared_ = true;
}

std::vector<Eigen::VectorXd> Scene::CurrentSoftPositions() const {
  std::vector<Eigen::VectorXd> x(softStates_.size());
  for (size_t s = 0; s < softStates_.size(); ++s) x[s] = softStates_[s].x;
  return x;
}

SoftStage Scene::MakeSoftStage(double dt, const std::vector<SoftBodyState>& start,
                               const std::vector<Eigen::VectorXd>& last) const {
  SoftStage st;
  st.models = &softModels_;
  st.dofOffset = softDofOffset_;
  st.targets.resize(softModels_.size());
  for (size_t s = 0; s < softModels_.size(); ++s) {
    SoftStageTarget& t = st.targets[s];
    t.xHat = start[s].x + dt * start[s].v;
    t.x0 = start[s].x;
    t.xLast = last[s];
    PrepareSoftDamping(softModels_[s], &t);
  }
  st.x0.resize(softModels_.size());
  st.xLast = last;
  for (size_t s = 0; s < softModels_.size(); ++s) st.x0[s] = start[s].x;
  return st;
}

void Scene::ApplyConstraints(double t, std::vector<Eigen::VectorXd>* x) const {
  for (size_t s = 0; s < softModels_.size(); ++s)
    ApplyNodeConstraints(softModels_[s], softInitial_[s], t, &(*x)[s]);
}

double Scene::MinDetF() const {
  double minDet = INFINITY;
  for (size_t s = 0; s < softModels_.size(); ++s) {
    double md = INFINITY;
    ElasticEnergy(softModels_[s], softStates_[s].x, &md);
    minDet = std::min(minDet, md);
  }
  return minDet;
}

std::vector<RigidPose> Scene::CurrentPoses() const {
  std::vector<RigidPose> poses;
  CurrentPoses(&poses);
  return poses;
}

void Scene::CurrentPoses(std::vector<RigidPose>* poses) const {
  poses->resize(states_.size());
  for (size_t i = 0; i < states_.size(); ++i) (*poses)[i] = {states_[i].p, states_[i].R};
}

SolverStats Scene::SolveStage(double dt, const std::vector<RigidBodyState>& start,
                              const std::vector<RigidPose>& last, std::vector<RigidPose>* poses,
                              ContactStats* contact, const SoftStage* soft,
                              std::vector<Eigen::VectorXd>* softX, double predictTime) {
  StageTargets& targets = buffers_.targets;
  targets.dt = dt;
  targets.pHat.resize(models_.size());
  targets.RHat.resize(models_.size());
  for (size_t i = 0; i < models_.size(); ++i) {
    targets.pHat[i] = start[i].p + dt * start[i].v;
    targets.RHat[i] = start[i].R + dt * start[i].Rdot;
  }
  targets.start.resize(models_.size());
  for (size_t i = 0; i < models_.size(); ++i) {
    RigidStageStart& s = targets.start[i];
    s.p = start[i].p;
    s.R = start[i].R;
    s.Rinv = start[i].R.inverse();
    s.last = last[i];
  }
  StageDissipation dissipation;
  dissipation.enabled = hasDissipation_;
  if (dissipation.enabled) {
    dissipation.mode = ModeOf(settings_.eval);
    dissipation.fadeFriction = settings_.eval.fadeFriction;
  }
  if (tapeMode_ == TapeMode::Replay || tapeMode_ == TapeMode::Inject) {
    TapedStage(targets, dissipation, poses, soft, softX);
    SolverStats st;
    st.status = StageStatus::Converged;
    return st;
  }
  SolverStats st;
  // Tried where the last stage had no active contact sample: where it had, contact usually
  // persists, and the check (a value-only contact evaluation) made a sliding box's run 16 %
  // longer for nothing. A stage that leaves contact is solved by Newton, the next one tried again.
  if (settings_.closedFormFreeStages && settings_.stageSolver == StageSolverKind::Newton &&
      softModels_.empty() && tapeMode_ == TapeMode::Off && !lastStageInContact_ &&
      FreeStage(targets, dissipation, poses, &st, contact)) {
    lastPotentialIterations_ = 0;  // a local stage: the next warm start may try the exact Hessian
    return st;
  }
  SceneStageProblem problem(models_, dofOffset_, numDofs_, targets, settings_.gravity, &pipeline_,
                            poses, dissipation, soft, softX, &workspace_);
  // The warm start (core/dynamics/warm_start.h; Newton only: Ipopt and Ceres check the cold stage). Kept
  // cold: (1) scenes with soft actors: soft nodes are not predicted, and a soft collider's stages
  // are only piecewise smooth (its deformed grid SDF's gradient jumps across tet and cell faces),
  // so that at tolerances near round-off Newton ends in the iteration cap from some starts (cold or
  // warm alike: tests/core/test_soft_body.cpp's soft-on-soft scene stalls at Δt = 1.8e-3 cold and
  // at 2e-3 warm). (2) Recorded steps (sensitivities, adjoint): their derivatives are evaluated at
  // the recorded solution, which a start reaches only to the solver's tolerance. Measured with
  // warm-started recorded steps: the four-box stack's forward derivative of its centre-of-mass
  // loss in c's spin (tests/core/test_adjoint.cpp), a small remainder (−0.00255 against
  // derivatives of order 100), moves from 4.3e-4 to 1.3e-3 off the trajectory differences; the
  // recorded steps cost a one-parameter forward run of the thrown box at most ~15 % more than
  // the plain steps (bench/bench_sensitivity.cpp: 0.011 s against 0.008 s), so the cold start
  // stays.
  const bool warm = settings_.stageSolver == StageSolverKind::Newton && predictTime > 0.0 &&
                    settings_.warmStart && softModels_.empty() && tapeMode_ == TapeMode::Off;
  if (warm) {
    const bool history = !history_.empty() && !historyTimes_.empty();
    PredictStagePoses(models_, states_, history ? &history_[0] : nullptr,
                      history ? time_ - historyTimes_[0] : 0.0, predictTime, start, dt,
                      &buffers_.predicted);
    TangentStep(dofOffset_, numDofs_, *poses, buffers_.predicted, &buffers_.warmStep);
    const bool twoSteps = history_.size() >= 2 && historyTimes_.size() >= 2;
    SteadyMotion(models_, states_, history ? &history_[0] : nullptr,
                 history ? time_ - historyTimes_[0] : 0.0, twoSteps ? &history_[1] : nullptr,
                 twoSteps ? historyTimes_[0] - historyTimes_[1] : 0.0, settings_.gravity,
                 &buffers_.steady);
    WarmStart(problem, dofOffset_, buffers_.steady, &buffers_.warmStep,
              &buffers_.warmScratch, settings_.solver.stepTolerance * dt);
  }
  switch (settings_.stageSolver) {
    case StageSolverKind::Newton:
      if (problem.IsPotential()) {
        NewtonStart hint;
        hint.exactHessian = warm && lastPotentialIterations_ <= kLocalStageIterations;
        st = MinimizeNewton(problem, settings_.solver, dt, solvers_.symmetric.get(),
                            &solvers_.newton, hint);
        lastPotentialIterations_ =
            warm && st.status == StageStatus::Converged ? st.iterations : kNoLocalStage;
        break;
      }
      {
        // Residual modes: Newton on r has only the merit ½‖r‖² to globalize with, which is badly
        // scaled where stiff contacts and friction meet (landing and settling contacts: ~20
        // iterations with many backtracks on a sphere pile). A stage that starts from the
        // explicit-normals minimizer (a potential, globalized by projected Newton) needs only the
        // local residual iterations. That costs about one iteration more on easy stages, so it is
        // switched on whenever a residual-first stage takes more than kResidualFirstIterations
        // iterations, for kExplicitFirstStages stages, then the residual-first start is tried
        // again; each further such probe that fails doubles the run (up to kMaxExplicitFirstStages),
        // one that succeeds resets it.
        // Either start converges to the same residual root. The start needs no more accuracy
        // than the distance between the two roots, so that minimization stops at a gradient
        // kStartRelativeGradient of its initial one (300-sphere pile, 0.6 s: 14.0 → 11.9 Newton
        // iterations per step against a full-accuracy start). If the residual solve fails, the
        // explicit-normals minimizer, continued to full accuracy, is the fallback (below).
        constexpr int kResidualFirstIterations = 8;
        constexpr int kMaxExplicitFirstStages = 320;
        constexpr double kStartRelativeGradient = 1e-2;
        std::vector<RigidPose>& guess = buffers_.guess;
        guess = *poses;
        const std::vector<Eigen::VectorXd> softGuess = softX ? *softX : std::vector<Eigen::VectorXd>();
        StageDissipation potential = dissipation;
        potential.mode = DissipationMode::ExplicitNormals;
        ContactStats explicitContact;
        auto minimizeExplicit = [&](const NonlinearSolverParams& params) {  // from *poses, *softX
          SceneStageProblem stage(models_, dofOffset_, numDofs_, targets, settings_.gravity,
                                  &pipeline_, poses, potential, soft, softX, &workspace_);
          const SolverStats out =
              MinimizeNewton(stage, params, dt, solvers_.symmetric.get(), &solvers_.newton);
          explicitContact = stage.LastContactStats();
          return out;
        };
        const bool explicitFirst = explicitFirstStages_ > 0;
        if (explicitFirst) --explicitFirstStages_;
        SolverStats first;  // the explicit-normals solve that gave the start (explicitFirst)
        bool haveExplicit = false;
        std::vector<RigidPose> explicitSolution;
        std::vector<Eigen::VectorXd> softExplicit;
        if (explicitFirst) {
          NonlinearSolverParams start = settings_.solver;
          start.relativeTolerance = std::max(start.relativeTolerance, kStartRelativeGradient);
          first = minimizeExplicit(start);
          haveExplicit = first.status == StageStatus::Converged;
          if (haveExplicit) {
            explicitSolution = *poses;
            if (softX) softExplicit = *softX;
          } else {
            *poses = guess;
            if (softX) *softX = softGuess;
          }
        }
        st = SolveResidualNewton(problem, settings_.solver, dt, solvers_.unsymmetric.get(),
                                 &solvers_.newton);
        if (!explicitFirst) {
          if (st.status != StageStatus::Converged || st.iterations > kResidualFirstIterations) {
            explicitFirstStages_ = explicitFirstRun_;
            explicitFirstRun_ = std::min(2 * explicitFirstRun_, kMaxExplicitFirstStages);
          } else {
            explicitFirstRun_ = kExplicitFirstStages;
          }
        }
        AddSolverWork(first, &st);
        if (st.status != StageStatus::Converged) {
          // Fallback: the explicit-normals minimizer to full accuracy (from the start it gave,
          // or from the stage's guess); the report carries its outcome and the work of every
          // solve of the stage.
          SolverStats work = st;
          *poses = haveExplicit ? explicitSolution : guess;
          if (softX) *softX = haveExplicit ? softExplicit : softGuess;
          const SolverStats outcome = minimizeExplicit(settings_.solver);
          AddSolverWork(outcome, &work);
          const std::string why = st.Message();
          st = outcome;
          CopySolverWork(work, &st);
          st.message = "residual solve failed (" + why + "); stage re-solved with explicit "
                       "normals" + (outcome.status == StageStatus::Converged ? "" : ": " + outcome.Message());
          st.fallback = true;
          *contact = explicitContact;
          lastStageInContact_ = InContact(*contact);
          if (tapeMode_ == TapeMode::Record) RecordStage(targets, potential, *poses, soft, softX);
          return st;
        }
      }
      break;
    case StageSolverKind::Ipopt:
      st = MinimizeIpopt(problem, IpoptStageParams());
      break;
    case StageSolverKind::Ceres:
      st = SolveCeres(problem, CeresStageParams());
      break;
  }
  *contact = problem.LastContactStats();
  lastStageInContact_ = InContact(*contact);
  if (tapeMode_ == TapeMode::Record) RecordStage(targets, dissipation, *poses, soft, softX);
  return st;
}

bool Scene::FreeStage(const StageTargets& targets, const StageDissipation& dissipation,
                      std::vector<RigidPose>* poses, SolverStats* stats, ContactStats* contact) {
  std::vector<RigidPose>& free = buffers_.free;
  free = *poses;
  for (size_t i = 0; i < models_.size(); ++i) {
    if (dofOffset_[i] < 0) continue;
    const RigidInertiaMinimum x = MinimizeRigidInertia(
        models_[i].secondMoment, targets.pHat[i], targets.RHat[i], targets.dt, settings_.gravity);
    // A non-finite target (a state gone bad) is left to Newton, which reports it.
    if (!x.p.allFinite() || !x.R.allFinite()) return false;
    free[i] = {x.p, x.R};
  }
  // The contact terms as SceneStageProblem evaluates them there (value only): each pair adds its
  // value, gradient and residual only through samples it counts active.
  const DissipationContext context = ContextOf(dissipation, targets.dt);
  ContactStats found;
  pipeline_.Evaluate(free, dofOffset_, 0, PsdProjection::None, nullptr, nullptr, nullptr, &found,
                     dissipation.enabled ? &context : nullptr, nullptr,
                     targets.start.empty() ? nullptr : &targets.start);
  if (InContact(found)) return false;
  poses->swap(free);
  *contact = found;
  *stats = SolverStats();
  stats->status = StageStatus::Converged;
  stats->passed.what = "closed-form free stage (no active contact sample)";
  stats->closedForm = true;
  return true;
}

bool Scene::StepAndRecord(double dt, StepTape* tape, StepReport* report, Error* error) {
  StepReport rep;
  tape_ = tape;
  tapeMode_ = TapeMode::Record;
  const bool ok = Step(dt, &rep, error);
  tapeMode_ = TapeMode::Off;
  if (report) *report = rep;
  if (!ok) return false;
  if (rep.status != StageStatus::Converged)
    return Fail(error, "a stage did not converge (" + rep.message +
                           "): the derivative of this step is not defined");
  for (int s = 0; s < tape->used; ++s)
    if (numDofs_ > 0 && !tape->stages[s].factored)
      return Fail(error, "the stage Jacobian at the solution is singular: the derivative of this "
                         "step is not defined");
  return true;
}

void Scene::RecordStage(const StageTargets& targets, const StageDissipation& dissipation,
                        const std::vector<RigidPose>& poses, const SoftStage* soft,
                        std::vector<Eigen::VectorXd>* softX) {
  if (static_cast<int>(tape_->stages.size()) <= tapeStage_) tape_->stages.emplace_back();
  StageTapeEntry& e = tape_->stages[tapeStage_++];
  tape_->used = tapeStage_;
  e.poses = poses;
  e.softX = softX ? *softX : std::vector<Eigen::VectorXd>();
  e.mode = dissipation.mode;
  // The stage Jacobian at the accepted solution, in the same mode (a copy of the iterate: the
  // problem commits into the vectors it is given).
  std::vector<RigidPose> at = poses;
  std::vector<Eigen::VectorXd> softAt = e.softX;
  StageDissipation recording = dissipation;
  e.slips.Clear();
  recording.slips = &e.slips;
  recording.recordSlips = true;
  SceneStageProblem problem(models_, dofOffset_, numDofs_, targets, settings_.gravity, &pipeline_,
                            &at, recording, soft, softX ? &softAt : nullptr, &workspace_);
  Eigen::VectorXd r;
  Eigen::SparseMatrix<double> J;
  problem.EvaluateResidual(&r, &J);
  e.factored = numDofs_ > 0 && e.lu->Factorize(J);
  e.jacobian = std::move(J);
}

void Scene::TapedStage(const StageTargets& targets, const StageDissipation& dissipation,
                       std::vector<RigidPose>* poses, const SoftStage* soft,
                       std::vector<Eigen::VectorXd>* softX) {
  StageTapeEntry& e = tape_->stages[tapeStage_++];
  *poses = e.poses;
  if (softX) *softX = e.softX;
  if (numDofs_ == 0) {
    e.residual.resize(0);
    return;
  }
  StageDissipation d = dissipation;
  d.mode = e.mode;
  d.slips = &e.slips;
  SceneStageProblem problem(models_, dofOffset_, numDofs_, targets, settings_.gravity, &pipeline_,
                            poses, d, soft, softX, &workspace_);
  if (tapeMode_ == TapeMode::Replay) {  // one Newton step with the recorded factors
    Eigen::VectorXd r;
    problem.Residual(Eigen::VectorXd::Zero(numDofs_), &r);
    problem.Commit(-e.lu->Solve(r));
    return;
  }
  const Eigen::VectorXd delta =  // Inject
      e.inject.size() == numDofs_ ? e.inject : Eigen::VectorXd::Zero(numDofs_);
  problem.Residual(delta, &e.residual);
  problem.Commit(delta);
}

bool Scene::Step(double h, StepReport* report, Error* error) {
  if (!(std::isfinite(h) && h > 0)) {
    std::ostringstream s;
    s << "dt: must be > 0 and finite, got " << h;
    return Fail(error, s.str());
  }
  if (!settingsError_.empty()) return Fail(error, settingsError_);
  if (settings_.stageSolver == StageSolverKind::Ipopt && !SetStageSolver(settings_.stageSolver, error))
    return false;
  const auto t0 = std::chrono::steady_clock::now();
  Prepare();
  tapeStage_ = 0;
  StepReport rep;
  rep.dt = h;
  ContactStats stageContact;
  auto account = [&](const SolverStats& st) {
    rep.maxCoulombRatio = std::max(rep.maxCoulombRatio, stageContact.maxCoulombRatio);
    rep.dissipativeSamples = std::max(rep.dissipativeSamples, stageContact.dissipativeSamples);
    rep.dissipation += stageContact.dissipation;
    ++rep.stages;
    rep.newtonIterations += st.iterations;
    rep.lineSearchSteps += st.lineSearchSteps;
    if (st.closedForm) ++rep.freeStages;
    if (st.fallback) {
      ++rep.fallbacks;
      if (rep.fallbackMessage.empty()) rep.fallbackMessage = st.Message();
    }
    rep.assemblySeconds += st.assemblySeconds;
    rep.factorizationSeconds += st.factorizationSeconds;
    rep.lineSearchSeconds += st.lineSearchSeconds;
    rep.krylovIterations += st.krylovIterations;
    rep.krylovFallbacks += st.krylovFallbacks;
    rep.finalGradientNorm = std::max(rep.finalGradientNorm, st.finalGradientNorm);
    if (Severity(st.status) > Severity(rep.status)) {
      rep.status = st.status;
      rep.message = st.Message();
    }
  };

  const size_t n = models_.size();
  const size_t ns = softModels_.size();
  std::vector<RigidPose>& poses = buffers_.poses;
  CurrentPoses(&poses);
  buffers_.stepStart = poses;
  const std::vector<RigidPose>& stepStart = buffers_.stepStart;
  std::vector<RigidBodyState>& next = buffers_.next;
  next = states_;
  std::vector<Eigen::VectorXd> softX = CurrentSoftPositions();
  const std::vector<Eigen::VectorXd> softStepStart = softX;
  std::vector<SoftBodyState> softNext = softStates_;
  const IntegrationMethod method = settings_.integrator;

  // BDF3 starts with DIRK33 steps while its history fills: a Backward Euler start (local error
  // O(h²)) would cap its global order at 2. BDF2 starts with one BDF1 (Backward Euler) step, whose
  // O(h²) local error is within BDF2's own global order.
  const bool bdf3Startup = method == IntegrationMethod::BDF3 && history_.size() < 2;
  if (IsMultistep(method) && !bdf3Startup) {
    // BDF-k with variable steps.
    const int k = std::min<int>(BdfSteps(method), static_cast<int>(history_.size()) + 1);
    std::vector<double>& times = buffers_.bdfTimes;
    times.assign({time_ + h, time_});
    for (int j = 0; j + 1 < k; ++j) times.push_back(historyTimes_[j]);
    std::vector<double>& weights = buffers_.bdfWeights;
    const double dt = BdfCoefficients(times, &weights);
    std::vector<RigidBodyState>& start = buffers_.start;
    start.resize(n);
    for (size_t i = 0; i < n; ++i) {
      start[i] = Affine(weights[0], states_[i], 0.0, states_[i]);
      for (int j = 1; j < k; ++j) start[i] = Affine(1.0, start[i], weights[j], history_[j - 1][i]);
    }
    std::vector<SoftBodyState> softStart(ns);
    for (size_t s = 0; s < ns; ++s) {
      softStart[s].x = weights[0] * softStates_[s].x;
      softStart[s].v = weights[0] * softStates_[s].v;
      for (int j = 1; j < k; ++j) {
        softStart[s].x += weights[j] * softHistory_[j - 1][s].x;
        softStart[s].v += weights[j] * softHistory_[j - 1][s].v;
      }
    }
    ApplyConstraints(time_ + h, &softX);
    const SoftStage soft = MakeSoftStage(dt, softStart, softStepStart);
    account(SolveStage(dt, start, stepStart, &poses, &stageContact, &soft, &softX, h));
    for (size_t s = 0; s < ns; ++s) {
      softNext[s].x = softX[s];
      softNext[s].v = (softX[s] - softStart[s].x) / dt;
    }
    for (size_t i = 0; i < n; ++i) {
      if (!models_[i].dynamic) continue;
      next[i].p = poses[i].p;
      next[i].R = poses[i].R;
      next[i].v = (poses[i].p - start[i].p) / dt;
      next[i].Rdot = (poses[i].R - start[i].R) / dt;
    }
  } else {
    // DIRK stages in material-point form, with the three rotation rules of core/dynamics/integrators.h.
    const DirkTableau& T = TableauOf(bdf3Startup ? IntegrationMethod::DIRK33 : method);
    // Every entry is written at its stage before it is read.
    std::vector<std::vector<RigidBodyState>>& VK = buffers_.stageSlopes;
    std::vector<std::vector<Eigen::Vector3d>>& torque = buffers_.stageTorques;
    std::vector<std::vector<RigidPose>>& Q = buffers_.stagePoses;
    if (VK.size() < static_cast<size_t>(T.stages)) {
      VK.resize(T.stages);
      torque.resize(T.stages);
      Q.resize(T.stages);
    }
    for (int st = 0; st < T.stages; ++st) {
      VK[st].resize(n);
      torque[st].resize(n);
    }
    // Soft nodes: stage slopes (position, velocity) per stage and actor, as for p and v.
    std::vector<std::vector<SoftBodyState>> softVK(ns ? T.stages : 0,
                                                   std::vector<SoftBodyState>(ns));
    std::vector<Eigen::VectorXd> softLast = softStepStart;
    for (int st = 0; st < T.stages; ++st) {
      std::vector<RigidBodyState>& start = buffers_.start;
      start = states_;
      for (size_t i = 0; i < n; ++i)
        for (int j = 0; j < st; ++j) {
          const double c = h * T.a[st][j];
          start[i].p += c * VK[j][i].p;
          start[i].R += c * VK[j][i].R;
          start[i].v += c * VK[j][i].v;
          start[i].Rdot += c * VK[j][i].Rdot;
        }
      std::vector<SoftBodyState> softStart = softStates_;
      double cStage = 0.0;  // the stage's abscissa c_i = Σ_j a_ij
      for (int j = 0; j <= st; ++j) cStage += T.a[st][j];
      for (size_t s = 0; s < ns; ++s)
        for (int j = 0; j < st; ++j) {
          const double c = h * T.a[st][j];
          softStart[s].x += c * softVK[j][s].x;
          softStart[s].v += c * softVK[j][s].v;
        }
      const double dt = h * T.a[st][st];
      // Dissipation geometry: the last configuration the bodies occupied (x_n, then Q_{i−1}).
      const std::vector<RigidPose>& last = st == 0 ? stepStart : Q[st - 1];
      ApplyConstraints(time_ + cStage * h, &softX);
      const SoftStage soft = MakeSoftStage(dt, softStart, softLast);
      account(SolveStage(dt, start, last, &poses, &stageContact, &soft, &softX, cStage * h));
      Q[st] = poses;
      for (size_t s = 0; s < ns; ++s) {
        softVK[st][s].x = (softX[s] - softStart[s].x) / dt;
        softVK[st][s].v = (softVK[st][s].x - softStart[s].v) / dt;
      }
      softLast = softX;
      for (size_t i = 0; i < n; ++i) {
        RigidBodyState& vk = VK[st][i];
        vk.p = (poses[i].p - start[i].p) / dt;
        vk.v = (vk.p - start[i].v) / dt;
        if (!models_[i].dynamic) {
          vk.R.setZero();
          vk.Rdot.setZero();
          torque[st][i].setZero();
          continue;
        }
        const Eigen::Matrix3d& J = models_[i].secondMoment;
        const Eigen::Matrix3d& Rq = poses[i].R;
        const Eigen::Matrix3d V = (poses[i].R - start[i].R) / dt;
        // The stage's world torque on the body: its stationarity makes the rotational inertia
        // force K = (V − v⁰)/Δt_i balance it, τ = axial(K J Qᵀ − Q J Kᵀ).
        const Eigen::Matrix3d Kraw = (V - start[i].Rdot) / dt;
        torque[st][i] = SpinMomentum(Rq, Kraw, J);
        // The stage velocity, made tangent to SO(3) at Q with the same spin momentum.
        vk.R = Skew(WorldInertia(Rq, J).ldlt().solve(SpinMomentum(Rq, V, J))) * Rq;
        vk.Rdot = (vk.R - start[i].Rdot) / dt;
      }
    }
    for (size_t i = 0; i < n; ++i) {
      if (!models_[i].dynamic) continue;
      const RigidBodyState& s = states_[i];
      RigidBodyState end = s;  // q_n + h Σ b_i V_i, v_n + h Σ b_i K_i
      Eigen::Vector3d spin = SpinMomentum(s.R, s.Rdot, models_[i].secondMoment);
      for (int st = 0; st < T.stages; ++st) {
        end.p += h * T.b[st] * VK[st][i].p;
        end.R += h * T.b[st] * VK[st][i].R;
        end.v += h * T.b[st] * VK[st][i].v;
        end.Rdot += h * T.b[st] * VK[st][i].Rdot;
        spin += h * T.b[st] * torque[st][i];  // L̇ = τ, by the method's own weights
      }
      next[i].p = end.p;
      next[i].v = end.v;
      next[i].R = T.stifflyAccurate ? Q[T.stages - 1][i].R : NearestRotation(end.R);
      // Keep the end velocity, corrected along the tangent directions [δω] R so that it carries
      // exactly the integrated spin momentum.
      const Eigen::Matrix3d& J = models_[i].secondMoment;
      const Eigen::Vector3d missing = spin - SpinMomentum(next[i].R, end.Rdot, J);
      next[i].Rdot = end.Rdot + Skew(WorldInertia(next[i].R, J).ldlt().solve(missing)) * next[i].R;
    }
    for (size_t s = 0; s < ns; ++s) {
      softNext[s] = softStates_[s];
      for (int st = 0; st < T.stages; ++st) {
        softNext[s].x += h * T.b[st] * softVK[st][s].x;
        softNext[s].v += h * T.b[st] * softVK[st][s].v;
      }
    }
    // Prescribed nodes sit exactly on their path at the step's end.
    std::vector<Eigen::VectorXd> endX(ns);
    for (size_t s = 0; s < ns; ++s) endX[s] = softNext[s].x;
    ApplyConstraints(time_ + h, &endX);
    for (size_t s = 0; s < ns; ++s) softNext[s].x = endX[s];
  }
  // History for the multistep methods: x_{n}, x_{n−1} with their times.
  if (history_.size() < 2) {
    history_.insert(history_.begin(), states_);
    softHistory_.insert(softHistory_.begin(), softStates_);
    historyTimes_.insert(historyTimes_.begin(), time_);
  } else {  // the oldest entry's storage takes the current state
    std::swap(history_[0], history_[1]);
    std::swap(softHistory_[0], softHistory_[1]);
    std::swap(historyTimes_[0], historyTimes_[1]);
    history_[0] = states_;
    softHistory_[0] = softStates_;
    historyTimes_[0] = time_;
  }
  states_.swap(next);  // next keeps the former state's storage for the next step
  softStates_ = std::move(softNext);
  time_ += h;
  rep.time = time_;
  if (tapeMode_ == TapeMode::Replay || tapeMode_ == TapeMode::Inject) {  // the state only
    if (report) *report = rep;
    return true;
  }
  if (!softModels_.empty()) rep.minDetF = MinDetF();
  rep.contact = ContactState();
  rep.wallSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (report) *report = rep;
  return true;
}

ContactStats Scene::ContactState() {
  Prepare();
  ContactStats st;
  const std::vector<Eigen::VectorXd> x = CurrentSoftPositions();
  SoftView view;
  view.x = &x;
  view.dofOffset = &softDofOffset_;
  CurrentPoses(&buffers_.reportPoses);
  pipeline_.Evaluate(buffers_.reportPoses, dofOffset_, 0, PsdProjection::None, nullptr, nullptr,
                     nullptr, &st, nullptr, nullptr, nullptr, &view);
  return st;
}

std::vector<ContactSampleRecord> Scene::ContactSamples() {
  Prepare();
  std::vector<ContactSampleRecord> out;
  const std::vector<Eigen::VectorXd> x = CurrentSoftPositions();
  SoftView view;
  view.x = &x;
  view.dofOffset = &softDofOffset_;
  pipeline_.CollectSamples(CurrentPoses(), &out, &view);
  return out;
}

bool Scene::SoftFaceTractions(ActorHandle a, std::vector<Eigen::Vector3d>* tractions,
                              Error* error) {
  if (a.index < 0 || a.index >= NumActors() || !actors_[a.index].soft)
    return Fail(error, "actor: not a soft actor handle");
  const SoftBodyModel& m = softModels_[actors_[a.index].local];
  tractions->assign(m.faces.size(), Eigen::Vector3d::Zero());
  for (const ContactSampleRecord& r : ContactSamples())
    if (r.colliding == a.index && r.face >= 0)
      (*tractions)[r.face] += r.weight * r.traction / m.faceArea[r.face];
  return true;
}

EnergyReport Scene::Energies() {
  EnergyReport e;
  for (size_t i = 0; i < models_.size(); ++i) {
    if (!models_[i].dynamic) continue;
    e.kinetic += KineticEnergy(models_[i], states_[i]);
    e.gravity += -models_[i].mass * settings_.gravity.dot(states_[i].p);
  }
  for (size_t s = 0; s < softModels_.size(); ++s) {
    const SoftBodyModel& m = softModels_[s];
    e.kinetic += KineticEnergy(m, softStates_[s]);
    for (int i = 0; i < m.NumNodes(); ++i)
      e.gravity += -m.nodeMass[i] * settings_.gravity.dot(softStates_[s].x.segment<3>(3 * i));
    e.elastic += ElasticEnergy(m, softStates_[s].x, nullptr);
  }
  e.contact = ContactState().energy;
  return e;
}

Eigen::Vector3d Scene::TotalLinearMomentum() const {
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < models_.size(); ++i)
    if (models_[i].dynamic) L += LinearMomentum(models_[i], states_[i]);
  for (size_t s = 0; s < softModels_.size(); ++s)
    for (int a = 0; a < softModels_[s].NumNodes(); ++a)
      L += softModels_[s].nodeMass[a] * softStates_[s].v.segment<3>(3 * a);
  return L;
}

Eigen::Vector3d Scene::TotalAngularMomentum() const {
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < models_.size(); ++i)
    if (models_[i].dynamic) L += AngularMomentum(models_[i], states_[i]);
  for (size_t s = 0; s < softModels_.size(); ++s)
    for (int a = 0; a < softModels_[s].NumNodes(); ++a)
      L += softModels_[s].nodeMass[a] *
           softStates_[s].x.segment<3>(3 * a).cross(softStates_[s].v.segment<3>(3 * a));
  return L;
}

std::vector<std::string> Scene::Notices() const {
  std::vector<std::string> out;
  for (const auto& m : models_)
    if (!m.notice.empty()) out.push_back(m.notice);
  for (const auto& m : softModels_)
    if (!m.notice.empty()) out.push_back(m.notice);
  return out;
}

bool Scene::HasDissipation() const {
  // A pair's μ, c_t and c_n are geometric means: dissipation needs two actors, one of them
  // dynamic, that both have a nonzero coefficient of the same kind.
  auto twoWith = [&](auto coefficient) {
    int count = 0, dynamic = 0;
    for (const auto& m : models_)
      if (coefficient(m.contact) > 0) {
        ++count;
        dynamic += m.dynamic;
      }
    for (const auto& m : softModels_)  // soft actors are always dynamic
      if (coefficient(m.contact) > 0) {
        ++count;
        ++dynamic;
      }
    return count >= 2 && dynamic >= 1;
  };
  return twoWith([](const ContactParams& c) { return c.coulombFrictionCoefficient; }) ||
         twoWith([](const ContactParams& c) { return c.viscousFrictionCoefficient; }) ||
         twoWith([](const ContactParams& c) { return c.normalViscousDampingCoefficient; });
}

}  // namespace superdex
