#include "core/sensitivity/sensitivity.h"

#include <chrono>
#include <cmath>

#include <memory>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/dynamics/integrators.h"
#include "core/model/rigid_math.h"
#include "core/sensitivity/scene_replica.h"

namespace superdex {
namespace {

// The parameters that can be differentiated: contact and material ones by their field (named by
// kContactParamsFields and kSoftMaterialFields), the initial-state ones by name.
struct KindRow {
  SceneParameterKind kind;
  double ContactParams::*contact = nullptr;
  double SoftMaterial::*material = nullptr;
  const char* name = nullptr;
};
constexpr KindRow kKinds[] = {
    {SceneParameterKind::PenaltyCoefficient, &ContactParams::penaltyCoefficient},
    {SceneParameterKind::CoulombFrictionCoefficient, &ContactParams::coulombFrictionCoefficient},
    {SceneParameterKind::ViscousFrictionCoefficient, &ContactParams::viscousFrictionCoefficient},
    {SceneParameterKind::NormalViscousDampingCoefficient,
     &ContactParams::normalViscousDampingCoefficient},
    {SceneParameterKind::FrictionFalloffVel, &ContactParams::frictionFalloffVel},
    {SceneParameterKind::YoungsModulus, nullptr, &SoftMaterial::youngsModulus},
    {SceneParameterKind::Density, nullptr, &SoftMaterial::density},
    {SceneParameterKind::Mass, nullptr, nullptr, "mass"},
    {SceneParameterKind::LinkMass, nullptr, nullptr, "link_mass"},
    {SceneParameterKind::DriveStiffness, nullptr, nullptr, "drive_stiffness"},
    {SceneParameterKind::DriveDamping, nullptr, nullptr, "drive_damping"},
    {SceneParameterKind::Position, nullptr, nullptr, "position"},
    {SceneParameterKind::Velocity, nullptr, nullptr, "velocity"},
    {SceneParameterKind::AngularVelocity, nullptr, nullptr, "angular_velocity"},
};

const KindRow& RowOf(SceneParameterKind kind) {
  for (const KindRow& k : kKinds)
    if (k.kind == kind) return k;
  return kKinds[0];
}

const char* NameOf(const KindRow& k) {
  if (k.contact) return FieldName(kContactParamsFields, k.contact);
  if (k.material) return FieldName(kSoftMaterialFields, k.material);
  return k.name;
}

bool IsContactKind(SceneParameterKind k) { return RowOf(k).contact != nullptr; }

KindMotion MotionOf(SceneParameterKind k) {
  return k == SceneParameterKind::Position   ? KindMotion::Position
         : k == SceneParameterKind::Velocity ? KindMotion::Velocity
                                             : KindMotion::AngularVelocity;
}

// Whether actor a's initial-state parameters are its kind's (ActorKind::MotionParameter): every
// actor but a rigid one, whose parameters are read in its state's own form (p, v, Ṙ = [ω]× R).
bool ThroughKind(const Scene& scene, ActorHandle a) { return scene.IsKind(a) || scene.IsSoft(a); }

const ArticulatedKind* ArticulatedOf(const Scene& scene, ActorHandle a) {
  return dynamic_cast<const ArticulatedKind*>(&scene.Kind(a));
}

// An initial-state parameter of a kind's actor: its value and direction over the actor's [q; v].
bool KindMotionParameter(const Scene& scene, const SceneParameter& p, double* value,
                         Eigen::VectorXd* direction) {
  return scene.Kind(p.actor).MotionParameter(MotionOf(p.kind), p.component,
                                             scene.KindStateOf(p.actor), value, direction);
}

}  // namespace

bool ParseSceneParameter(const Scene& scene, const std::string& text, SceneParameter* p,
                         Error* error) {
  const size_t dot = text.find('.');
  if (dot == std::string::npos || dot == 0)
    return Fail(error, "parameter '" + text + "': expected ACTOR.NAME, e.g. "
                      "box.coulomb_friction_coefficient");
  const std::string actor = text.substr(0, dot);
  std::string name = text.substr(dot + 1);
  p->actor = scene.FindActor(actor);
  if (!p->actor.IsValid())
    return Fail(error, "parameter '" + text + "': no actor named '" + actor + "'");
  p->component = 0;
  const size_t dot2 = name.find('.');
  std::string axis;
  if (dot2 != std::string::npos) {
    axis = name.substr(dot2 + 1);
    name = name.substr(0, dot2);
  }
  bool found = false;
  for (const KindRow& k : kKinds)
    if (name == NameOf(k)) {
      p->kind = k.kind;
      found = true;
    }
  if (!found) {
    std::string all;
    for (const KindRow& k : kKinds) all += std::string(all.empty() ? "" : ", ") + NameOf(k);
    return Fail(error, "parameter '" + text + "': unknown name '" + name + "'; one of " + all);
  }
  const bool soft = scene.IsSoft(p->actor), kind = scene.IsKind(p->actor);
  if (p->IsLinkParameter()) {  // "ACTOR.NAME.LINK" of an articulated actor
    const ArticulatedKind* tree = ArticulatedOf(scene, p->actor);
    if (!tree)
      return Fail(error, "parameter '" + text + "': " + name + " is an articulated actor's and '" +
                             actor + "' is not one");
    p->component = tree->FindLink(axis);
    if (p->component < 0)
      return Fail(error, "parameter '" + text + "': " + name + " needs a link of '" + actor +
                             "' by name (" + name + ".LINK), got '" + axis + "'");
    const JointType type = tree->Tree().Joint(p->component).type;
    if (p->kind != SceneParameterKind::LinkMass && type != JointType::Revolute &&
        type != JointType::Prismatic)
      return Fail(error, "parameter '" + text + "': drives are for Revolute and Prismatic "
                             "joints, link '" + axis + "''s is " + ToString(type));
    return true;
  }
  if (p->IsInitialState()) {
    if (axis != "x" && axis != "y" && axis != "z")
      return Fail(error, "parameter '" + text + "': " + name + " needs a component .x, .y or .z");
    p->component = axis[0] - 'x';
    if (soft && p->kind == SceneParameterKind::AngularVelocity)
      return Fail(error, "parameter '" + text + "': angular_velocity is for rigid actors");
    if (!soft && !kind && !scene.Model(p->actor).dynamic)
      return Fail(error, "parameter '" + text + "': actor '" + actor + "' is static");
    double value = 0.0;
    Eigen::VectorXd direction;
    if ((kind || soft) && !KindMotionParameter(scene, *p, &value, &direction))
      return Fail(error, "parameter '" + text + "': actor '" + actor + "' (" +
                             scene.Kind(p->actor).KindName() + ") has no " + name +
                             (scene.Kind(p->actor).IsStatic() ? " (it is static)" : ""));
  } else {
    if (!axis.empty())
      return Fail(error, "parameter '" + text + "': " + name + " has no components");
    if (!soft && p->kind == SceneParameterKind::YoungsModulus)
      return Fail(error, "parameter '" + text + "': " + name + " is a soft-actor material "
                        "parameter and '" + actor + "' is " +
                        (kind ? "a " + scene.Kind(p->actor).KindName() + " actor" : "rigid"));
    const bool rigidMass =
        p->kind == SceneParameterKind::Mass || p->kind == SceneParameterKind::Density;
    if (rigidMass && !soft && (kind || !scene.Model(p->actor).dynamic))
      return Fail(error, "parameter '" + text + "': " + name + " is a soft or dynamic rigid "
                             "actor's and '" + actor + "' is " +
                             (kind ? "a " + scene.Kind(p->actor).KindName() + " actor"
                                   : "not dynamic"));
    if (p->kind == SceneParameterKind::Mass && soft)
      return Fail(error, "parameter '" + text + "': mass is a dynamic rigid actor's and '" +
                             actor + "' is soft (fit its density)");
  }
  return true;
}

std::string SceneParameterNames() {
  std::string all;
  for (const KindRow& k : kKinds)
    all += std::string(all.empty() ? "" : ", ") + NameOf(k) +
           (k.kind >= SceneParameterKind::Position ? ".x|y|z"
            : k.kind >= SceneParameterKind::LinkMass ? ".LINK" : "");
  return all;
}

std::string ToString(const Scene& scene, const SceneParameter& p) {
  std::string s = scene.ActorName(p.actor) + "." + NameOf(RowOf(p.kind));
  if (p.IsLinkParameter()) s += "." + ArticulatedOf(scene, p.actor)->LinkName(p.component);
  if (p.IsInitialState()) s += std::string(".") + char('x' + p.component);
  return s;
}

double ParameterValue(const Scene& scene, const SceneParameter& p) {
  if (IsContactKind(p.kind)) return scene.GetContactParams(p.actor).*RowOf(p.kind).contact;
  if (p.kind == SceneParameterKind::YoungsModulus)
    return scene.SoftModel(p.actor).material.youngsModulus;
  if (p.kind == SceneParameterKind::Density)
    return scene.IsSoft(p.actor) ? scene.SoftModel(p.actor).material.density
                                 : scene.Model(p.actor).mass / scene.Model(p.actor).volume;
  if (p.kind == SceneParameterKind::Mass) return scene.Model(p.actor).mass;
  if (p.IsLinkParameter()) {
    const ArticulatedKind& tree = *ArticulatedOf(scene, p.actor);
    const JointParams& j = tree.LinkJointParams(p.component);
    return p.kind == SceneParameterKind::LinkMass       ? tree.LinkMass(p.component)
           : p.kind == SceneParameterKind::DriveStiffness ? j.driveStiffness
                                                          : j.driveDamping;
  }
  if (ThroughKind(scene, p.actor)) {  // a soft actor's: the mean over its nodes
    double value = NAN;
    Eigen::VectorXd direction;
    KindMotionParameter(scene, p, &value, &direction);
    return value;
  }
  const RigidBodyState& s = scene.State(p.actor);
  if (p.kind == SceneParameterKind::Position) return s.p[p.component];
  if (p.kind == SceneParameterKind::Velocity) return s.v[p.component];
  return s.AngularVelocity()[p.component];
}

bool SetParameterValue(Scene* scene, const SceneParameter& p, double value, Error* error) {
  if (IsContactKind(p.kind)) {
    ContactParams c = scene->GetContactParams(p.actor);
    c.*RowOf(p.kind).contact = value;
    return scene->SetContactParams(p.actor, c, error);
  }
  if (p.kind == SceneParameterKind::Mass) return scene->SetRigidMass(p.actor, value, error);
  if (p.kind == SceneParameterKind::LinkMass)
    return scene->SetLinkMass(p.actor, p.component, value, error);
  if (p.IsLinkParameter()) {
    JointParams j = ArticulatedOf(*scene, p.actor)->LinkJointParams(p.component);
    (p.kind == SceneParameterKind::DriveStiffness ? j.driveStiffness : j.driveDamping) = value;
    return scene->SetLinkJointParams(p.actor, p.component, j, error);
  }
  if (p.kind == SceneParameterKind::Density && !scene->IsSoft(p.actor))
    return scene->SetRigidMass(p.actor, value * scene->Model(p.actor).volume, error);
  if (p.kind == SceneParameterKind::YoungsModulus || p.kind == SceneParameterKind::Density) {
    const SoftMaterial& m = scene->SoftModel(p.actor).material;
    return p.kind == SceneParameterKind::YoungsModulus
               ? scene->SetSoftMaterial(p.actor, value, m.density, error)
               : scene->SetSoftMaterial(p.actor, m.youngsModulus, value, error);
  }
  if (!std::isfinite(value))
    return Fail(error, ToString(*scene, p) + ": must be finite");
  if (ThroughKind(*scene, p.actor)) {  // the state moves along the parameter's direction
    double current = 0.0;
    Eigen::VectorXd d;
    if (!KindMotionParameter(*scene, p, &current, &d))
      return Fail(error, ToString(*scene, p) + ": the actor's kind has no such parameter");
    KindState s = scene->KindStateOf(p.actor);
    const Eigen::Index n = s.x.size();
    s.x += (value - current) * d.head(n);
    s.v += (value - current) * d.tail(n);
    return scene->SetKindState(p.actor, s, error);
  }
  const double shift = value - ParameterValue(*scene, p);
  RigidBodyState s = scene->State(p.actor);
  if (p.kind == SceneParameterKind::Position) s.p[p.component] += shift;
  if (p.kind == SceneParameterKind::Velocity) s.v[p.component] += shift;
  if (p.kind == SceneParameterKind::AngularVelocity)
    s.Rdot += Skew(shift * Eigen::Vector3d::Unit(p.component)) * s.R;
  return scene->SetState(p.actor, s, error);
}

namespace {

// The smallest stage step Δt_i of one step of the method: γ·dt for the BDF methods (γ = 1, 2/3,
// 6/11 for BDF1-3; the first steps run BackwardEuler or DIRK33), min a_ii·dt for the DIRKs.
double SmallestStageStep(IntegrationMethod method, double dt) {
  double fraction = 1.0;
  if (IsMultistep(method)) {
    fraction = BdfSteps(method) == 2 ? 2.0 / 3.0 : 6.0 / 11.0;
    const DirkTableau& startup = TableauOf(IntegrationMethod::DIRK33);
    for (int i = 0; i < startup.stages; ++i) fraction = std::min(fraction, startup.a[i][i]);
  } else {
    const DirkTableau& T = TableauOf(method);
    for (int i = 0; i < T.stages; ++i) fraction = std::min(fraction, T.a[i][i]);
  }
  return fraction * dt;
}

}  // namespace

// Perturbation sizes. r is most curved in the stage velocity (Y − Y⁰)/Δt_i through the friction
// regularization ρ, on the scale V_f: a position perturbation s moves it by s/Δt_i, a velocity
// perturbation δv by δv. The state moves by at most s = 0.024 V_f min Δt_i in positions and
// s/dt in velocities, which keeps that curvature's O(η²) share small, and the Richardson
// combination below removes it; much below that the rounding of the stage velocities
// (x − x⁰)/Δt_i, and for the DIRKs of their slopes (V − v⁰)/Δt_i, takes over. The friction force
// is evaluated about the recorded slips (core/contact/slip_tape.h), so the kinks of its Jacobian at
// V_t = 0 and V_f do not limit the step. Measured on the tests' scenes (worst of the
// derivatives of tests/core/test_sensitivity.cpp against trajectory differences): 3.4e-5 at
// 0.006 (rounding), 6.8e-6 at 0.012, 4.1e-6 at 0.018, 2.0e-6 at 0.024, 2.4e-6 at 0.032, 2.0e-6 at
// 0.048, and 2.0e-6 … 5.9e-6 with 0.024 scaled by 0.9 … 1.1 (rounding noise); the four-box
// stack's forward derivatives under six integrators (test_adjoint.cpp): mean 1.5e-5 at 0.012,
// 1.3e-5 at 0.024. Model parameters move by at most 1e-4 of their value.
double DifferenceStateStep(const Scene& scene, double dt) {
  return 0.024 * scene.MinFrictionFalloffVel() * SmallestStageStep(scene.Settings().integrator, dt);
}

bool CheckDifferentiable(Scene& scene, const SceneParameter& p, int index, Error* error) {
  if (!p.actor.IsValid() || p.actor.index >= scene.NumActors())
    return Fail(error, "parameter " + std::to_string(index) + ": invalid actor handle");
  const std::string name = ToString(scene, p);
  for (int a = 0; a < scene.NumActors(); ++a)
    if (scene.Carrier({a}).IsValid() && !scene.IsAttached({a}))
      return Fail(error, name + ": actor '" + scene.ActorName({a}) + "' is a soft skin; "
                         "sensitivities through soft-skinned actors are not supported yet");
  for (int a = 0; a < scene.NumActors(); ++a)
    if (scene.Kind({a}).PointCloud())
      return Fail(error, name + ": actor '" + scene.ActorName({a}) + "' is a PointCloud "
                         "collider; sensitivities through point-cloud contact are not supported "
                         "yet");
  if (p.IsLinkParameter()) {
    if (!(ParameterValue(scene, p) > 0))
      return Fail(error, name + ": differentiated at positive values only; start from a value > 0");
    return true;
  }
  if (!p.IsInitialState()) {
    if (!(ParameterValue(scene, p) > 0))
      return Fail(error, name + ": differentiated at positive values only (the pair value "
                         "is the geometric mean of the two actors', not differentiable at "
                         "0); start from a value > 0");
    return true;
  }
  if (scene.HasStepHistory())
    return Fail(error, name + ": an initial-state parameter is differentiated from the first "
                       "step (the scene already has step history)");
  return true;
}

Eigen::VectorXd InitialStateDirection(Scene& scene, const SceneParameter& p) {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(scene.StateSize());
  if (!p.IsInitialState()) return d;
  const int o = scene.StateOffset(p.actor);
  const int c = p.component;
  if (ThroughKind(scene, p.actor)) {
    double value = 0.0;
    Eigen::VectorXd direction;
    if (KindMotionParameter(scene, p, &value, &direction))
      d.segment(o, direction.size()) = direction;
  } else if (p.kind == SceneParameterKind::Position) {
    d[o + c] = 1.0;
  } else if (p.kind == SceneParameterKind::Velocity) {
    d[o + 12 + c] = 1.0;
  } else {  // Ṙ = [ω]× R
    const Eigen::Matrix3d dRdot = Skew(Eigen::Vector3d::Unit(c)) * scene.State(p.actor).R;
    d.segment(o + 15, 9) = Eigen::Map<const Eigen::VectorXd>(dRdot.data(), 9);
  }
  return d;
}

Eigen::SparseMatrix<double> CenterOfMassMap(Scene& scene, ActorHandle a) {
  Eigen::SparseMatrix<double> C(3, scene.StateSize());
  const int o = scene.StateOffset(a);
  if (o < 0) return C;
  std::vector<Eigen::Triplet<double>> t;
  if (ThroughKind(scene, a)) {
    const Eigen::MatrixXd J = scene.Kind(a).CenterOfMassJacobian(scene.KindStateOf(a));
    for (int c = 0; c < 3; ++c)
      for (Eigen::Index i = 0; i < J.cols(); ++i)
        if (J(c, i) != 0.0) t.emplace_back(c, o + i, J(c, i));
  } else {
    for (int c = 0; c < 3; ++c) t.emplace_back(c, o + c, 1.0);
  }
  C.setFromTriplets(t.begin(), t.end());
  return C;
}

// The replicas of a forward-sensitivity run: made on a thread's first replay, refreshed with the
// recorded stage solutions and factors once per step (`step` counts the steps).
struct ForwardSensitivity::Replicas {
  struct Entry {
    std::unique_ptr<SceneReplica> replica;
    long step = 0;
  };
  tbb::enumerable_thread_specific<Entry> perThread;
  long step = 0;
};

bool ForwardSensitivity::Begin(Scene* scene, const std::vector<SceneParameter>& parameters,
                               Error* error) {
  scene_ = scene;
  parameters_ = parameters;
  replicas_.reset();  // copies of the scene as it is now are made on the first step
  stepSeconds_ = tangentSeconds_ = 0.0;
  const int P = static_cast<int>(parameters.size());
  dS_ = Eigen::MatrixXd::Zero(scene->StateSize(), P);
  for (int j = 0; j < P; ++j) {
    if (!CheckDifferentiable(*scene, parameters[j], j, error)) return false;
    dS_.col(j) = InitialStateDirection(*scene, parameters[j]);
  }
  return true;
}

bool ForwardSensitivity::Step(double dt, StepReport* report, Error* error) {
  Scene& scene = *scene_;
  const auto t0 = std::chrono::steady_clock::now();
  const Scene::Snapshot before = scene.Save();
  const Eigen::VectorXd S0 = scene.PackState();
  const bool ok = StepAndRecord(&scene, dt, &tape_, report, error);
  const auto t1 = std::chrono::steady_clock::now();
  stepSeconds_ += std::chrono::duration<double>(t1 - t0).count();
  if (!ok) return false;
  const int P = static_cast<int>(parameters_.size());
  Eigen::MatrixXd next(dS_.rows(), P);
  const double stateStep = DifferenceStateStep(scene, dt);
  const Eigen::VectorXd weight =
      (Eigen::VectorXd::Ones(dS_.rows()) + (dt - 1.0) * scene.PackedVelocityMask());
  // (S(+e) − S(−e)) / 2e for direction j with the state and parameter moved together, replayed on
  // `sc` (the scene or a replica) with `tape`.
  auto difference = [&](Scene& sc, StepTape& tape, int j, double e, Eigen::VectorXd* out,
                        Error* err) -> bool {
    const SceneParameter& p = parameters_[j];
    const bool model = !p.IsInitialState();
    const double theta = model ? ParameterValue(sc, p) : 0.0;
    Eigen::VectorXd plus;
    for (int sign : {1, -1}) {
      sc.Restore(before);
      sc.UnpackState(S0 + (sign * e) * dS_.col(j));
      if (model && !SetParameterValue(&sc, p, theta + sign * e, err)) return false;
      TapeRecorder replay(&tape, TapeRecorder::Mode::Replay);
      const bool stepped = sc.Step(dt, nullptr, err, &replay);
      if (model) SetParameterValue(&sc, p, theta, nullptr);
      if (!stepped) return false;
      if (sign > 0)
        plus = sc.PackState();
      else
        *out = (plus - sc.PackState()) / (2.0 * e);
    }
    return true;
  };
  // Column j of dS_{n+1}/dθ.
  auto column = [&](Scene& sc, StepTape& tape, int j, Error* err) -> bool {
    const SceneParameter& p = parameters_[j];
    // Velocity entries weigh by dt: a velocity change δv moves the stage velocity by δv.
    const double stateNorm = dS_.col(j).cwiseProduct(weight).lpNorm<Eigen::Infinity>();
    double eta = p.IsInitialState() ? INFINITY : 1e-4 * std::abs(ParameterValue(sc, p));
    if (stateNorm > 0) eta = std::min(eta, stateStep / stateNorm);
    if (!std::isfinite(eta)) {  // an initial-state direction that no longer moves anything
      next.col(j).setZero();
      return true;
    }
    // Richardson: D(η) = D + c η² + O(η⁴), so (4 D(η/2) − D(η))/3 = D + O(η⁴).
    Eigen::VectorXd coarse, fine;
    if (!difference(sc, tape, j, eta, &coarse, err) ||
        !difference(sc, tape, j, 0.5 * eta, &fine, err))
      return false;
    next.col(j) = (4.0 * fine - coarse) / 3.0;
    return true;
  };
  // Columns in parallel only where they amortize each thread's factorization of the recorded
  // Jacobians, and where the replays are not already parallel inside (soft stages evaluate their
  // tets in parallel). Measured (bench/bench_sensitivity.cpp, 2 cores, 1000 steps): 16 sliding
  // boxes, 96 parameters 26.9 → 15.4 s, 8 parameters 3.3 → 2.6 s; thrown box, 5 parameters
  // 0.084 → 0.070 s; but 2 parameters 0.048 → 0.051–0.059 s, and the 27-node soft cube with 2 or 5
  // parameters 5–40 % slower.
  const bool parallel = P >= 4 && scene.SoftActors().empty();
  bool replayOk = true;
  if (!parallel) {
    const Scene::Snapshot after = scene.Save();
    for (int j = 0; j < P && replayOk; ++j) replayOk = column(scene, tape_, j, error);
    scene.Restore(after);
  } else {
    // The parameters' replays are independent: in parallel, each thread on its own copy of the
    // scene with its own factors of the recorded stage Jacobians (one factorization per thread
    // and step). Each column is computed whole by one thread: the result does not depend on the
    // number of threads.
    if (!replicas_) replicas_ = std::make_shared<Replicas>();
    ++replicas_->step;
    auto& replicas = replicas_->perThread;
    std::vector<char> ok(P, 0);
    tbb::parallel_for(0, P, [&](int j) {
      Replicas::Entry& r = replicas.local();
      if (!r.replica) r.replica = std::make_unique<SceneReplica>(scene, tape_, true);
      else if (r.step != replicas_->step) r.replica->Refresh(tape_, true);
      r.step = replicas_->step;
      r.replica->error = Error();
      ok[j] = column(r.replica->scene, r.replica->tape, j, &r.replica->error);
    });
    for (int j = 0; j < P && replayOk; ++j)
      if (!ok[j]) {
        replayOk = Fail(error, "the replay of parameter " + ToString(scene, parameters_[j]) +
                                   " failed");
        for (const Replicas::Entry& r : replicas)
          if (r.replica && !r.replica->error.message.empty()) Fail(error, r.replica->error.message);
      }
  }
  tangentSeconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  if (!replayOk) return false;
  dS_ = std::move(next);
  return true;
}

Eigen::MatrixXd ForwardSensitivity::CenterOfMassJacobian(ActorHandle a) const {
  return CenterOfMassMap(*scene_, a) * dS_;
}

}  // namespace superdex
