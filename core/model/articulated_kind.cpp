// The articulated actor (articulated_kind.h has the configuration, the stage energy and the DIRK
// rules).
#include "core/model/articulated_kind.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "core/model/rigid_kind.h"
#include "core/model/rigid_math.h"
#include "energies/joint_energies.h"
#include "energies/psd_projection.h"
#include "energies/rigid_inertia.h"

namespace superdex {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;

/// The stage's working memory: forward kinematics and the dense blocks of the chain.
struct ArticulatedScratch : KindScratch {
  KinematicFrames frames;
  Eigen::MatrixXd chart, chartHessian, hessian;
};

/// A link's chart Hessian made positive semi-definite: the rotation block, the one part that may
/// be indefinite (far from R̂), projected per `projection` when it does not factorize.
void ProjectChartHessian(PsdProjection projection, Eigen::Matrix<double, 6, 6>* H) {
  if (Eigen::LLT<Eigen::Matrix3d>(H->bottomRightCorner<3, 3>()).info() == Eigen::Success) return;
  SmallStencilMatrix P = *H;
  ProjectToPsd(&P, projection == PsdProjection::Abs);
  *H = P;
}

/// Whether the 3 × 3 block at `offset` of q is a rotation (to 1e-9).
bool IsRotationAt(const Eigen::VectorXd& q, int offset) {
  const Eigen::Matrix3d R = Matrix3At(q, offset);
  return R.allFinite() && (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() <= 1e-9 &&
         R.determinant() > 0.0;
}

std::string LinkLabel(const ArticulatedActorDesc& desc, int l) {
  std::ostringstream s;
  s << "link " << l;
  if (!desc.links[l].name.empty()) s << " ('" << desc.links[l].name << "')";
  return s.str();
}

/// Empty when link l's mass properties are valid; else the rule they break.
std::string ValidateMass(const ArticulatedLinkDesc& link) {
  if (!(std::isfinite(link.mass) && link.mass >= 0.0)) return "mass must be finite and >= 0";
  if (!link.centerOfMass.allFinite()) return "center_of_mass must be finite";
  const Eigen::Matrix3d& I = link.inertia;
  if (!I.allFinite() || (I - I.transpose()).norm() > 1e-12 * std::max(I.norm(), 1e-300))
    return "inertia must be a finite symmetric matrix";
  // J = ½ tr(I) 1 − I is the second moment; it is PSD exactly when I's eigenvalues obey the
  // triangle inequality (and are >= 0).
  const Eigen::Matrix3d J = 0.5 * I.trace() * Eigen::Matrix3d::Identity() - I;
  const double tol = 1e-12 * std::max(I.trace(), 1e-300);
  if (Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(J).eigenvalues().minCoeff() < -tol)
    return "inertia must be a physical inertia tensor (eigenvalues >= 0 obeying the triangle "
           "inequality)";
  if (link.mass == 0.0 && I.norm() != 0.0) return "a link of mass 0 must have inertia 0";
  return {};
}

}  // namespace

bool BuildLinkShapes(const ArticulatedActorDesc& desc, std::vector<LinkShape>* shapes,
                     Error* error) {
  shapes->clear();
  for (int l = 0; l < static_cast<int>(desc.links.size()); ++l) {
    const ArticulatedLinkDesc& link = desc.links[l];
    for (size_t j = 0; j < link.shapes.size(); ++j) {
      LinkShapeDesc shape = link.shapes[j];
      if (shape.name.empty()) {
        shape.name = desc.name + "/" + (link.name.empty() ? "link" + std::to_string(l) : link.name);
        if (j > 0) shape.name += "#" + std::to_string(j);
      }
      const std::string prefix = "articulation '" + desc.name + "': " + LinkLabel(desc, l) +
                                 ": shapes[" + std::to_string(j) + "].";
      std::unique_ptr<AttachedBodyKind> kind =
          AttachedBodyKind::Build(shape, l, link.centerOfMass, prefix, error);
      if (!kind) return false;
      shapes->push_back({l, std::move(kind)});
    }
  }
  return true;
}

std::unique_ptr<ArticulatedKind> ArticulatedKind::Build(const ArticulatedActorDesc& desc,
                                                        Error* error) {
  const std::string who = "articulation '" + desc.name + "': ";
  if (desc.links.empty()) {
    Fail(error, who + "links: must have at least one link");
    return nullptr;
  }
  std::vector<KinematicJoint> joints;
  for (const ArticulatedLinkDesc& link : desc.links) joints.push_back(link.joint);
  std::unique_ptr<ArticulatedKind> kind(new ArticulatedKind());
  kind->tree_ = KinematicTree(std::move(joints));
  if (std::string m = kind->tree_.Validate(); !m.empty()) {
    Fail(error, who + m);
    return nullptr;
  }
  for (int l = 0; l < kind->NumLinks(); ++l) {
    const ArticulatedLinkDesc& d = desc.links[l];
    if (std::string m = ValidateMass(d); !m.empty()) {
      Fail(error, who + LinkLabel(desc, l) + ": " + m);
      return nullptr;
    }
    if (std::string m = superdex::Validate(d.jointParams, "joint_params."); !m.empty()) {
      Fail(error, who + LinkLabel(desc, l) + ": " + m);
      return nullptr;
    }
    const JointType type = d.joint.type;
    if (d.jointParams.Active() && type != JointType::Revolute && type != JointType::Prismatic) {
      Fail(error, who + LinkLabel(desc, l) + ": joint_params: limits, damping and drives are for " +
                      "Revolute and Prismatic joints, the joint is " + ToString(type));
      return nullptr;
    }
    Link link;
    link.name = d.name;
    link.joint = d.jointParams;
    link.mass = d.mass;
    link.com = d.centerOfMass;
    link.secondMoment = 0.5 * d.inertia.trace() * Eigen::Matrix3d::Identity() - d.inertia;
    link.radius = d.mass > 0.0 ? std::sqrt(link.secondMoment.trace() / d.mass) : 0.0;
    kind->links_.push_back(link);
  }
  const KinematicTree& tree = kind->tree_;
  const int nc = tree.NumCoordinates(), m = tree.NumTangentDofs();
  Eigen::VectorXd qJ = desc.jointPositions.size() ? desc.jointPositions : tree.ZeroConfiguration();
  Eigen::VectorXd u = desc.jointVelocities.size() ? desc.jointVelocities : Eigen::VectorXd::Zero(m);
  std::ostringstream sizes;
  if (qJ.size() != nc || !qJ.allFinite())
    sizes << "joint_positions: must have " << nc << " finite entries, has " << qJ.size();
  else if (u.size() != m || !u.allFinite())
    sizes << "joint_velocities: must have " << m << " finite entries, has " << u.size();
  for (int l = 0; sizes.str().empty() && l < kind->NumLinks(); ++l) {
    const int o = tree.RotationCoordinate(l);
    if (o >= 0 && !IsRotationAt(qJ, o))
      sizes << "joint_positions: the rotation of " << LinkLabel(desc, l) << "'s joint is not a "
            << "rotation matrix";
  }
  if (!sizes.str().empty()) {
    Fail(error, who + sizes.str());
    return nullptr;
  }
  kind->initial_ = kind->StateAt(qJ, u);
  // Every tangent dof must move mass: M positive definite.
  KinematicFrames frames;
  tree.Evaluate(qJ, &frames);
  Eigen::MatrixXd M;
  Eigen::VectorXd p;
  kind->GeneralizedMomentum(frames, kind->initial_.x, Eigen::VectorXd::Zero(6 * kind->NumLinks()),
                            &M, &p);
  for (int k = 0; k < m; ++k) {
    if (!(M(k, k) > 1e-12 * std::max(M.diagonal().maxCoeff(), 1e-300))) {
      int owner = 0;
      while (owner + 1 < kind->NumLinks() && tree.TangentOffset(owner + 1) <= k) ++owner;
      Fail(error, who + LinkLabel(desc, owner) + ": its joint moves no mass (every link it " +
                      "carries has mass 0)");
      return nullptr;
    }
  }
  kind->name = desc.name;
  return kind;
}

KindState ArticulatedKind::StateAt(const Eigen::VectorXd& qJ, const Eigen::VectorXd& u) const {
  KindState s;
  s.x.setZero(NumDofs());
  s.x.head(tree_.NumCoordinates()) = qJ;
  KinematicFrames frames;
  WriteLinks(&s.x, &frames);
  WriteVelocity(s.x, frames, u, &s.v);
  return s;
}

std::unique_ptr<ActorKind> ArticulatedKind::Clone() const {
  return std::unique_ptr<ActorKind>(new ArticulatedKind(*this));
}

std::vector<RigidPose> ArticulatedKind::LinkPoses(const Eigen::VectorXd& q) const {
  KinematicFrames frames;
  tree_.Evaluate(q.head(tree_.NumCoordinates()), &frames);
  return std::move(frames.link);
}

void ArticulatedKind::WriteLinks(Eigen::VectorXd* q, KinematicFrames* frames) const {
  tree_.Evaluate(q->head(tree_.NumCoordinates()), frames);
  for (int l = 0; l < NumLinks(); ++l) {
    const RigidPose& pose = frames->link[l];
    q->segment<3>(LinkOffset(l)) = pose.p + pose.R * links_[l].com;
    Matrix3At(q, LinkOffset(l) + 3) = pose.R;
  }
}

void ArticulatedKind::WriteVelocity(const Eigen::VectorXd& q, const KinematicFrames& frames,
                                    const Eigen::VectorXd& u, Eigen::VectorXd* v) const {
  v->setZero(NumDofs());
  for (int l = 0; l < NumLinks(); ++l) {
    // The joint's own rates: a 1-dof joint's and a free joint's translation are u's entries, a
    // rotation R_rel ← exp([δφ]×) R_rel moves at [u_φ]× R_rel.
    const int o = tree_.CoordinateOffset(l), t = tree_.TangentOffset(l);
    const int r = tree_.RotationCoordinate(l);
    const int before = r >= 0 ? r - o : JointCoordinates(tree_.Joint(l).type);
    v->segment(o, before) = u.segment(t, before);  // the same layout in q and δ up to a rotation
    if (r >= 0) Matrix3At(v, r) = Skew(u.segment<3>(tree_.RotationTangent(l))) * Matrix3At(q, r);
    Eigen::Vector3d dc, w;
    tree_.LinkChartStep(frames, l, q.segment<3>(LinkOffset(l)), u, &dc, &w);
    v->segment<3>(LinkOffset(l)) = dc;
    Matrix3At(v, LinkOffset(l) + 3) = Skew(w) * Matrix3At(q, LinkOffset(l) + 3);
  }
}

void ArticulatedKind::GeneralizedMomentum(const KinematicFrames& frames, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& linkMomenta, Eigen::MatrixXd* M,
                                          Eigen::VectorXd* p) const {
  const int m = NumTangentDofs();
  M->setZero(m, m);
  p->setZero(m);
  Eigen::MatrixXd A;
  for (int l = 0; l < NumLinks(); ++l) {
    const Link& link = links_[l];
    if (!(link.mass > 0.0)) continue;
    const Eigen::Vector3d c = q.segment<3>(LinkOffset(l));
    tree_.LinkChartJacobian(frames, l, c, &A);
    Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
    D.topLeftCorner<3, 3>() = link.mass * Eigen::Matrix3d::Identity();
    D.bottomRightCorner<3, 3>() = WorldInertia(Matrix3At(q, LinkOffset(l) + 3), link.secondMoment);
    M->noalias() += A.transpose() * D * A;
    p->noalias() += A.transpose() * linkMomenta.segment<6>(6 * l);
  }
}

Eigen::VectorXd ArticulatedKind::LinkMomenta(const Eigen::VectorXd& q,
                                             const Eigen::VectorXd& v) const {
  Eigen::VectorXd P = Eigen::VectorXd::Zero(6 * NumLinks());
  for (int l = 0; l < NumLinks(); ++l) {
    const int o = LinkOffset(l);
    P.segment<3>(6 * l) = links_[l].mass * v.segment<3>(o);
    P.segment<3>(6 * l + 3) =
        SpinMomentum(Matrix3At(q, o + 3), Matrix3At(v, o + 3), links_[l].secondMoment);
  }
  return P;
}

Eigen::VectorXd ArticulatedKind::JointVelocities(const KindState& s) const {
  KinematicFrames frames;
  tree_.Evaluate(s.x.head(tree_.NumCoordinates()), &frames);
  Eigen::MatrixXd M;
  Eigen::VectorXd p;
  GeneralizedMomentum(frames, s.x, LinkMomenta(s.x, s.v), &M, &p);
  return M.ldlt().solve(p);
}

double ArticulatedKind::StageEnergy(const KindStageData& stage, const Eigen::VectorXd& q,
                                    int order, PsdProjection projection, Eigen::VectorXd* g,
                                    std::vector<Eigen::Triplet<double>>* H) const {
  ArticulatedScratch& s = stage.scratch.Get<ArticulatedScratch>();
  const int m = NumTangentDofs();
  tree_.Evaluate(q.head(tree_.NumCoordinates()), &s.frames);
  const double w = 1.0 / (stage.dt * stage.dt);
  if (order >= 2) s.hessian.setZero(m, m);
  double value = 0.0;
  for (int l = 0; l < NumLinks(); ++l) {
    const Link& link = links_[l];
    if (!(link.mass > 0.0)) continue;
    const RigidPose& pose = s.frames.link[l];
    const Eigen::Vector3d c = pose.p + pose.R * link.com;
    const int o = LinkOffset(l);
    const RigidInertiaTerm e =
        RigidInertia(link.mass, link.secondMoment, c, pose.R, stage.qHat.segment<3>(o),
                     Matrix3At(stage.qHat, o + 3), order >= 1);
    value += w * e.value - link.mass * stage.gravity.dot(c);
    if (order < 1) continue;
    Vector6 load = w * e.gradient;  // the link's chart gradient (f, τ) [N, N·m]
    load.head<3>() -= link.mass * stage.gravity;
    tree_.LinkChartJacobian(s.frames, l, c, &s.chart);
    g->noalias() += s.chart.transpose() * load;
    if (order < 2) continue;
    Eigen::Matrix<double, 6, 6> He = w * e.hessian;
    if (projection != PsdProjection::None) ProjectChartHessian(projection, &He);
    s.chartHessian.noalias() = He * s.chart;
    s.hessian.noalias() += s.chart.transpose() * s.chartHessian;
    if (projection == PsdProjection::None)
      tree_.AddLinkChartCurvature(s.frames, l, c, load.head<3>(), load.tail<3>(), &s.hessian);
  }
  value += JointTerms(stage, q, order, g, &s.hessian);
  if (order >= 2) {
    for (int j = 0; j < m; ++j)  // every entry: the pattern stays the same from stage to stage
      for (int i = 0; i < m; ++i) H->emplace_back(i, j, s.hessian(i, j));
  }
  return value;
}

namespace {

/// A drive's stage law: a = k_p + k_d/Δt and x_eq (energies/joint_energies.h, DriveEnergy) at time
/// t from the stage start x⁰.
struct DriveLaw {
  double a = 0.0;
  double xEq = 0.0;
};

double TargetVelocity(const JointParams& p, double t) {
  return p.driveTargetVelocity.empty() ? PiecewiseSlope(p.driveTargetPosition, t)
                                       : PiecewiseLinear(p.driveTargetVelocity, t);
}

DriveLaw DriveAt(const JointParams& p, double t, double dt, double x0) {
  DriveLaw law;
  const double kd = p.driveDamping / dt;
  law.a = p.driveStiffness + kd;
  law.xEq = (p.driveStiffness * PiecewiseLinear(p.driveTargetPosition, t) +
             kd * (x0 + dt * TargetVelocity(p, t))) / law.a;
  return law;
}

}  // namespace

double ArticulatedKind::JointTerms(const KindStageData& stage, const Eigen::VectorXd& q, int order,
                                   Eigen::VectorXd* g, Eigen::MatrixXd* H) const {
  double value = 0.0;
  for (int l = 0; l < NumLinks(); ++l) {
    const JointParams& p = links_[l].joint;
    if (!p.Active()) continue;  // (only 1-dof joints have active terms: Build)
    const int o = tree_.CoordinateOffset(l), t = tree_.TangentOffset(l);
    const double x = q[o], x0 = stage.q0[o];
    JointEnergy e = JointLimitEnergy(x, p.lowerLimit, p.upperLimit, p.limitStiffness);
    if (p.damping > 0.0) {
      const double c = p.damping / stage.dt;
      e.value += 0.5 * c * (x - x0) * (x - x0);
      e.d1 += c * (x - x0);
      e.d2 += c;
    }
    if (p.driveStiffness > 0.0 || p.driveDamping > 0.0) {
      const DriveLaw law = DriveAt(p, stage.time, stage.dt, x0);
      const JointEnergy d = DriveEnergy(x, law.xEq, law.a, p.driveForceLimit);
      e.value += d.value;
      e.d1 += d.d1;
      e.d2 += d.d2;
    }
    value += e.value;
    if (order >= 1) (*g)[t] += e.d1;
    if (order >= 2) (*H)(t, t) += e.d2;
  }
  return value;
}

Eigen::VectorXd ArticulatedKind::DriveForces(const KindState& s, double t) const {
  Eigen::VectorXd F = Eigen::VectorXd::Zero(NumTangentDofs());
  Eigen::VectorXd u;
  for (int l = 0; l < NumLinks(); ++l) {
    const JointParams& p = links_[l].joint;
    if (!(p.driveStiffness > 0.0 || p.driveDamping > 0.0)) continue;
    if (u.size() == 0) u = JointVelocities(s);
    const int o = tree_.CoordinateOffset(l), k = tree_.TangentOffset(l);
    const double f = -p.driveStiffness * (s.x[o] - PiecewiseLinear(p.driveTargetPosition, t)) -
                     p.driveDamping * (u[k] - TargetVelocity(p, t));
    F[k] = std::clamp(f, -p.driveForceLimit, p.driveForceLimit);
  }
  return F;
}

void ArticulatedKind::Retract(const Eigen::VectorXd& q, const Eigen::VectorXd& delta,
                              Eigen::VectorXd* out) const {
  thread_local KinematicFrames frames;
  const int nc = tree_.NumCoordinates();
  out->resize(NumDofs());
  tree_.Retract(q.head(nc), delta, out->head(nc));
  WriteLinks(out, &frames);
}

void ArticulatedKind::TangentBetween(const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                                     Eigen::VectorXd* delta) const {
  const int nc = tree_.NumCoordinates();
  tree_.TangentBetween(from.head(nc), to.head(nc), delta);
}

void ArticulatedKind::AddResidualJacobianCorrection(
    const Eigen::VectorXd& /*q*/, const Eigen::VectorXd& residual,
    std::vector<Eigen::Triplet<double>>* J) const {
  for (int l = 0; l < NumLinks(); ++l)
    if (const int t = tree_.RotationTangent(l); t >= 0)
      AppendSpinTrivialization(residual.segment<3>(t), t, J);
}

Eigen::MatrixXd ArticulatedKind::ChartTangentMap(const Eigen::VectorXd& delta) const {
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(delta.size(), delta.size());
  for (int l = 0; l < NumLinks(); ++l)
    if (const int t = tree_.RotationTangent(l); t >= 0)
      T.block<3, 3>(t, t) = LeftJacobianSo3(delta.segment<3>(t));
  return T;
}

double ArticulatedKind::StepLength(const Eigen::VectorXd& q, const Eigen::VectorXd& delta) const {
  thread_local KinematicFrames frames;
  tree_.Evaluate(q.head(tree_.NumCoordinates()), &frames);
  double length = 0.0;
  for (int l = 0; l < NumLinks(); ++l) {
    const Eigen::Vector3d c = frames.link[l].p + frames.link[l].R * links_[l].com;
    Eigen::Vector3d dc, dphi;
    tree_.LinkChartStep(frames, l, c, delta, &dc, &dphi);
    length = std::max({length, dc.lpNorm<Eigen::Infinity>(), dphi.norm() * links_[l].radius});
  }
  return length;
}

void ArticulatedKind::DirkStageSlope(const Eigen::VectorXd& x, const KindState& start, double dt,
                                     KindSlope* out) const {
  KinematicFrames frames;
  tree_.Evaluate(x.head(tree_.NumCoordinates()), &frames);
  const Eigen::VectorXd raw = (x - start.x) / dt;  // the links' stage velocities, not tangent
  // (1) The tangent velocity with the same generalized momentum.
  Eigen::MatrixXd M;
  Eigen::VectorXd p;
  GeneralizedMomentum(frames, x, LinkMomenta(x, raw), &M, &p);
  WriteVelocity(x, frames, M.ldlt().solve(p), &out->slope.x);
  // A 1-dof joint's coordinate keeps its own stage rate (x − x⁰)/Δt_i, as a vector kind's: its
  // damping and drive read the stage's joint velocity from x⁰, and with the projected rate
  // instead (off by O(Δt) where x⁰'s links lie off the tree) a damped arm fell to first order
  // under DIRK22 and SymplecticDIRK22.
  for (int l = 0; l < NumLinks(); ++l) {
    const JointType type = tree_.Joint(l).type;
    if (type == JointType::Revolute || type == JointType::Prismatic)
      out->slope.x[tree_.CoordinateOffset(l)] = raw[tree_.CoordinateOffset(l)];
  }
  out->slope.v = (out->slope.x - start.v) / dt;
  // (3) Each link's force and torque about the world origin at the stage from its tangent slope
  // K = (V − v⁰)/Δt_i: m K_c and c × m K_c + axial(K_R J Qᵀ − Q J K_Rᵀ), the rates of its world
  // momenta. The projection (1) keeps every component of the generalized momentum, so these sum,
  // over the links, to the stage's external force and torque as the raw slopes' do.
  out->extra.setZero(6 * NumLinks());
  for (int l = 0; l < NumLinks(); ++l) {
    const int o = LinkOffset(l);
    const Eigen::Vector3d f = links_[l].mass * out->slope.v.segment<3>(o);
    const Eigen::Matrix3d KR = Matrix3At(out->slope.v, o + 3);
    const Eigen::Matrix3d Q = Matrix3At(x, o + 3);
    const Eigen::Matrix3d& J = links_[l].secondMoment;
    out->extra.segment<3>(6 * l) = f;
    out->extra.segment<3>(6 * l + 3) = Eigen::Vector3d(x.segment<3>(o)).cross(f) +
                                       Axial(KR * J * Q.transpose() - Q * J * KR.transpose());
  }
}

void ArticulatedKind::DirkStepEnd(const KindState& start, const Eigen::VectorXd& lastStage,
                                  bool stifflyAccurate, const std::vector<KindSlope>& slopes,
                                  const std::vector<double>& hb, KindState* end) const {
  // (3) Each link's linear momentum and angular momentum about the world origin, integrated.
  Eigen::VectorXd momenta = LinkMomenta(start.x, start.v);
  for (int l = 0; l < NumLinks(); ++l)
    momenta.segment<3>(6 * l + 3) +=
        Eigen::Vector3d(start.x.segment<3>(LinkOffset(l))).cross(momenta.segment<3>(6 * l));
  for (size_t i = 0; i < slopes.size(); ++i) momenta += hb[i] * slopes[i].extra;
  // (2) The end configuration on the tree.
  const int nc = tree_.NumCoordinates();
  if (stifflyAccurate) {
    end->x.head(nc) = lastStage.head(nc);
  } else {
    for (int l = 0; l < NumLinks(); ++l)
      if (const int r = tree_.RotationCoordinate(l); r >= 0)
        Matrix3At(&end->x, r) = NearestRotation(Matrix3At(end->x, r));
  }
  KinematicFrames frames;
  WriteLinks(&end->x, &frames);
  // The end velocity carrying the integrated momenta (each link's spin about its end centre).
  for (int l = 0; l < NumLinks(); ++l)
    momenta.segment<3>(6 * l + 3) -=
        Eigen::Vector3d(end->x.segment<3>(LinkOffset(l))).cross(momenta.segment<3>(6 * l));
  Eigen::MatrixXd M;
  Eigen::VectorXd p;
  GeneralizedMomentum(frames, end->x, momenta, &M, &p);
  WriteVelocity(end->x, frames, M.ldlt().solve(p), &end->v);
}

void ArticulatedKind::PredictStage(const KindState& current, const KindState* previous,
                                   double hPrevious, double tau,
                                   const Eigen::VectorXd& /*stageStart*/, double /*stageDt*/,
                                   Eigen::VectorXd* q) const {
  Eigen::VectorXd u = JointVelocities(current);
  if (previous && hPrevious > 0.0) u += 0.5 * tau * (u - JointVelocities(*previous)) / hPrevious;
  Retract(current.x, tau * u, q);
}

double ArticulatedKind::ForceChange(const KindState& current, const KindState& previous,
                                    double hPrevious, const KindState& before,
                                    double hBefore) const {
  double change = 0.0;
  for (int l = 0; l < NumLinks(); ++l) {
    const int o = LinkOffset(l);
    const Eigen::VectorXd a = (current.v.segment<12>(o) - previous.v.segment<12>(o)) / hPrevious -
                              (previous.v.segment<12>(o) - before.v.segment<12>(o)) / hBefore;
    change = std::max(change, a.head<3>().norm() + links_[l].radius * a.tail<9>().norm());
  }
  return change;
}

double ArticulatedKind::KineticEnergy(const KindState& s) const {
  double T = 0.0;
  for (int l = 0; l < NumLinks(); ++l) {
    const int o = LinkOffset(l);
    const Eigen::Matrix3d Rdot = Matrix3At(s.v, o + 3);
    T += 0.5 * links_[l].mass * s.v.segment<3>(o).squaredNorm() +
         0.5 * (Rdot * links_[l].secondMoment * Rdot.transpose()).trace();
  }
  return T;
}

double ArticulatedKind::GravityEnergy(const KindState& s, const Eigen::Vector3d& gravity) const {
  double U = 0.0;
  for (int l = 0; l < NumLinks(); ++l)
    U -= links_[l].mass * gravity.dot(s.x.segment<3>(LinkOffset(l)));
  return U;
}

Eigen::Vector3d ArticulatedKind::LinearMomentum(const KindState& s) const {
  Eigen::Vector3d P = Eigen::Vector3d::Zero();
  for (int l = 0; l < NumLinks(); ++l) P += links_[l].mass * s.v.segment<3>(LinkOffset(l));
  return P;
}

Eigen::Vector3d ArticulatedKind::AngularMomentum(const KindState& s) const {
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (int l = 0; l < NumLinks(); ++l) {
    const int o = LinkOffset(l);
    const Eigen::Vector3d c = s.x.segment<3>(o);
    L += links_[l].mass * c.cross(Eigen::Vector3d(s.v.segment<3>(o))) +
         SpinMomentum(Matrix3At(s.x, o + 3), Matrix3At(s.v, o + 3), links_[l].secondMoment);
  }
  return L;
}

Eigen::Vector3d ArticulatedKind::CenterOfMass(const KindState& s) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double mass = 0.0;
  for (int l = 0; l < NumLinks(); ++l) {
    sum += links_[l].mass * s.x.segment<3>(LinkOffset(l));
    mass += links_[l].mass;
  }
  return mass > 0.0 ? Eigen::Vector3d(sum / mass) : Eigen::Vector3d::Zero();
}

Eigen::Vector3d ArticulatedKind::CenterOfMassVelocity(const KindState& s) const {
  double mass = 0.0;
  for (const Link& link : links_) mass += link.mass;
  return mass > 0.0 ? Eigen::Vector3d(LinearMomentum(s) / mass) : Eigen::Vector3d::Zero();
}

int ArticulatedKind::FindLink(const std::string& name) const {
  for (int l = 0; l < NumLinks(); ++l)
    if (links_[l].name == name) return l;
  return -1;
}

std::string ArticulatedKind::SetLinkMass(int l, double mass) {
  if (!(std::isfinite(mass) && mass > 0.0)) return "mass: must be > 0";
  if (!(links_[l].mass > 0.0)) return "mass: the link is massless (its inertia is not given)";
  links_[l].secondMoment *= mass / links_[l].mass;
  links_[l].mass = mass;
  return {};
}

std::string ArticulatedKind::SetLinkJointParams(int l, const JointParams& params) {
  if (std::string m = superdex::Validate(params, "joint_params."); !m.empty()) return m;
  const JointType type = tree_.Joint(l).type;
  if (params.Active() && type != JointType::Revolute && type != JointType::Prismatic)
    return std::string("joint_params: limits, damping and drives are for Revolute and Prismatic "
                       "joints, the joint is ") + ToString(type);
  links_[l].joint = params;
  return {};
}

void ArticulatedKind::CarriedFrameJacobians(const Eigen::VectorXd& q,
                                            const std::vector<FramePoint>& points,
                                            std::vector<Eigen::MatrixXd>* A) const {
  KinematicFrames frames;
  tree_.Evaluate(q.head(tree_.NumCoordinates()), &frames);
  A->resize(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    tree_.LinkChartJacobian(frames, points[i].frame, points[i].point, &(*A)[i]);
}

void ArticulatedKind::AddCarriedFrameCurvature(
    const Eigen::VectorXd& q, const std::vector<FramePoint>& points,
    const std::vector<Eigen::Matrix<double, 6, 1>>& loads, Eigen::MatrixXd* H) const {
  KinematicFrames frames;
  tree_.Evaluate(q.head(tree_.NumCoordinates()), &frames);
  for (size_t i = 0; i < points.size(); ++i)
    tree_.AddLinkChartCurvature(frames, points[i].frame, points[i].point, loads[i].head<3>(),
                                loads[i].tail<3>(), H);
}

Aabb ArticulatedKind::Bounds(const Eigen::VectorXd& q) const {
  Aabb b;
  for (int l = 0; l < NumLinks(); ++l) {
    const Eigen::Vector3d c = q.segment<3>(LinkOffset(l));
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(2.0 * links_[l].radius);
    b.Extend(c - r);
    b.Extend(c + r);
  }
  return b;
}

}  // namespace superdex
