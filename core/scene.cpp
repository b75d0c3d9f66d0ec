#include "core/scene.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <chrono>
#include <cmath>
#include <sstream>

#include "core/rigid_math.h"
#include "core/rigid_stage.h"
#include "optim/ceres_stage_solver.h"
#include "optim/ipopt_stage_solver.h"
#include "optim/residual_newton.h"

namespace superdex {
namespace {

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

int Severity(StageStatus s) {
  return s == StageStatus::Converged ? 0 : s == StageStatus::Stopped ? 1 : 2;
}

}  // namespace

std::string Validate(const SceneSettings& s, const std::string& prefix) {
  if (!s.gravity.allFinite()) return prefix + "gravity: must be finite";
  if (std::string m = Validate(s.solver); !m.empty()) return prefix + "solver." + m;
  if (std::string m = Validate(s.eval, prefix + "experimental_eval_params."); !m.empty()) return m;
  switch (s.integrator) {
    case IntegrationMethod::BackwardEuler:
    case IntegrationMethod::BDF2:
    case IntegrationMethod::SymplecticDIRK12: break;
    default:
      return prefix + "integrator: " + ToString(s.integrator) +
             " is not supported yet (supported: BackwardEuler, BDF2, SymplecticDIRK12)";
  }
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

Scene::Scene(const SceneSettings& settings) : settings_(settings) {}

bool Scene::SetStageSolver(StageSolverKind kind, Error* error) {
  if (kind == StageSolverKind::Ipopt && HasDissipation() && !settings_.eval.explicitNormals)
    return Fail(error, "stage_solver: ipopt minimizes potential stages only, and this scene's "
                       "dissipation is not a potential (explicit_normals = false); use newton or "
                       "ceres, or set experimental_eval_params.explicit_normals = true");
  settings_.stageSolver = kind;
  return true;
}

ActorHandle Scene::AddRigidActor(const RigidActorDesc& desc, Error* error) {
  RigidBodyModel model;
  RigidBodyState state;
  if (!BuildRigidBody(desc, "", &model, &state, error)) return {};
  models_.push_back(std::move(model));
  states_.push_back(state);
  prepared_ = false;
  hasHistory_ = false;
  return {static_cast<int>(models_.size()) - 1};
}

bool Scene::SetIntegrator(IntegrationMethod method, Error* error) {
  SceneSettings s = settings_;
  s.integrator = method;
  if (std::string m = Validate(s); !m.empty()) return Fail(error, m);
  settings_ = s;
  hasHistory_ = false;
  return true;
}

bool Scene::SetState(ActorHandle a, const RigidBodyState& state, Error* error) {
  if (a.index < 0 || a.index >= NumActors()) return Fail(error, "actor: invalid handle");
  if (!state.p.allFinite() || !state.R.allFinite() || !state.v.allFinite() ||
      !state.Rdot.allFinite())
    return Fail(error, "state: must be finite");
  if ((state.R.transpose() * state.R - Eigen::Matrix3d::Identity()).norm() > 1e-9 ||
      state.R.determinant() <= 0)
    return Fail(error, "state.R: must be a rotation matrix");
  states_[a.index] = state;
  hasHistory_ = false;
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
  pipeline_.Configure(&models_);
  prepared_ = true;
}

std::vector<RigidPose> Scene::CurrentPoses() const {
  std::vector<RigidPose> poses(states_.size());
  for (size_t i = 0; i < states_.size(); ++i) poses[i] = {states_[i].p, states_[i].R};
  return poses;
}

SolverStats Scene::SolveStage(double dt, const std::vector<RigidBodyState>& start,
                              std::vector<RigidPose>* poses, ContactStats* contact) {
  StageTargets targets;
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
    s.last = {states_[i].p, states_[i].R};
  }
  StageDissipation dissipation;
  dissipation.enabled = HasDissipation();
  if (dissipation.enabled) {
    dissipation.mode = ModeOf(settings_.eval);
    dissipation.fadeFriction = settings_.eval.fadeFriction;
  }
  RigidStageProblem problem(models_, dofOffset_, numDofs_, targets, settings_.gravity, &pipeline_,
                            poses, dissipation);
  SolverStats st;
  switch (settings_.stageSolver) {
    case StageSolverKind::Newton:
      st = problem.IsPotential() ? MinimizeNewton(problem, settings_.solver, dt)
                                 : SolveResidualNewton(problem, settings_.solver, dt);
      break;
    case StageSolverKind::Ipopt:
      st = MinimizeIpopt(problem, IpoptStageParams());
      break;
    case StageSolverKind::Ceres:
      st = SolveCeres(problem, CeresStageParams());
      break;
  }
  *contact = problem.LastContactStats();
  return st;
}

bool Scene::Step(double h, StepReport* report, Error* error) {
  if (!(std::isfinite(h) && h > 0)) {
    std::ostringstream s;
    s << "dt: must be > 0 and finite, got " << h;
    return Fail(error, s.str());
  }
  if (std::string m = Validate(settings_); !m.empty()) return Fail(error, m);
  if (settings_.stageSolver == StageSolverKind::Ipopt && !SetStageSolver(settings_.stageSolver, error))
    return false;
  const auto t0 = std::chrono::steady_clock::now();
  Prepare();
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
    rep.finalGradientNorm = std::max(rep.finalGradientNorm, st.finalGradientNorm);
    if (Severity(st.status) > Severity(rep.status)) {
      rep.status = st.status;
      rep.message = st.message;
    }
  };

  const size_t n = models_.size();
  std::vector<RigidPose> poses = CurrentPoses();
  std::vector<RigidBodyState> next = states_;
  IntegrationMethod method = settings_.integrator;
  if (method == IntegrationMethod::BDF2 && !hasHistory_) method = IntegrationMethod::BackwardEuler;

  switch (method) {
    case IntegrationMethod::BackwardEuler: {
      account(SolveStage(h, states_, &poses, &stageContact));
      for (size_t i = 0; i < n; ++i) {
        if (!models_[i].dynamic) continue;
        next[i].p = poses[i].p;
        next[i].R = poses[i].R;
        next[i].v = (poses[i].p - states_[i].p) / h;
        next[i].Rdot = (poses[i].R - states_[i].R) / h;
      }
      break;
    }
    case IntegrationMethod::BDF2: {
      // Variable-step BDF2, ω = h_n / h_{n−1}:
      //   x_{n+1} − a x_n + b x_{n−1} = Δt v_{n+1},  a = (1+ω)²/(1+2ω), b = ω²/(1+2ω),
      //   Δt = h (1+ω)/(1+2ω); the same for v. Stage: x⁰ = a x_n − b x_{n−1}, v⁰ likewise.
      const double w = h / previousDt_;
      const double a = (1 + w) * (1 + w) / (1 + 2 * w);
      const double b = w * w / (1 + 2 * w);
      const double dt = h * (1 + w) / (1 + 2 * w);
      std::vector<RigidBodyState> start(n);
      for (size_t i = 0; i < n; ++i) start[i] = Affine(a, states_[i], -b, previous_[i]);
      account(SolveStage(dt, start, &poses, &stageContact));
      for (size_t i = 0; i < n; ++i) {
        if (!models_[i].dynamic) continue;
        next[i].p = poses[i].p;
        next[i].R = poses[i].R;
        next[i].v = (poses[i].p - start[i].p) / dt;
        next[i].Rdot = (poses[i].R - start[i].R) / dt;
      }
      break;
    }
    case IntegrationMethod::SymplecticDIRK12: {
      // Implicit midpoint: a Backward Euler stage of h/2 to y, then x_{n+1} = 2y − x_n (rotations
      // in the Lie algebra: R_{n+1} = exp(2 log(R_y R_nᵀ)) R_n = R_y R_nᵀ R_y) and
      // v_{n+1} = 2 v_y − v_n with v_y = (y − x_n)/(h/2); the spin as below.
      const double dt = 0.5 * h;
      account(SolveStage(dt, states_, &poses, &stageContact));
      for (size_t i = 0; i < n; ++i) {
        if (!models_[i].dynamic) continue;
        const RigidBodyState& s = states_[i];
        const Eigen::Vector3d vy = (poses[i].p - s.p) / dt;
        const Eigen::Matrix3d Rdy = (poses[i].R - s.R) / dt;
        next[i].p = 2.0 * poses[i].p - s.p;
        next[i].R = NearestRotation(poses[i].R * s.R.transpose() * poses[i].R);
        next[i].v = 2.0 * vy - s.v;
        // Material-point midpoint conserves the spin angular momentum of the affine end state
        // (2R_y − R_n, 2Ṙ_y − Ṙ_n) exactly; on SO(3) the same momentum is carried by
        // Ṙ = [ω] R_{n+1} with I_world ω = axial(Ṙ' J R'ᵀ − R' J Ṙ'ᵀ).
        const Eigen::Matrix3d Ra = 2.0 * poses[i].R - s.R;
        const Eigen::Matrix3d Rda = 2.0 * Rdy - s.Rdot;
        const Eigen::Matrix3d& J = models_[i].secondMoment;
        const Eigen::Vector3d spin = Axial(Rda * J * Ra.transpose() - Ra * J * Rda.transpose());
        const Eigen::Matrix3d Iw =
            next[i].R * (J.trace() * Eigen::Matrix3d::Identity() - J) * next[i].R.transpose();
        next[i].Rdot = Skew(Iw.ldlt().solve(spin)) * next[i].R;
      }
      break;
    }
    default:
      return Fail(error, std::string("integrator: ") + ToString(method) + " is not supported yet");
  }
  previous_ = states_;
  previousDt_ = h;
  hasHistory_ = true;
  states_ = std::move(next);
  time_ += h;
  rep.time = time_;
  rep.contact = ContactState();
  rep.wallSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (report) *report = rep;
  return true;
}

ContactStats Scene::ContactState() {
  Prepare();
  ContactStats st;
  pipeline_.Evaluate(CurrentPoses(), dofOffset_, 0, PsdProjection::None, nullptr, nullptr, &st);
  return st;
}

EnergyReport Scene::Energies() {
  EnergyReport e;
  for (size_t i = 0; i < models_.size(); ++i) {
    if (!models_[i].dynamic) continue;
    e.kinetic += KineticEnergy(models_[i], states_[i]);
    e.gravity += -models_[i].mass * settings_.gravity.dot(states_[i].p);
  }
  e.contact = ContactState().energy;
  return e;
}

Eigen::Vector3d Scene::TotalLinearMomentum() const {
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < models_.size(); ++i)
    if (models_[i].dynamic) L += LinearMomentum(models_[i], states_[i]);
  return L;
}

Eigen::Vector3d Scene::TotalAngularMomentum() const {
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < models_.size(); ++i)
    if (models_[i].dynamic) L += AngularMomentum(models_[i], states_[i]);
  return L;
}

std::vector<std::string> Scene::Notices() const {
  std::vector<std::string> out;
  for (const auto& m : models_)
    if (!m.notice.empty()) out.push_back(m.notice);
  return out;
}

bool Scene::HasDissipation() const {
  for (const auto& m : models_)
    if (m.contact.coulombFrictionCoefficient > 0 || m.contact.viscousFrictionCoefficient > 0 ||
        m.contact.normalViscousDampingCoefficient > 0)
      return true;
  return false;
}

}  // namespace superdex
