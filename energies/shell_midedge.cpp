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

// II = [II00, II01, II10, II11] (not yet symmetrized) at the points q[0..2], p[0..2], a free
// edge i's mid-edge normal m_i = n + φ_i t_i (t_i the unit in-plane normal of the edge).
template <typename T, typename P>
std::array<T, 4> SecondForm(const V3<T> (&q)[3], const V3<T> (&p)[3], const MidedgeTriangle& t,
                            const std::array<P, 3>& phi) {
  const V3<T> n = Normalized(Cross(Sub(q[1], q[0]), Sub(q[2], q[0])));
  V3<T> m[3];
  for (int i = 0; i < 3; ++i) {
    if (t.edge[i] == MidedgeEdge::Boundary) {
      const V3<T> ti = Normalized(Cross(Sub(q[(i + 2) % 3], q[(i + 1) % 3]), n));
      m[i] = {n[0] + phi[i] * ti[0], n[1] + phi[i] * ti[1], n[2] + phi[i] * ti[2]};
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

// W at x and the free edges' angles φ (scalar types T, P; P is T or double).
template <typename T, typename P>
T Energy(const std::array<T, 18>& x, const std::array<P, 3>& phi, const MidedgeTriangle& t,
         const LameParameters& lame, double thickness) {
  V3<T> q[3], p[3];
  Points(x, q, p);
  const std::array<T, 4> II = SecondForm(q, p, t, phi);
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
  const std::array<double, 4> II = SecondForm(q, p, t, std::array<double, 3>{0.0, 0.0, 0.0});
  Eigen::Matrix2d m;
  m << II[0], 0.5 * (II[1] + II[2]), 0.5 * (II[1] + II[2]), II[3];
  return m;
}

namespace {

// The free edges' φ* minimizing W at x (W is quadratic in φ: b and A from a jet in φ alone,
// φ* = −A⁻¹ b on the free edges; zero elsewhere), and how many there are.
int FreeEdgeAngles(const std::array<double, 18>& xs, const MidedgeTriangle& t,
                   const LameParameters& lame, double thickness, std::array<double, 3>* phi) {
  *phi = {0.0, 0.0, 0.0};
  int free[3], k = 0;
  for (int i = 0; i < 3; ++i)
    if (t.edge[i] == MidedgeEdge::Boundary) free[k++] = i;
  if (k == 0) return 0;
  using J = Jet2<3>;
  std::array<J, 3> ph;
  std::array<J, 18> xj;
  for (int i = 0; i < 3; ++i) ph[i] = J::Variable(0.0, i);
  for (int i = 0; i < 18; ++i) xj[i] = J(xs[i]);
  const J W = Energy(xj, ph, t, lame, thickness);
  Eigen::MatrixXd A(k, k);
  Eigen::VectorXd b(k);
  for (int a = 0; a < k; ++a) {
    b[a] = W.g[free[a]];
    for (int c = 0; c < k; ++c) A(a, c) = W.h(free[a], free[c]);
  }
  const Eigen::VectorXd f = -A.ldlt().solve(b);
  for (int a = 0; a < k; ++a) (*phi)[free[a]] = f[a];
  return k;
}

}  // namespace

double MidedgeBendingEnergy(const MidedgeStencil& x, const MidedgeTriangle& t,
                            const LameParameters& lame, double thickness, int order, bool project,
                            Eigen::Matrix<double, 18, 1>* g, Eigen::Matrix<double, 18, 18>* H) {
  std::array<double, 18> xd;
  for (int i = 0; i < 18; ++i) xd[i] = x[i];
  std::array<double, 3> phi;
  const int freeEdges = FreeEdgeAngles(xd, t, lame, thickness, &phi);
  if (order < 1) return Energy(xd, phi, t, lame, thickness);
  if (freeEdges == 0) {
    using J = Jet2<18>;
    std::array<J, 18> xs;
    for (int i = 0; i < 18; ++i) xs[i] = J::Variable(x[i], i);
    const J W = Energy(xs, phi, t, lame, thickness);
    *g += W.g;
    if (order >= 2) {
      StencilMatrix h = 0.5 * (W.h + W.h.transpose());
      if (project) ProjectToPsd(&h, false);
      *H += h;
    }
    return W.v;
  }
  // With free edges, W*(x) = min_φ W(x, φ): at φ* its gradient is ∂W/∂x (∂W/∂φ = 0 there), its
  // Hessian the Schur complement W_xx − W_xφ W_φφ⁻¹ W_φx (jets over x and the three φ).
  using J = Jet2<21>;
  std::array<J, 18> xs;
  std::array<J, 3> ph;
  for (int i = 0; i < 18; ++i) xs[i] = J::Variable(x[i], i);
  for (int i = 0; i < 3; ++i) ph[i] = J::Variable(phi[i], 18 + i);
  const J W = Energy(xs, ph, t, lame, thickness);
  *g += W.g.head<18>();
  if (order >= 2) {
    int free[3], k = 0;
    for (int i = 0; i < 3; ++i)
      if (t.edge[i] == MidedgeEdge::Boundary) free[k++] = i;
    Eigen::MatrixXd App(k, k), Axp(18, k);
    for (int a = 0; a < k; ++a) {
      Axp.col(a) = W.h.block<18, 1>(0, 18 + free[a]);
      for (int c = 0; c < k; ++c) App(a, c) = W.h(18 + free[a], 18 + free[c]);
    }
    StencilMatrix h = W.h.topLeftCorner<18, 18>() - Axp * App.ldlt().solve(Axp.transpose());
    h = 0.5 * (h + h.transpose()).eval();
    if (project) ProjectToPsd(&h, false);
    *H += h;
  }
  return W.v;
}

}  // namespace superdex
