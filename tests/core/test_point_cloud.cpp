// The PointCloud collider (core/contact/point_cloud.h, spec: "Double-Integral Generalization") on
// shells.
//
// Expectations:
//   - the pair potential of two tilted sheets equals an independent double sum over A's surface
//     quadrature and B's points of L_B⁻² w_q w_B (k/2) h(−φ)² with φ = |y − x_B| − L_B, both
//     ordered pairs, to round-off (relative 1e-12), with B's points the nodes (lumped areas) or a
//     triangle rule's points; a U-folded sheet's self-contact the same double sum restricted to
//     pairs with |X_B − X_A| >= r L_B in the reference configuration, and a flat sheet's none;
//   - a small sheet at gap g = 0.8 L_B over a large one: the discrete potential converges to the
//     continuum's area × L_B⁻² ∫ W(√(g² + ρ²) − L_B) 2πρ dρ as B's mesh refines (by more than
//     1.5× per halving of the spacing, within 0.1 % at h = L_B/4: measured 16 %, 8.4 %, 0.005 %
//     at L_B = 1 cm; a compact smooth integrand sampled on a grid converges fast once the grid
//     resolves it), and the same at half the L_B with the mesh scaled with it;
//   - the normal (penalty) forces of the pair are central: total force and torque vanish to
//     round-off (1e-12 of the forces' magnitude); the friction forces' torque defect is at most
//     (L_B + δ) × Σ|f| and halves with L_B (ratio 0.5 ± 0.1, the geometry scaled with L_B);
//   - a stage of two sheets in point-cloud contact, and of a folded sheet in self-contact,
//     moving with friction and damping: gradient and exact Hessian against central
//     differences (explicit normals), residual Jacobian (reconstructed and current load);
//   - bad input: r <= 1, L_B <= 0, a collider type a shell has no field for, PointCloud asked of
//     a rigid or a soft actor: one clear error each.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "core/contact/contact_pipeline.h"
#include "core/model/shell_kind.h"
#include "core/model/soft_kind.h"
#include "core/scene.h"
#include "energies/penalty_ramp.h"
#include "geometry/quadrature.h"
#include "stage_derivative_recorder.h"

namespace superdex {
namespace {

constexpr double kL = 0.01;  // L_B [m]

ShellActorDesc Sheet(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, const Eigen::Vector2i& cells,
                     const Eigen::Vector3d& position, double tilt = 0.0) {
  ShellActorDesc d;
  d.name = "sheet";
  d.mesh = std::make_shared<TriangleMesh>(MakeRectangleMesh(lo, hi, cells));
  d.meshSource = "rectangle";
  d.position = position;
  d.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d(1, 2, 0).normalized()));
  d.contact.penaltyCoefficient = 1e6;
  d.pointCloud.radius = kL;
  return d;
}

std::unique_ptr<ShellKind> BuildOrFail(const ShellActorDesc& d) {
  Error e;
  std::unique_ptr<ShellKind> k = ShellKind::Build(d, &e);
  INFO(e.message);
  REQUIRE(k);
  return k;
}

// A sheet of n × 2n cells over [0, w] × [0, 2w] folded about y = w into a U: the upper half lies
// at height `gap` over the lower one (the fold a half circle of diameter `gap`).
std::shared_ptr<TriangleMesh> FoldedSheet(double w, int n, double gap) {
  auto mesh = std::make_shared<TriangleMesh>(
      MakeRectangleMesh(Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 2 * w), Eigen::Vector2i(n, 2 * n)));
  const double r = 0.5 * gap, arc = M_PI * r;
  for (Eigen::Vector3d& v : mesh->vertices) {
    const double s = v.y() - (w - 0.5 * arc);  // arc length past the fold's start
    if (s <= 0) continue;
    if (s < arc) {
      const double a = s / r;
      v = Eigen::Vector3d(v.x(), w - 0.5 * arc + r * std::sin(a), r - r * std::cos(a));
    } else {
      v = Eigen::Vector3d(v.x(), w - 0.5 * arc - (s - arc), gap);
    }
  }
  return mesh;
}

// The pipeline's contact terms over kinds at their initial states (all dofs free, offsets in
// kind order); dissipation with x_n = x⁰ = x − the kinds' velocities × dt when `context`.
struct Evaluation {
  std::vector<const ActorKind*> kinds;
  std::vector<Eigen::VectorXd> q, qLast;
  std::vector<std::vector<int>> stageDof;
  ContactFilter filter;
  ContactPipeline pipeline;
  int dofs = 0;
  explicit Evaluation(std::vector<const ActorKind*> k) : kinds(std::move(k)) {
    std::vector<int> actor;
    for (size_t a = 0; a < kinds.size(); ++a) {
      const KindState s = kinds[a]->InitialState();
      q.push_back(s.x);
      qLast.push_back(s.x - 1e-3 * s.v);
      std::vector<int> dof(s.x.size());
      for (auto& d : dof) d = dofs++;
      stageDof.push_back(dof);
      filter.AddActor("default", -1);
      actor.push_back(static_cast<int>(a));
    }
    pipeline.Configure(&filter, &kinds, actor);
  }
  double Run(int order, Eigen::VectorXd* g, Eigen::VectorXd* residual,
             const DissipationContext* context, ContactStats* stats) {
    KindView view;
    view.q = &q;
    view.qLast = &qLast;
    view.q0 = &qLast;
    view.stageDof = &stageDof;
    if (g) g->setZero(dofs);
    if (residual) residual->setZero(dofs);
    return pipeline.Evaluate(order, PsdProjection::None, g, nullptr, nullptr, stats, context,
                             residual, &view);
  }
};

// The independent double sum: A's samples (its faces' P1Q3 rule, weights A_t w_q) on B's points
// (its nodes with lumped areas Σ A_t / 3, or its faces' `rule` points), each pair's
// L_B⁻² w_q w_B (k/2) h(−φ)², skipping pairs closer than rL_B in the reference when `self`.
double DirectDoubleSum(const ShellKind& A, const Eigen::VectorXd& xA, const ShellKind& B,
                       const Eigen::VectorXd& xB, const std::optional<ActorBoundaryElementType>& rule,
                       bool self, double r, const PenaltyParams& p) {
  struct Point {
    Eigen::Vector3d x, X;
    double w;
  };
  auto node = [](const Eigen::VectorXd& x, int i) { return Eigen::Vector3d(x.segment<3>(3 * i)); };
  auto area = [&](const Eigen::VectorXd& X, const Eigen::Vector3i& F) {
    return 0.5 * (node(X, F[1]) - node(X, F[0])).cross(node(X, F[2]) - node(X, F[0])).norm();
  };
  auto facePoints = [&](const ShellKind& K, const Eigen::VectorXd& x, ActorBoundaryElementType t) {
    const Eigen::VectorXd& X = *K.ReferenceConfiguration();
    const TriangleQuadratureRule& q = GetTriangleQuadratureRule(t);
    std::vector<Point> out;
    for (const Eigen::Vector3i& F : K.Model().faces)
      for (size_t i = 0; i < q.weights.size(); ++i) {
        Point pt{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), area(X, F) * q.weights[i]};
        for (int c = 0; c < 3; ++c) {
          pt.x += q.barycentric[i][c] * node(x, F[c]);
          pt.X += q.barycentric[i][c] * node(X, F[c]);
        }
        out.push_back(pt);
      }
    return out;
  };
  const std::vector<Point> samples = facePoints(A, xA, ActorBoundaryElementType::P1Q3);
  std::vector<Point> points;
  if (rule) {
    points = facePoints(B, xB, *rule);
  } else {
    const Eigen::VectorXd& X = *B.ReferenceConfiguration();
    points.resize(X.size() / 3);
    for (size_t i = 0; i < points.size(); ++i) points[i] = {node(xB, i), node(X, i), 0.0};
    for (const Eigen::Vector3i& F : B.Model().faces)
      for (int c = 0; c < 3; ++c) points[F[c]].w += area(X, F) / 3.0;
  }
  double sum = 0.0;
  for (const Point& s : samples)
    for (const Point& b : points) {
      if (self && (s.X - b.X).norm() < r * kL) continue;
      const double phi = (s.x - b.x).norm() - kL;
      const double h = PenaltyRampSpecForm(phi, p.eps, p.delta);
      sum += s.w * b.w / (kL * kL) * 0.5 * p.k * h * h;
    }
  return sum;
}

}  // namespace

TEST_CASE("point cloud: the pair potential is the double sum of the spheres' potentials",
          "[core][point_cloud]") {
  const bool quadraturePoints = GENERATE(false, true);
  ShellActorDesc a = Sheet({0, 0}, {0.03, 0.03}, {2, 2}, Eigen::Vector3d::Zero());
  ShellActorDesc b = Sheet({0.005, 0.005}, {0.035, 0.035}, {3, 3}, Eigen::Vector3d(0, 0, 0.0085), 0.08);
  std::optional<ActorBoundaryElementType> rule;
  if (quadraturePoints) rule = ActorBoundaryElementType::P1Q6;
  a.pointCloud.colliderTriangleElementType = b.pointCloud.colliderTriangleElementType = rule;
  const auto A = BuildOrFail(a), B = BuildOrFail(b);
  Evaluation ev({A.get(), B.get()});
  ContactStats stats;
  const double value = ev.Run(0, nullptr, nullptr, nullptr, &stats);
  PenaltyParams p;
  p.k = 1e6;
  const double expected = DirectDoubleSum(*A, ev.q[0], *B, ev.q[1], rule, false, 0, p) +
                          DirectDoubleSum(*B, ev.q[1], *A, ev.q[0], rule, false, 0, p);
  INFO("pipeline " << value << " J, direct " << expected << " J, active " << stats.activeSamples);
  CHECK(stats.activeSamples > 10);
  CHECK(expected > 0.0);
  CHECK(std::abs(value - expected) <= 1e-12 * expected);
}

TEST_CASE("point cloud: self-contact counts the pairs apart in the reference configuration",
          "[core][point_cloud]") {
  const double r = GENERATE(1.5, 3.0);
  ShellActorDesc flat = Sheet({0, 0}, {0.03, 0.06}, {6, 12}, Eigen::Vector3d::Zero());
  flat.pointCloud.selfContact = true;
  flat.pointCloud.selfContactExclusionRatio = r;
  const auto F = BuildOrFail(flat);
  Evaluation flatEv({F.get()});
  ContactStats stats;
  CHECK(flatEv.Run(0, nullptr, nullptr, nullptr, &stats) == 0.0);  // nothing within r L_B
  CHECK(stats.activeSamples == 0);

  // The flat sheet folded into a U (its reference stays flat).
  const std::shared_ptr<TriangleMesh> U = FoldedSheet(0.03, 6, 0.008);
  for (int i = 0; i < U->NumVertices(); ++i) flatEv.q[0].segment<3>(3 * i) = U->vertices[i];
  const double value = flatEv.Run(0, nullptr, nullptr, nullptr, &stats);
  PenaltyParams p;
  p.k = 1e6;
  const double expected =
      DirectDoubleSum(*F, flatEv.q[0], *F, flatEv.q[0], std::nullopt, true, r, p);
  INFO("r " << r << ": pipeline " << value << " J, direct " << expected << " J");
  CHECK(expected > 0.0);
  CHECK(std::abs(value - expected) <= 1e-12 * expected);
  // Without self-contact the folded sheet has no pair.
  flat.pointCloud.selfContact = false;
  const auto V = BuildOrFail(flat);
  Evaluation off({V.get()});
  off.q = flatEv.q;
  CHECK(off.Run(0, nullptr, nullptr, nullptr, &stats) == 0.0);
}

}  // namespace superdex

namespace superdex {
namespace {

// The continuum potential of a point on a plane of points at distance g, per unit area of the
// colliding surface: L⁻² ∫ W(√(g² + ρ²) − L) 2πρ dρ (Simpson's rule, 20000 intervals) [J/m²].
double PlaneOfSpheres(double g, double L, const PenaltyParams& p) {
  const double rhoMax = std::sqrt(std::pow(L + p.delta, 2) - g * g);
  const int n = 20000;
  auto f = [&](double rho) {
    const double h = PenaltyRampSpecForm(std::sqrt(g * g + rho * rho) - L, p.eps, p.delta);
    return 0.5 * p.k * h * h * 2.0 * M_PI * rho;
  };
  double sum = f(0.0) + f(rhoMax);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(rhoMax * i / n);
  return sum * rhoMax / (3.0 * n) / (L * L);
}

// A sheet of side 4L (cells of L) colliding on a sheet of side 12L with `cells` cells a side at
// height 0.8 L above it (the reverse direction filtered out): the pair potential [J].
double SmallOnLarge(double L, int cells) {
  ShellActorDesc a = Sheet({-2 * L, -2 * L}, {2 * L, 2 * L}, {4, 4}, Eigen::Vector3d::Zero());
  ShellActorDesc b = Sheet({-6 * L, -6 * L}, {6 * L, 6 * L}, {cells, cells},
                           Eigen::Vector3d(0, 0, 0.8 * L));
  a.pointCloud.radius = b.pointCloud.radius = L;
  b.name = "large";
  const auto A = BuildOrFail(a), B = BuildOrFail(b);
  Evaluation ev({A.get(), B.get()});
  ev.filter.EnableActors(1, 0, false, false);  // only A's samples on B's spheres
  ContactStats stats;
  return ev.Run(0, nullptr, nullptr, nullptr, &stats);
}

}  // namespace

TEST_CASE("point cloud: the potential converges to the continuum's as B's points refine",
          "[core][point_cloud]") {
  PenaltyParams p;
  p.k = 1e6;
  for (double L : {0.01, 0.005}) {
    const double exact = 16 * L * L * PlaneOfSpheres(0.8 * L, L, p);
    std::vector<double> error;
    for (int cells : {12, 24, 48}) error.push_back(std::abs(SmallOnLarge(L, cells) / exact - 1.0));
    INFO("L_B " << L << ": relative errors " << error[0] << ", " << error[1] << ", " << error[2]
                << " at h = L_B, L_B/2, L_B/4");
    CHECK(error[2] < 1e-3);
    CHECK(error[1] < error[0] / 1.5);
    CHECK(error[2] < error[1] / 1.5);
  }
}

TEST_CASE("point cloud: normal forces are central, the friction torque defect is O(L_B)",
          "[core][point_cloud]") {
  std::vector<double> arm;
  for (double L : {0.01, 0.005}) {
    ShellActorDesc a = Sheet({-3 * L, -3 * L}, {3 * L, 3 * L}, {6, 6}, Eigen::Vector3d::Zero());
    ShellActorDesc b = Sheet({-2 * L, -2 * L}, {2 * L, 2 * L}, {4, 4}, Eigen::Vector3d(0, 0, 0.8 * L));
    a.pointCloud.radius = b.pointCloud.radius = L;
    a.linearVelocity = Eigen::Vector3d(0.3, 0.1, 0.0);
    const auto A = BuildOrFail(a), B = BuildOrFail(b);
    Evaluation ev({A.get(), B.get()});
    DissipationContext context;
    context.dt = 1e-3;
    context.mode = DissipationMode::ImplicitLoad;  // the spec's recommendation for point clouds
    Eigen::VectorXd g, r;
    ContactStats stats;
    ev.Run(1, &g, &r, &context, &stats);
    REQUIRE(stats.dissipativeSamples > 0);
    // Force and torque (about the origin) of the nodal forces f_a at x_a.
    auto resultant = [&](const Eigen::VectorXd& f, Eigen::Vector3d* force, Eigen::Vector3d* torque,
                         double* scale) {
      force->setZero();
      torque->setZero();
      *scale = 0.0;
      for (size_t k = 0; k < ev.q.size(); ++k)
        for (int i = 0; 3 * i < ev.q[k].size(); ++i) {
          const Eigen::Vector3d x = ev.q[k].segment<3>(3 * i), fi = f.segment<3>(ev.stageDof[k][3 * i]);
          *force += fi;
          *torque += x.cross(fi);
          *scale += fi.norm() * (1.0 + x.norm());
        }
    };
    Eigen::Vector3d F, T;
    double scale;
    resultant(g, &F, &T, &scale);
    INFO("L_B " << L << ": normal force " << F.transpose() << ", torque " << T.transpose());
    CHECK(F.norm() <= 1e-12 * scale);
    CHECK(T.norm() <= 1e-12 * scale);
    resultant(r, &F, &T, &scale);
    CHECK(F.norm() <= 1e-12 * scale);  // friction pairs are equal and opposite
    // B's share of the friction, and the defect's moment arm |T| / |F_B|.
    Eigen::Vector3d FB = Eigen::Vector3d::Zero();
    for (int i = 0; 3 * i < ev.q[1].size(); ++i) FB += r.segment<3>(ev.stageDof[1][3 * i]);
    arm.push_back(T.norm() / FB.norm());
    INFO("friction on B " << FB.transpose() << " N, torque defect " << T.norm() << " N m");
    CHECK(arm.back() <= L + 0.001);
    CHECK(arm.back() > 0.0);
  }
  INFO("moment arms " << arm[0] << ", " << arm[1] << " m");
  CHECK(std::abs(arm[1] / arm[0] - 0.5) < 0.1);
}

TEST_CASE("point cloud: the stage's derivatives with two sheets and with a folded one",
          "[core][point_cloud][gradient]") {
  const int mode = GENERATE(0, 1, 2);  // explicit normals, reconstructed load, current load
  const bool self = GENERATE(false, true);
  SceneSettings settings;
  settings.eval.explicitNormals = mode == 0;
  settings.eval.implicitNormalForceForDissipation = mode == 2;
  Scene scene(settings);
  Error e;
  auto withFriction = [](ShellActorDesc d) {
    d.contact.viscousFrictionCoefficient = 1e3;
    d.contact.normalViscousDampingCoefficient = 0.3;
    d.pointCloud.selfContact = true;
    return d;
  };
  int dofs = 0;
  if (self) {  // a flat sheet folded into a U, its halves sliding over each other
    ShellActorDesc d = withFriction(Sheet({0, 0}, {0.03, 0.06}, {3, 6}, Eigen::Vector3d::Zero()));
    d.pointCloud.radius = 0.006;
    const ActorHandle h = scene.AddActor(BuildOrFail(d), &e);
    REQUIRE(h.IsValid());
    KindState s = scene.KindStateOf(h);
    const std::shared_ptr<TriangleMesh> U = FoldedSheet(0.03, 3, 0.005);
    for (int i = 0; i < U->NumVertices(); ++i) {
      s.x.segment<3>(3 * i) = U->vertices[i];
      s.v.segment<3>(3 * i) = Eigen::Vector3d(0.2 * (U->vertices[i].z() > 0.004), 0.05, -0.05);
    }
    REQUIRE(scene.SetKindState(h, s, &e));
    dofs = static_cast<int>(s.x.size());
  } else {
    ShellActorDesc a = withFriction(Sheet({-0.02, -0.02}, {0.02, 0.02}, {3, 3}, Eigen::Vector3d::Zero()));
    ShellActorDesc b = withFriction(
        Sheet({-0.015, -0.015}, {0.015, 0.015}, {2, 2}, Eigen::Vector3d(0, 0, 0.0085), 0.08));
    a.linearVelocity = Eigen::Vector3d(0.2, 0.1, 0.0);
    b.name = "upper";
    b.linearVelocity = Eigen::Vector3d(-0.1, 0.2, -0.1);
    REQUIRE(scene.AddActor(BuildOrFail(a), &e).IsValid());
    REQUIRE(scene.AddActor(BuildOrFail(b), &e).IsValid());
    dofs = 3 * 16 + 3 * 9;
  }
  test::StageDerivativeRecorder rec;
  rec.residualStep = 1e-8;
  StepReport r;
  REQUIRE(scene.Step(1e-3, &r, &e, &rec));
  REQUIRE(rec.checked);
  INFO("mode " << mode << (self ? ", folded sheet" : ", two sheets") << ", active "
               << rec.active);
  CHECK(rec.dofs == dofs);
  rec.CheckAccuracy(mode == 0);
}

TEST_CASE("point cloud: bad parameters and kinds are refused with the field and the rule",
          "[core][point_cloud]") {
  Error e;
  ShellActorDesc d = Sheet({0, 0}, {0.03, 0.03}, {2, 2}, Eigen::Vector3d::Zero());
  d.pointCloud.selfContactExclusionRatio = 1.0;
  CHECK_FALSE(ShellKind::Build(d, &e));
  CHECK(e.message == "point_cloud.self_contact_exclusion_ratio: must be > 1, got 1");
  d = Sheet({0, 0}, {0.03, 0.03}, {2, 2}, Eigen::Vector3d::Zero());
  d.pointCloud.radius = 0.0;
  CHECK_FALSE(ShellKind::Build(d, &e));
  CHECK(e.message == "point_cloud.radius: must be > 0, got 0");
  d = Sheet({0, 0}, {0.03, 0.03}, {2, 2}, Eigen::Vector3d::Zero());
  d.colliderType = ColliderType::Sdf;
  CHECK_FALSE(ShellKind::Build(d, &e));
  CHECK(e.message == "collider_type: Sdf is not available for shell actors (expected Auto, None "
                     "or PointCloud: a shell has no distance field of its own)");
  Scene scene;
  RigidActorDesc rigid;
  rigid.name = "ball";
  rigid.colliderType = ColliderType::PointCloud;
  CHECK_FALSE(scene.AddRigidActor(rigid, &e).IsValid());
  INFO(e.message);
  CHECK(e.message.find("collider_type: PointCloud is not available for rigid bodies") !=
        std::string::npos);
  SoftActorDesc soft;
  soft.name = "block";
  soft.mesh = std::make_shared<TetMesh>(MakeTetBox(Eigen::Vector3d::Constant(0.05), {1, 1, 1}));
  soft.colliderType = ColliderType::PointCloud;
  CHECK_FALSE(SoftKind::Build(soft, &e));
  CHECK(e.message == "collider_type: PointCloud is not available for soft actors (expected None, "
                     "Sdf or Auto)");
}

}  // namespace superdex
