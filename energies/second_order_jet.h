// A second-order jet: a value with its gradient and Hessian in N variables, carried through
// +, −, ×, ÷ and √ exactly (forward-mode automatic differentiation to second order). For energy
// terms whose closed-form Hessian is long (a shell's mid-edge bending), written once as a template
// on the scalar type and evaluated on doubles or on jets. Fixed size: no heap allocation.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace superdex {

template <int N>
struct Jet2 {
  double v = 0.0;
  Eigen::Matrix<double, N, 1> g = Eigen::Matrix<double, N, 1>::Zero();
  Eigen::Matrix<double, N, N> h = Eigen::Matrix<double, N, N>::Zero();

  Jet2() = default;
  explicit Jet2(double value) : v(value) {}
  /// Variable i of the N, at `value`.
  static Jet2 Variable(double value, int i) {
    Jet2 j(value);
    j.g[i] = 1.0;
    return j;
  }
};

template <int N>
Jet2<N> operator+(const Jet2<N>& a, const Jet2<N>& b) {
  Jet2<N> r;
  r.v = a.v + b.v;
  r.g = a.g + b.g;
  r.h = a.h + b.h;
  return r;
}

template <int N>
Jet2<N> operator-(const Jet2<N>& a, const Jet2<N>& b) {
  Jet2<N> r;
  r.v = a.v - b.v;
  r.g = a.g - b.g;
  r.h = a.h - b.h;
  return r;
}

template <int N>
Jet2<N> operator*(double s, const Jet2<N>& a) {
  Jet2<N> r;
  r.v = s * a.v;
  r.g = s * a.g;
  r.h = s * a.h;
  return r;
}

template <int N>
Jet2<N> operator*(const Jet2<N>& a, const Jet2<N>& b) {
  Jet2<N> r;
  r.v = a.v * b.v;
  r.g = a.v * b.g + b.v * a.g;
  r.h = a.v * b.h + b.v * a.h + a.g * b.g.transpose() + b.g * a.g.transpose();
  return r;
}

/// 1/a.
template <int N>
Jet2<N> Inverse(const Jet2<N>& a) {
  const double i = 1.0 / a.v;
  Jet2<N> r;
  r.v = i;
  r.g = -i * i * a.g;
  r.h = -i * i * a.h + 2.0 * i * i * i * a.g * a.g.transpose();
  return r;
}

template <int N>
Jet2<N> Sqrt(const Jet2<N>& a) {
  const double s = std::sqrt(a.v);
  Jet2<N> r;
  r.v = s;
  r.g = a.g / (2.0 * s);
  r.h = a.h / (2.0 * s) - a.g * a.g.transpose() / (4.0 * s * s * s);
  return r;
}

inline double Inverse(double a) { return 1.0 / a; }
inline double Sqrt(double a) { return std::sqrt(a); }

}  // namespace superdex
