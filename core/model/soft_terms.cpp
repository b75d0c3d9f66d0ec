#include "core/model/soft_terms.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "energies/psd_projection.h"

namespace superdex {
namespace {

// Below this many tets the element loop runs serially.
constexpr int kParallelTets = 2000;

void Gather(const Eigen::VectorXd& x, const Eigen::Vector4i& T, Eigen::Vector3d xs[4]) {
  for (int a = 0; a < 4; ++a) xs[a] = x.segment<3>(3 * T[a]);
}

}  // namespace

void PrepareSoftDamping(const SoftBodyModel& m, SoftStageTarget* target) {
  target->dampingStiffness.clear();
  if (!(m.material.stiffnessDamping > 0.0)) return;
  const int nt = m.rest.NumTets();
  target->dampingStiffness.resize(nt);
  auto one = [&](int t) {
    Eigen::Vector3d xs[4];
    Gather(target->xHat, m.rest.tets[t], xs);
    TetElasticTerm term;
    EvaluateStableNeoHookean(m.elements[t], m.lame, xs, 2, true, &term);
    target->dampingStiffness[t] = term.hessian;
  };
  if (nt >= kParallelTets) {
    tbb::parallel_for(0, nt, one);
  } else {
    for (int t = 0; t < nt; ++t) one(t);
  }
}

double EvaluateSoftStageTerms(const SoftBodyModel& m, const SoftStageTarget& target, double dt,
                              const Eigen::Vector3d& gravity, const Eigen::VectorXd& x, int order,
                              PsdProjection projection, Eigen::VectorXd* gradient,
                              std::vector<Eigen::Triplet<double>>* triplets,
                              SoftTermScratch* scratch, double* minDetF) {
  const int n = m.NumNodes();
  const double w = 1.0 / (dt * dt);
  double value = 0.0;
  // Inertia and gravity on the free nodes.
  for (int a = 0; a < n; ++a) {
    if (m.freeIndex[a] < 0) continue;
    const double ma = m.nodeMass[a];
    const Eigen::Vector3d xa = x.segment<3>(3 * a);
    const Eigen::Vector3d dx = xa - target.xHat.segment<3>(3 * a);
    value += 0.5 * w * ma * dx.squaredNorm() - ma * gravity.dot(xa);
    if (order == 0) continue;
    const int o = 3 * a;
    gradient->segment<3>(o) += w * ma * dx - ma * gravity;
    if (order < 2) continue;
    for (int k = 0; k < 3; ++k) triplets->emplace_back(o + k, o + k, w * ma);
  }

  // Elements: elastic energy and stiffness damping.
  const int nt = m.rest.NumTets();
  scratch->terms.resize(nt);
  const double beta = m.material.stiffnessDamping;
  const bool damping = beta > 0.0 && !target.dampingStiffness.empty();
  const double c = damping ? beta / dt : 0.0;
  auto one = [&](int t) {
    const Eigen::Vector4i& T = m.rest.tets[t];
    Eigen::Vector3d xs[4];
    Gather(x, T, xs);
    TetElasticTerm& term = scratch->terms[t];
    EvaluateStableNeoHookean(m.elements[t], m.lame, xs, order,
                             order >= 2 && projection == PsdProjection::Clamp, &term);
    if (order >= 2 && projection == PsdProjection::Abs) {
      StencilMatrix H = term.hessian;
      ProjectToPsd(&H, true);
      term.hessian = H;
    }
    if (damping) {
      Eigen::Matrix<double, 12, 1> d;
      for (int a = 0; a < 4; ++a)
        d.segment<3>(3 * a) = xs[a] - target.x0.segment<3>(3 * T[a]);
      const Eigen::Matrix<double, 12, 12>& K = target.dampingStiffness[t];
      const Eigen::Matrix<double, 12, 1> Kd = K * d;
      term.value += 0.5 * c * d.dot(Kd);
      if (order >= 1) term.gradient += c * Kd;
      if (order >= 2) term.hessian += c * K;
    }
  };
  if (nt >= kParallelTets) {
    tbb::parallel_for(0, nt, one);
  } else {
    for (int t = 0; t < nt; ++t) one(t);
  }
  double minDet = INFINITY;
  for (int t = 0; t < nt; ++t) {
    const TetElasticTerm& term = scratch->terms[t];
    value += term.value;
    minDet = std::min(minDet, term.detF);
    if (order == 0) continue;
    const Eigen::Vector4i& T = m.rest.tets[t];
    int offs[4];
    for (int a = 0; a < 4; ++a) {
      offs[a] = m.freeIndex[T[a]] < 0 ? -1 : 3 * T[a];
      if (offs[a] >= 0) gradient->segment<3>(offs[a]) += term.gradient.segment<3>(3 * a);
    }
    if (order < 2) continue;
    for (int a = 0; a < 4; ++a) {
      if (offs[a] < 0) continue;
      for (int b = 0; b < 4; ++b) {
        if (offs[b] < 0) continue;
        for (int j = 0; j < 3; ++j)
          for (int i = 0; i < 3; ++i)
            triplets->emplace_back(offs[a] + i, offs[b] + j, term.hessian(3 * a + i, 3 * b + j));
      }
    }
  }
  if (minDetF) *minDetF = minDet;
  return value;
}

}  // namespace superdex
