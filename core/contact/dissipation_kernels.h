// Kernels shared by the rigid and soft contact dissipation: scalar-generic (double or Ceres jet)
// helpers for the alignment factor and the split direction, so that the residual-mode Jacobians
// are differentiated automatically from the same formulas the residuals use. Include only from
// core/ .cpp files (it pulls in ceres/jet.h).
#pragma once

#include <ceres/jet.h>

#include <Eigen/Core>

#include "core/contact/dissipation_setup.h"
#include "energies/contact_dissipation.h"
#include "energies/normal_penalty.h"
#include "energies/stencil.h"
#include "geometry/analytic_sdf.h"

namespace superdex {
namespace dissipation_kernels {

inline double ValueOf(double x) { return x; }
template <int N>
inline double ValueOf(const ceres::Jet<double, N>& x) {
  return x.a;
}

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Mat3 = Eigen::Matrix<T, 3, 3>;

template <typename T>
Mat3<T> SkewT(const Vec3<T>& v) {
  Mat3<T> S;
  S << T(0.0), -v.z(), v.y(), v.z(), T(0.0), -v.x(), -v.y(), v.x(), T(0.0);
  return S;
}

/// The dissipative alignment factor a = (m − s)/(m + 1) when fading is on and m > −1, else 1
/// (spec: "Normal/Tangential Split"), for doubles and jets alike.
template <typename T>
T AlignmentFactor(const T& s, const DissipationSetup& setup) {
  if (!setup.fadeFriction || !(setup.maxAlignment > -1.0)) return T(1.0);
  return (T(setup.maxAlignment) - s) / (setup.maxAlignment + 1.0);
}

/// The unit split direction: N_B = G_B/|G_B| by default, −N_A/|N_A| with
/// frictionWithColliderNormal = false.
template <typename T>
Vec3<T> SplitDirection(const Vec3<T>& G, const Vec3<T>& NA, const DissipationSetup& setup) {
  using std::sqrt;
  return setup.frictionWithColliderNormal ? Vec3<T>(G / sqrt(G.squaredNorm()))
                                          : Vec3<T>(-NA / sqrt(NA.squaredNorm()));
}

/// ∂R/∂V of one sample in a current-geometry mode (ReconstructedLoad or ImplicitLoad), as a
/// function of the current pullback Y (and the colliding normal N_A in collider coordinates), for
/// doubles and jets. The field is expanded to first order about the sample's evaluation point Ȳ
/// (exact value and first derivatives there): φ = Φ(Ȳ) + ∇Φ·(Y − Ȳ), G = ∇Φ + ∇²Φ (Y − Ȳ).
/// Load φ_load = φ (ImplicitLoad) or φ + G·(Y_n − Y) (ReconstructedLoad), λ_n = −W'(φ_load) (to
/// first order about its value), the alignment factor and split direction from G and N_A, and
/// V = (Y − Y⁰)/Δt_i.
template <typename T>
Vec3<T> CurrentModeDissipationGradient(const Vec3<T>& Y, const Vec3<T>& NA,
                                       const Eigen::Vector3d& Ybar, const SdfSample& field,
                                       const Eigen::Vector3d& Yn, const Eigen::Vector3d& Y0,
                                       const DissipationSetup& s) {
  const Vec3<T> dY = Y - Ybar.cast<T>();
  const T phi = T(field.value) + field.gradient.cast<T>().dot(dY);
  const Vec3<T> G = field.gradient.cast<T>() + field.hessian.cast<T>() * dY;
  const T phiLoad =
      s.mode == DissipationMode::ImplicitLoad ? phi : T(phi + G.dot(Yn.cast<T>() - Y));
  const double pl = ValueOf(phiLoad);
  const PenaltyDensity pd = NormalPenaltyDensity(pl, s.penalty);
  const T lambda = T(-pd.dW) - pd.d2W * (phiLoad - pl);
  const T factor = AlignmentFactor<T>(G.dot(NA), s);
  const Vec3<T> N = SplitDirection<T>(G, NA, s);
  const Vec3<T> V = (Y - Y0.cast<T>()) / s.dt;
  return DissipationGradient(T(factor * lambda), N, V, s.coefficients,
                             [](const T& v) { return ValueOf(v); });
}

/// The current-mode kernel g = ∂R/∂V at the sample's evaluation point Y (with N_A) and its
/// derivatives G_Y = ∂g/∂Y [Pa/m], G_N = ∂g/∂N_A [Pa]; callers chain them to their stencils.
struct CurrentModeLinearization {
  Eigen::Vector3d g;
  Eigen::Matrix3d GY, GN;
};

/// Closed form of the linearization (dissipation_kernels.cpp). With g = L D(N, V), L = a λ_n:
///   G_Y = D ∂L/∂Yᵀ + L (∂D/∂V / Δt + ∂D/∂N ∂N/∂Y),   G_N = D ∂L/∂N_Aᵀ + L ∂D/∂N ∂N/∂N_A,
///   ∂D/∂V = (μ ρ'/V_t + c_t) P + μ (ρ'' − ρ'/V_t) t tᵀ + c_n N Nᵀ,
///   ∂D/∂N = (c_n I − A_t)(N Vᵀ + V_n I),  A_t = (μ ρ'/V_t + c_t) I + μ (ρ'' − ρ'/V_t) t tᵀ,
///   ∂λ_n/∂Y = −W''(φ_load) ∂φ_load/∂Y,  ∂φ_load/∂Y = ∇Φ (ImplicitLoad) or ∇²Φ (Y_n − Y)
///   (ReconstructedLoad), ∂a/∂Y = −∇²Φ N_A/(m + 1), ∂a/∂N_A = −∇Φ/(m + 1) (fading),
///   ∂N/∂Y = (I − N Nᵀ) ∇²Φ/|∇Φ| (N = ∇Φ/|∇Φ|) or ∂N/∂N_A = −(I − N Nᵀ)/|N_A| (N = −N_A/|N_A|).
/// Equal to LinearizeCurrentModeGradientByJets to round-off (tests/core/test_dissipation_kernels).
CurrentModeLinearization LinearizeCurrentModeGradient(const Eigen::Vector3d& Y,
                                                      const Eigen::Vector3d& NA,
                                                      const SdfSample& field,
                                                      const Eigen::Vector3d& Yn,
                                                      const Eigen::Vector3d& Y0,
                                                      const DissipationSetup& s);

/// The same linearization by forward-mode AD of CurrentModeDissipationGradient in its six
/// arguments (Y, N_A): the reference the closed form is tested against (about three times its
/// cost per sample).
inline CurrentModeLinearization LinearizeCurrentModeGradientByJets(
    const Eigen::Vector3d& Y, const Eigen::Vector3d& NA, const SdfSample& field,
    const Eigen::Vector3d& Yn, const Eigen::Vector3d& Y0, const DissipationSetup& s) {
  using Jet = ceres::Jet<double, 6>;
  Vec3<Jet> Yj, Nj;
  for (int k = 0; k < 3; ++k) {
    Yj[k] = Jet(Y[k], k);
    Nj[k] = Jet(NA[k], 3 + k);
  }
  const Vec3<Jet> g = CurrentModeDissipationGradient<Jet>(Yj, Nj, Y, field, Yn, Y0, s);
  CurrentModeLinearization out;
  for (int i = 0; i < 3; ++i) {
    out.g[i] = g[i].a;
    for (int k = 0; k < 3; ++k) {
      out.GY(i, k) = g[i].v[k];
      out.GN(i, k) = g[i].v[3 + k];
    }
  }
  return out;
}

/// Adds w ∂r/∂δ of `sample.Residual(δ, r)` (N stencil dofs) at δ = 0 into *jacobian, by
/// forward-mode automatic differentiation.
template <int N, typename Sample>
void AddResidualJacobian(const Sample& sample, double w, StencilMatrix* jacobian) {
  using Jet = ceres::Jet<double, N>;
  Jet delta[N], out[N];
  for (int i = 0; i < N; ++i) delta[i] = Jet(0.0, i);
  sample.Residual(delta, out);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) (*jacobian)(i, j) += w * out[i].v[j];
}

}  // namespace dissipation_kernels
}  // namespace superdex
