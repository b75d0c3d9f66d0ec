#include "core/model/rigid_kind.h"

#include <Eigen/Cholesky>
#include <algorithm>

#include "core/model/rigid_math.h"
#include "energies/rigid_inertia.h"

namespace superdex {
namespace {

Eigen::Map<const Eigen::Matrix3d> RotationOf(const Eigen::VectorXd& q) {
  return Eigen::Map<const Eigen::Matrix3d>(q.data() + 3);
}

}  // namespace

void AppendRigidInertiaHessian(const Eigen::Matrix<double, 6, 6>& H, PsdProjection projection,
                               int offset, std::vector<Eigen::Triplet<double>>* triplets) {
  auto append = [&](const auto& M) {
    for (int c = 0; c < 6; ++c)
      for (int r = 0; r < 6; ++r)
        if (r == c || (r >= 3 && c >= 3) || M(r, c) != 0.0)
          triplets->emplace_back(offset + r, offset + c, M(r, c));
  };
  if (projection == PsdProjection::None ||
      Eigen::LLT<Eigen::Matrix3d>(H.bottomRightCorner<3, 3>()).info() == Eigen::Success)
    return append(H);
  SmallStencilMatrix P = H;
  ProjectToPsd(&P, projection == PsdProjection::Abs);
  append(P);
}

void AppendSpinTrivialization(const Eigen::Vector3d& tau, int row,
                              std::vector<Eigen::Triplet<double>>* triplets) {
  const Eigen::Matrix3d S = -0.5 * Skew(tau);
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k)
      if (k != c) triplets->emplace_back(row + k, row + c, S(k, c));
}

double RigidTrustFraction(const RigidBodyModel& m, const Eigen::Vector3d& dp,
                          const Eigen::Vector3d& dtheta) {
  const double rho = std::max(m.samplesRadius, RmsRadius(m));
  if (!(rho > 0.0)) return 1.0;
  const double move = dp.norm() + dtheta.norm() * rho;
  const double trust = kCorrectionTrust * rho;
  return move > trust ? trust / move : 1.0;
}

double RigidStepLength(const RigidBodyModel& m, const Eigen::Vector3d& dp,
                       const Eigen::Vector3d& dtheta) {
  return std::max(dp.lpNorm<Eigen::Infinity>(), dtheta.norm() * RmsRadius(m));
}

DirkRotationSlope DirkStageRotation(const Eigen::Matrix3d& J, const Eigen::Matrix3d& Q,
                                    const Eigen::Matrix3d& R0, const Eigen::Matrix3d& Rdot0,
                                    double dt) {
  const Eigen::Matrix3d V = (Q - R0) / dt;
  DirkRotationSlope out;
  out.torque = SpinMomentum(Q, (V - Rdot0) / dt, J);
  out.V = Skew(WorldInertia(Q, J).ldlt().solve(SpinMomentum(Q, V, J))) * Q;
  return out;
}

Eigen::Matrix3d SpinCorrectedRate(const Eigen::Matrix3d& J, const Eigen::Matrix3d& R,
                                  const Eigen::Matrix3d& Rdot, const Eigen::Vector3d& spin) {
  const Eigen::Vector3d missing = spin - SpinMomentum(R, Rdot, J);
  return Rdot + Skew(WorldInertia(R, J).ldlt().solve(missing)) * R;
}

bool FreeStageAcceleration(double mass, const Eigen::Vector3d& gravity,
                           const Eigen::Vector3d* force, const Eigen::Vector3d* torque,
                           Eigen::Vector3d* a) {
  if (torque && torque->any()) return false;
  *a = force ? Eigen::Vector3d(gravity + *force / mass) : gravity;
  return true;
}

RigidPose PredictRigidPose(const RigidBodyState& s, const RigidBodyState* previous,
                           double hPrevious, double tau, const Eigen::Vector3d* stageStart,
                           double stageDt) {
  const bool history = previous && hPrevious > 0.0;
  Eigen::Vector3d dv = Eigen::Vector3d::Zero(), alpha = Eigen::Vector3d::Zero();
  const Eigen::Vector3d omega = s.AngularVelocity();
  if (history) {
    dv = s.v - previous->v;
    alpha = (omega - previous->AngularVelocity()) / hPrevious;
  }
  RigidPose out;
  if (stageStart) {
    Eigen::Vector3d v = s.v;
    if (history) v += tau * dv / hPrevious;
    out.p = *stageStart + stageDt * v;
  } else {
    const Eigen::Vector3d a = history ? Eigen::Vector3d(dv / hPrevious) : dv;
    out.p = s.p + tau * s.v + 0.5 * tau * tau * a;
  }
  out.R = ExpSo3(tau * omega + 0.5 * tau * tau * alpha) * s.R;
  return out;
}

double RigidForceChange(const RigidBodyModel& m, const RigidBodyState& s2,
                        const RigidBodyState& s1, double hPrevious, const RigidBodyState& s0,
                        double hBefore) {
  const Eigen::Vector3d a2 = (s2.v - s1.v) / hPrevious, a1 = (s1.v - s0.v) / hBefore;
  auto momentum = [&](const RigidBodyState& s) -> Eigen::Vector3d {
    return WorldInertia(s.R, m.secondMoment) * s.AngularVelocity();
  };
  const Eigen::Vector3d L2 = momentum(s2), L1 = momentum(s1), L0 = momentum(s0);
  const Eigen::Vector3d dTorque = (L2 - L1) / hPrevious - (L1 - L0) / hBefore;
  const double rho = RmsRadius(m);
  const double angular = rho > 0.0 ? dTorque.norm() / (m.mass * rho) : 0.0;
  return (a2 - a1).norm() + angular;
}

RigidKind::RigidKind(RigidBodyModel model, const RigidBodyState& state)
    : model_(std::move(model)), initial_(state) {
  contact = model_.contact;
  name = model_.name;
}

void RigidKind::SetMass(double mass) {
  model_.secondMoment *= mass / model_.mass;
  model_.mass = mass;
}

void RigidKind::SetContactParams(const ContactParams& params) {
  contact = params;
  model_.contact = params;
}

std::unique_ptr<RigidKind> RigidKind::Build(const RigidActorDesc& desc, Error* error) {
  RigidBodyModel model;
  RigidBodyState state;
  if (!BuildRigidBody(desc, "", &model, &state, error)) return nullptr;
  return std::make_unique<RigidKind>(std::move(model), state);
}

std::unique_ptr<ActorKind> RigidKind::Clone() const { return std::make_unique<RigidKind>(*this); }

KindState RigidKind::Pack(const RigidBodyState& s) {
  KindState k;
  k.x.resize(12);
  k.v.resize(12);
  k.x.head<3>() = s.p;
  k.x.tail<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(s.R.data());
  k.v.head<3>() = s.v;
  k.v.tail<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(s.Rdot.data());
  return k;
}

RigidBodyState RigidKind::Unpack(const KindState& k) {
  RigidBodyState s;
  s.p = k.x.head<3>();
  s.R = RotationOf(k.x);
  s.v = k.v.head<3>();
  s.Rdot = RotationOf(k.v);
  return s;
}

RigidPose RigidKind::PoseOf(const Eigen::VectorXd& q) {
  RigidPose pose;
  pose.p = q.head<3>();
  pose.R = RotationOf(q);
  return pose;
}

double RigidKind::StageEnergy(const KindStageData& stage, const Eigen::VectorXd& q, int order,
                              PsdProjection projection, Eigen::VectorXd* g,
                              std::vector<Eigen::Triplet<double>>* H) const {
  if (!model_.dynamic) return 0.0;
  const double w = 1.0 / (stage.dt * stage.dt);
  const Eigen::Vector3d p = q.head<3>();
  const RigidInertiaTerm t = RigidInertia(model_.mass, model_.secondMoment, p, RotationOf(q),
                                          stage.qHat.head<3>(), RotationOf(stage.qHat),
                                          order >= 1);
  // An applied force at the centre of mass: the exact potential −F(t_i)·p.
  const Eigen::Vector3d F = model_.appliedForce.empty()
                                ? Eigen::Vector3d::Zero()
                                : PiecewiseLinear(model_.appliedForce, stage.time);
  double value = w * t.value + GravityPotential(model_.mass, stage.gravity, p);
  if (!model_.appliedForce.empty()) value -= F.dot(p);
  if (order < 1) return value;
  g->head<6>() += w * t.gradient;
  g->head<3>() -= model_.mass * stage.gravity;
  if (!model_.appliedForce.empty()) g->head<3>() -= F;
  if (order < 2) return value;
  AppendRigidInertiaHessian(w * t.hessian, projection, 0, H);
  return value;
}

bool RigidKind::StageLoad(const KindStageData& stage, Eigen::VectorXd* f) const {
  if (!model_.dynamic || model_.appliedTorque.empty()) return false;
  f->setZero(6);
  f->tail<3>() = PiecewiseLinear(model_.appliedTorque, stage.time);
  return true;
}

namespace {
// [a, vec M] into *out (12 entries; no allocation once sized).
void PackInto(const Eigen::Vector3d& a, const Eigen::Matrix3d& M, Eigen::VectorXd* out) {
  out->resize(12);
  out->head<3>() = a;
  out->tail<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(M.data());
}
}  // namespace

void RigidKind::Prescribe(double t, Eigen::VectorXd* q) const {
  if (model_.dynamic) return;
  if (!model_.kinematic) return PackInto(initial_.p, initial_.R, q);
  const RigidBodyState s = KinematicStateAt(model_, t);
  PackInto(s.p, s.R, q);
}

void RigidKind::EndPrescribed(double t, KindState* s) const {
  if (!model_.kinematic) return;
  const RigidBodyState k = KinematicStateAt(model_, t);
  PackInto(k.p, k.R, &s->x);
  PackInto(k.v, k.Rdot, &s->v);
}

void RigidChartRetract(const Eigen::VectorXd& q, const Eigen::VectorXd& delta,
                       Eigen::VectorXd* out) {
  out->resize(12);
  out->head<3>() = q.head<3>() + delta.head<3>();
  const Eigen::Matrix3d R = ExpSo3(delta.segment<3>(3)) * RotationOf(q);
  out->tail<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(R.data());
}

void RigidChartBetween(const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                       Eigen::VectorXd* delta) {
  delta->resize(6);
  delta->head<3>() = to.head<3>() - from.head<3>();
  delta->tail<3>() = LogSo3(RotationOf(to) * RotationOf(from).transpose());
}

void RigidKind::Retract(const Eigen::VectorXd& q, const Eigen::VectorXd& delta,
                        Eigen::VectorXd* out) const {
  RigidChartRetract(q, delta, out);
}

void RigidKind::AddResidualJacobianCorrection(const Eigen::VectorXd& /*q*/,
                                              const Eigen::VectorXd& residual,
                                              std::vector<Eigen::Triplet<double>>* J) const {
  if (!model_.dynamic) return;
  AppendSpinTrivialization(residual.segment<3>(3), 3, J);
}

Eigen::MatrixXd RigidKind::ChartTangentMap(const Eigen::VectorXd& delta) const {
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(6, 6);
  T.bottomRightCorner<3, 3>() = LeftJacobianSo3(delta.segment<3>(3));
  return T;
}

double RigidKind::StepLength(const Eigen::VectorXd& /*q*/, const Eigen::VectorXd& delta) const {
  return RigidStepLength(model_, delta.head<3>(), delta.segment<3>(3));
}

double RigidKind::TrustFraction(const Eigen::VectorXd& /*q*/, const Eigen::VectorXd& delta) const {
  return RigidTrustFraction(model_, delta.head<3>(), delta.segment<3>(3));
}

void RigidKind::DirkStageSlope(const Eigen::VectorXd& x, const KindState& start, double dt,
                               KindSlope* out) const {
  KindState& vk = out->slope;
  vk.x.resize(12);
  vk.v.resize(12);
  vk.x.head<3>() = (x.head<3>() - start.x.head<3>()) / dt;
  vk.v.head<3>() = (vk.x.head<3>() - start.v.head<3>()) / dt;
  out->extra.setZero(3);
  if (!model_.dynamic) {  // a kinematic body's stage poses' slope, for the next stages' x⁰
    if (model_.kinematic) {
      vk.x.tail<9>() = (x.tail<9>() - start.x.tail<9>()) / dt;
    } else {
      vk.x.tail<9>().setZero();
    }
    vk.v.tail<9>().setZero();
    return;
  }
  const DirkRotationSlope rot = DirkStageRotation(model_.secondMoment, RotationOf(x),
                                                  RotationOf(start.x), RotationOf(start.v), dt);
  out->extra = rot.torque;
  const Eigen::Matrix3d KR = (rot.V - RotationOf(start.v)) / dt;
  vk.x.tail<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(rot.V.data());
  vk.v.tail<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(KR.data());
}

void RigidKind::DirkStepEnd(const KindState& start, const Eigen::VectorXd& lastStage,
                            bool stifflyAccurate, const std::vector<KindSlope>& slopes,
                            const std::vector<double>& hb, KindState* end) const {
  if (!model_.dynamic) return;
  const Eigen::Matrix3d& J = model_.secondMoment;
  Eigen::Vector3d spin = SpinMomentum(RotationOf(start.x), RotationOf(start.v), J);
  for (size_t st = 0; st < slopes.size(); ++st) spin += hb[st] * slopes[st].extra;  // L̇ = τ
  const Eigen::Matrix3d R =
      stifflyAccurate ? Eigen::Matrix3d(RotationOf(lastStage)) : NearestRotation(RotationOf(end->x));
  const Eigen::Matrix3d RdotEnd = SpinCorrectedRate(J, R, RotationOf(end->v), spin);
  end->x.tail<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(R.data());
  end->v.tail<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(RdotEnd.data());
}

void RigidKind::PredictStage(const KindState& current, const KindState* previous,
                             double hPrevious, double tau, const Eigen::VectorXd& stageStart,
                             double stageDt, Eigen::VectorXd* q) const {
  *q = current.x;
  if (!model_.dynamic) return;
  const Eigen::Vector3d p0 = stageStart.head<3>();
  const RigidBodyState prev = previous ? Unpack(*previous) : RigidBodyState();
  const RigidPose pose =
      PredictRigidPose(Unpack(current), previous ? &prev : nullptr, hPrevious, tau, &p0, stageDt);
  q->head<3>() = pose.p;
  q->tail<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(pose.R.data());
}

void RigidKind::TangentBetween(const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                               Eigen::VectorXd* delta) const {
  RigidChartBetween(from, to, delta);
}

double RigidKind::ForceChange(const KindState& current, const KindState& previous,
                              double hPrevious, const KindState& before, double hBefore) const {
  if (!model_.dynamic || !(model_.mass > 0.0)) return 0.0;
  return RigidForceChange(model_, Unpack(current), Unpack(previous), hPrevious, Unpack(before),
                          hBefore);
}

bool RigidKind::FreeStageMinimizer(const KindStageData& stage, Eigen::VectorXd* q) const {
  if (!model_.dynamic) {
    Prescribe(stage.time, q);
    return true;
  }
  const Eigen::Vector3d F = model_.appliedForce.empty()
                                ? Eigen::Vector3d::Zero()
                                : PiecewiseLinear(model_.appliedForce, stage.time);
  const Eigen::Vector3d tau = model_.appliedTorque.empty()
                                  ? Eigen::Vector3d::Zero()
                                  : PiecewiseLinear(model_.appliedTorque, stage.time);
  Eigen::Vector3d g;
  if (!FreeStageAcceleration(model_.mass, stage.gravity,
                             model_.appliedForce.empty() ? nullptr : &F, &tau, &g))
    return false;
  const RigidInertiaMinimum x =
      MinimizeRigidInertia(model_.secondMoment, stage.qHat.head<3>(), RotationOf(stage.qHat),
                           stage.dt, g);
  q->resize(12);
  q->head<3>() = x.p;
  q->tail<9>() = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(x.R.data());
  return true;
}

void RigidKind::DifferenceGroups(const KindState& s,
                                 std::vector<KindDifferenceGroup>* groups) const {
  groups->clear();
  if (!model_.dynamic) return;
  const double radius = std::max(RmsRadius(model_), 1e-6);
  const Eigen::Matrix3d R = Eigen::Map<const Eigen::Matrix3d>(s.x.data() + 3);
  KindDifferenceGroup g;
  for (int c = 0; c < 3; ++c) g.directions.push_back({{{c, 1.0}}, false, 1.0});
  for (int k = 0; k < 3; ++k) {
    const Eigen::Matrix3d V = Skew(Eigen::Vector3d::Unit(k)) * R;
    KindDifferenceGroup::Direction d{{}, false, radius};
    for (int e = 0; e < 9; ++e) d.entries.emplace_back(3 + e, V.data()[e]);
    g.directions.push_back(std::move(d));
  }
  for (int c = 0; c < 3; ++c) g.directions.push_back({{{12 + c, 1.0}}, true, 1.0});
  for (int e = 0; e < 9; ++e) g.directions.push_back({{{15 + e, 1.0}}, true, radius});
  for (int i = 0; i < 24; ++i) g.entries.push_back(i);
  for (int i = 0; i < 6; ++i) {
    g.tangentDofs.push_back(i);
    g.tangentLength.push_back(i < 3 ? 1.0 : radius);
  }
  groups->push_back(std::move(g));
}

bool RigidKind::MotionParameter(KindMotion motion, int component, const KindState& s,
                                double* value, Eigen::VectorXd* direction) const {
  if (!model_.dynamic || component < 0 || component > 2) return false;
  direction->setZero(24);
  if (motion == KindMotion::Position) {
    *value = s.x[component];
    (*direction)[component] = 1.0;
  } else if (motion == KindMotion::Velocity) {
    *value = s.v[component];
    (*direction)[12 + component] = 1.0;
  } else {  // Ṙ = [ω]× R
    const RigidBodyState b = Unpack(s);
    *value = b.AngularVelocity()[component];
    const Eigen::Matrix3d dRdot = Skew(Eigen::Vector3d::Unit(component)) * b.R;
    direction->segment<9>(15) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(dRdot.data());
  }
  return true;
}

Eigen::MatrixXd RigidKind::CenterOfMassJacobian(const KindState& /*s*/) const {
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(3, 12);
  C.leftCols<3>().setIdentity();
  return C;
}

double RigidKind::KineticEnergy(const KindState& s) const {
  return model_.dynamic ? superdex::KineticEnergy(model_, Unpack(s)) : 0.0;
}

double RigidKind::GravityEnergy(const KindState& s, const Eigen::Vector3d& gravity) const {
  return model_.dynamic ? GravityPotential(model_.mass, gravity, s.x.head<3>()) : 0.0;
}

Eigen::Vector3d RigidKind::LinearMomentum(const KindState& s) const {
  return model_.dynamic ? superdex::LinearMomentum(model_, Unpack(s)) : Eigen::Vector3d::Zero();
}

Eigen::Vector3d RigidKind::AngularMomentum(const KindState& s) const {
  return model_.dynamic ? superdex::AngularMomentum(model_, Unpack(s)) : Eigen::Vector3d::Zero();
}

Aabb RigidKind::Bounds(const Eigen::VectorXd& q) const {
  return WorldBounds(model_, q.head<3>(), RotationOf(q));
}

const RigidCollider* RigidKind::Collider() const {
  return model_.collider.type == ColliderType::None ? nullptr : &model_.collider;
}

KindFrame RigidKind::ColliderFrame(const Eigen::VectorXd& q) const {
  return OwnPoseFrame(PoseOf(q));
}

}  // namespace superdex
