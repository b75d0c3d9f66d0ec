// The slit annular plate under a line load (Sze, Liu & Lo, "Popular benchmark problems for
// geometric nonlinear analysis of shells", Finite Elements in Analysis and Design 40 (2004)
// 1551–1569, section 3.3): an annulus of radii 6 and 10, thickness 0.03, E = 21e6, ν = 0, cut
// along one radius; one side of the cut clamped, the other loaded by a vertical line force of up
// to 0.8 per unit length. Its large-rotation response (the free side rises past 17, more than
// the plate's width) is the reference's S4R solution on 10 × 80 elements: the vertical
// deflections of the loaded side's inner point A and outer point B,
//   P/Pmax   0.1    0.2    0.5     1.0
//   W_A      4.277  6.725  10.468  13.891
//   W_B      5.876  9.160  13.768  17.528
// Here: mid-edge Kirchhoff–Love bending with the StVK membrane on 8 × 64 quads split in two
// (1024 triangles), the load ramped in 23 quasi-static Backward Euler steps (first 1 %, 2.5 %,
// 5 %, 7.5 %, 10 %, then 5 % more each; the mass and time scaled so that inertia is below 1e-5
// of the plate's stiffness), the clamped side's nodes pinned with their edges' mid-edge normals
// held, the line load lumped on the loaded side's nodes by the trapezoid rule (NodeLoad).
// Asserted: W_A and W_B within 4 % of the reference at full load, every step converged; the
// intermediate levels are printed (measured: see docs/shells.md).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "core/model/shell_kind.h"
#include "core/scene.h"

namespace superdex {

TEST_CASE("shell: the slit annular plate under a line load follows Sze et al.'s curve",
          "[core][shell][slit_plate]") {
  const int nr = 8, nt = 64;
  // Load fractions per step: small first increments (the flat plate rises by ~4 at P/Pmax = 0.1),
  // then 0.05 each; a step of 50 s each.
  std::vector<double> level = {0.01, 0.025, 0.05, 0.075};
  for (double f = 0.1; f < 1.0 + 1e-9; f += 0.05) level.push_back(f);
  const double dt = 50.0;
  ShellActorDesc d;
  d.name = "slit plate";
  d.mesh = std::make_shared<TriangleMesh>(MakeAnnulusMesh(6.0, 10.0, 2.0 * M_PI, Eigen::Vector2i(nr, nt)));
  d.meshSource = "annulus";
  d.material.youngsModulus = 21e6;
  d.material.poissonRatio = 0.0;
  d.material.thickness = 0.03;
  d.material.density = 1e-3;
  d.colliderType = ColliderType::None;
  for (int i = 0; i <= nr; ++i) d.clampedNodes.push_back(i);  // θ = 0
  const double q = 0.8, dr = 4.0 / nr;
  NodeLoad inner, ends;
  for (int i = 0; i <= nr; ++i) (i == 0 || i == nr ? ends : inner).nodes.push_back(i + (nr + 1) * nt);
  inner.force = {{0.0, Eigen::Vector3d::Zero()}};
  ends.force = {{0.0, Eigen::Vector3d::Zero()}};
  for (size_t k = 0; k < level.size(); ++k) {
    inner.force.emplace_back(dt * (k + 1), Eigen::Vector3d(0, 0, level[k] * q * dr));
    ends.force.emplace_back(dt * (k + 1), Eigen::Vector3d(0, 0, 0.5 * level[k] * q * dr));
  }
  d.loads = {inner, ends};
  SceneSettings settings;
  settings.integrator = IntegrationMethod::BackwardEuler;
  settings.gravity.setZero();
  Scene scene(settings);
  Error e;
  std::unique_ptr<ShellKind> kind = ShellKind::Build(d, &e);
  INFO(e.message);
  REQUIRE(kind);
  const ActorHandle a = scene.AddActor(std::move(kind), &e);
  REQUIRE(a.IsValid());
  const int A = (nr + 1) * nt, B = nr + (nr + 1) * nt;
  const double ref[4][3] = {{0.1, 4.277, 5.876}, {0.2, 6.725, 9.160}, {0.5, 10.468, 13.768},
                            {1.0, 13.891, 17.528}};
  int converged = 0, steps = 0, next = 0;
  double WA = 0.0, WB = 0.0;
  int newton = 0;
  for (double f : level) {
    StepReport r;
    REQUIRE(scene.Step(dt, &r, &e));
    ++steps;
    converged += r.status == StageStatus::Converged;
    newton = std::max(newton, r.newtonIterations);
    const Eigen::VectorXd& x = scene.KindStateOf(a).x;
    WA = x[3 * A + 2];
    WB = x[3 * B + 2];
    if (next < 4 && std::abs(f - ref[next][0]) < 1e-9) {
      std::printf("slit plate P/Pmax %.2f: W_A %.3f (ref %.3f, %+.2f %%), W_B %.3f (ref %.3f, %+.2f %%)\n",
                  f, WA, ref[next][1], 100 * (WA / ref[next][1] - 1), WB, ref[next][2],
                  100 * (WB / ref[next][2] - 1));
      ++next;
    }
  }
  std::printf("slit plate: %d of %d steps converged, at most %d Newton iterations\n", converged,
              steps, newton);
  INFO("full load: W_A " << WA << " (13.891), W_B " << WB << " (17.528)");
  CHECK(converged == steps);
  CHECK(std::abs(WA / 13.891 - 1.0) < 0.04);
  CHECK(std::abs(WB / 17.528 - 1.0) < 0.04);
}

}  // namespace superdex
