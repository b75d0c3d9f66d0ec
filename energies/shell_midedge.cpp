#include "energies/shell_midedge.h"

#include <array>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "energies/second_order_jet.h"
#include "energies/psd_projection.h"

namespace superdex {
namespace {

template <typename T>
using V3 = std::array<T, 3>;

template <typename T>
V3<T> Sub(const V3<T>& a, const V3<T>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

template <typename T>
V3<T> Add(const V3<T>& a, const V3<T>& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}

template <typename T>
V3<T> Cross(const V3<T>& a, const V3<T>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

template <typename T>
T Dot(const V3<T>& a, const V3<T>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

template <typename T>
V3<T> Normalized(const V3<T>& a) {
  const T inv = Inverse(Sqrt(Dot(a, a)));
  return {inv * a[0], inv * a[1], inv * a[2]};
}

// II = [II00, II01, II10, II11] (not yet symmetrized) at the points q[0..2], p[0..2].
template <typename T>
std::array<T, 4> SecondForm(const V3<T> (&q)[3], const V3<T> (&p)[3], const MidedgeTriangle& t) {
  const V3<T> n = Normalized(Cross(Sub(q[1], q[0]), Sub(q[2], q[0])));
  V3<T> m[3];
  for (int i = 0; i < 3; ++i) {
    if (t.edge[i] == MidedgeEdge::Boundary) {
      m[i] = n;
      continue;
    }
    if (t.edge[i] == MidedgeEdge::Held) {
      m[i] = {T(t.held[i].x()), T(t.held[i].y()), T(t.held[i].z())};
      continue;
    }
    const V3<T>& a = q[(i + 1) % 3];
    const V3<T>& b = q[(i + 2) % 3];
    const V3<T> ni = Normalized(Cross(Sub(a, b), Sub(p[i], b)));
    m[i] = Normalized(Add(n, ni));
  }
  const V3<T> ru = Sub(q[1], q[0]), rv = Sub(q[2], q[0]);
  const V3<T> du = Sub(m[1], m[0]), dv = Sub(m[2], m[0]);
  return {2.0 * Dot(ru, du), 2.0 * Dot(ru, dv), 2.0 * Dot(rv, du), 2.0 * Dot(rv, dv)};
}

template <typename T>
void Points(const std::array<T, 18>& x, V3<T> (&q)[3], V3<T> (&p)[3]) {
  for (int k = 0; k < 3; ++k) {
    q[k] = {x[3 * k], x[3 * k + 1], x[3 * k + 2]};
    p[k] = {x[9 + 3 * k], x[9 + 3 * k + 1], x[9 + 3 * k + 2]};
  }
}

// W at x (scalar type T).
template <typename T>
T Energy(const std::array<T, 18>& x, const MidedgeTriangle& t, const LameParameters& lame,
         double thickness) {
  V3<T> q[3], p[3];
  Points(x, q, p);
  const std::array<T, 4> II = SecondForm(q, p, t);
  const T d00 = II[0] - T(t.IIbar(0, 0));
  const T d01 = 0.5 * (II[1] + II[2]) - T(t.IIbar(0, 1));
  const T d11 = II[3] - T(t.IIbar(1, 1));
  const Eigen::Matrix2d& A = t.abarInv;
  // M = ā⁻¹ ΔII.
  const T m00 = A(0, 0) * d00 + A(0, 1) * d01;
  const T m01 = A(0, 0) * d01 + A(0, 1) * d11;
  const T m10 = A(1, 0) * d00 + A(1, 1) * d01;
  const T m11 = A(1, 0) * d01 + A(1, 1) * d11;
  const T tr = m00 + m11;
  const T tr2 = m00 * m00 + 2.0 * (m01 * m10) + m11 * m11;
  const double c = thickness * thickness * thickness / 12.0 * t.restArea;
  return c * (lame.mu * tr2 + 0.5 * lame.lambda * (tr * tr));
}

}  // namespace

MidedgeTriangle MakeMidedgeTriangle(const MidedgeStencil& X, const bool hasNeighbour[3],
                                    const bool held[3]) {
  MidedgeTriangle t;
  const Eigen::Vector3d e1 = X.segment<3>(3) - X.segment<3>(0);
  const Eigen::Vector3d e2 = X.segment<3>(6) - X.segment<3>(0);
  const Eigen::Vector3d n = e1.cross(e2).normalized();
  for (int i = 0; i < 3; ++i) {
    t.edge[i] = hasNeighbour[i] ? MidedgeEdge::Shared : MidedgeEdge::Boundary;
    t.held[i] = n;
    if (!held || !held[i]) continue;
    if (hasNeighbour[i]) {  // the rest mid-edge normal
      const Eigen::Vector3d a = X.segment<3>(3 * ((i + 1) % 3)), b = X.segment<3>(3 * ((i + 2) % 3));
      t.held[i] = (n + (a - b).cross(X.segment<3>(9 + 3 * i) - b).normalized()).normalized();
    }
    t.edge[i] = MidedgeEdge::Held;
  }
  Eigen::Matrix2d abar;
  abar << e1.dot(e1), e1.dot(e2), e1.dot(e2), e2.dot(e2);
  t.restArea = 0.5 * e1.cross(e2).norm();
  t.abarInv = abar.inverse();
  t.IIbar = MidedgeSecondFundamentalForm(X, t);
  return t;
}

Eigen::Matrix2d MidedgeSecondFundamentalForm(const MidedgeStencil& x, const MidedgeTriangle& t) {
  std::array<double, 18> xs;
  for (int i = 0; i < 18; ++i) xs[i] = x[i];
  V3<double> q[3], p[3];
  Points(xs, q, p);
  const std::array<double, 4> II = SecondForm(q, p, t);
  Eigen::Matrix2d m;
  m << II[0], 0.5 * (II[1] + II[2]), 0.5 * (II[1] + II[2]), II[3];
  return m;
}

double MidedgeBendingEnergy(const MidedgeStencil& x, const MidedgeTriangle& t,
                            const LameParameters& lame, double thickness, int order, bool project,
                            Eigen::Matrix<double, 18, 1>* g, Eigen::Matrix<double, 18, 18>* H) {
  if (order < 1) {
    std::array<double, 18> xs;
    for (int i = 0; i < 18; ++i) xs[i] = x[i];
    return Energy(xs, t, lame, thickness);
  }
  using J = Jet2<18>;
  std::array<J, 18> xs;
  for (int i = 0; i < 18; ++i) xs[i] = J::Variable(x[i], i);
  const J W = Energy(xs, t, lame, thickness);
  *g += W.g;
  if (order >= 2) {
    StencilMatrix h = 0.5 * (W.h + W.h.transpose());
    if (project) ProjectToPsd(&h, false);
    *H += h;
  }
  return W.v;
}

}  // namespace superdex
