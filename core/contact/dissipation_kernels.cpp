#include "core/contact/dissipation_kernels.h"

#include <cmath>

namespace superdex {
namespace dissipation_kernels {

CurrentModeLinearization LinearizeCurrentModeGradient(const Eigen::Vector3d& Y,
                                                      const Eigen::Vector3d& NA,
                                                      const SdfSample& field,
                                                      const Eigen::Vector3d& Yn,
                                                      const Eigen::Vector3d& Y0,
                                                      const DissipationSetup& s) {
  const Eigen::Vector3d& G = field.gradient;
  const Eigen::Matrix3d& HPhi = field.hessian;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const DissipationCoefficients& c = s.coefficients;
  // Planes and the flat regions of boxes have ∇²Φ = 0: the terms it multiplies are skipped (exact
  // zeros, so the result is the same to the bit), and so is ∂D/∂N when N does not move either.
  const bool flat = HPhi.isZero(0.0);

  // Normal load λ_n = −W'(φ_load) [Pa] and its derivative in Y.
  const bool implicitLoad = s.mode == DissipationMode::ImplicitLoad;
  const double phiLoad = implicitLoad ? field.value : field.value + G.dot(Yn - Y);
  const Eigen::Vector3d dPhiLoad =
      implicitLoad ? G : (flat ? Eigen::Vector3d::Zero() : Eigen::Vector3d(HPhi * (Yn - Y)));
  const PenaltyDensity pd = NormalPenaltyDensity(phiLoad, s.penalty);
  const double lambda = -pd.dW;
  const Eigen::Vector3d dLambda = -pd.d2W * dPhiLoad;

  // Alignment factor a(G·N_A) [-].
  const double factor = AlignmentFactor(G.dot(NA), s);
  Eigen::Vector3d dFactorY = Eigen::Vector3d::Zero(), dFactorN = Eigen::Vector3d::Zero();
  if (s.fadeFriction && s.maxAlignment > -1.0) {
    if (!flat) dFactorY = -(HPhi * NA) / (s.maxAlignment + 1.0);
    dFactorN = -G / (s.maxAlignment + 1.0);
  }
  const double L = factor * lambda;
  // Zero on a flat field in the reconstructed mode (dλ and ∂a/∂Y both vanish with ∇²Φ).
  const bool loadMoves = implicitLoad || !flat;
  const Eigen::Vector3d dLY =
      loadMoves ? Eigen::Vector3d(factor * dLambda + lambda * dFactorY) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d dLN = lambda * dFactorN;

  // Split direction N and its derivatives.
  const Eigen::Vector3d N = SplitDirection(G, NA, s);
  const Eigen::Matrix3d P = I - N * N.transpose();
  Eigen::Matrix3d dNY = Eigen::Matrix3d::Zero(), dNN = Eigen::Matrix3d::Zero();
  const bool normalMoves = !s.frictionWithColliderNormal || !flat;
  if (!s.frictionWithColliderNormal)
    dNN = -P / NA.norm();
  else if (!flat)
    dNY = P * HPhi / G.norm();

  // D = ∂R/∂V at unit load, and its derivatives in V and N.
  const Eigen::Vector3d V = (Y - Y0) / s.dt;
  const double Vn = V.dot(N);
  const Eigen::Vector3d Vt = V - Vn * N;
  const double speed = Vt.norm();
  const FrictionRamp f = EvaluateFrictionRamp(speed, c.vf);
  const double inPlane = c.mu * f.slope + c.ct;
  const Eigen::Vector3d D = inPlane * Vt + c.cn * Vn * N;
  // At = inPlane I + μ (ρ'' − ρ'/V_t) t tᵀ (t = V_t/|V_t|), and At P = inPlane P + μ (ρ'' − ρ'/V_t)
  // t tᵀ as t ⊥ N (P At P = At P).
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  if (speed > 0.0) t = Vt / speed;
  const Eigen::Matrix3d slipCurvature = (c.mu * f.curvature) * t * t.transpose();
  const Eigen::Matrix3d DV = inPlane * P + slipCurvature + c.cn * N * N.transpose();

  CurrentModeLinearization out;
  out.g = L * D;
  if (!normalMoves) {  // dNY = dNN = 0
    out.GY = (L / s.dt) * DV;
    if (loadMoves) out.GY.noalias() += D * dLY.transpose();
    out.GN = D * dLN.transpose();
    return out;
  }
  const Eigen::Matrix3d At = inPlane * I + slipCurvature;
  const Eigen::Matrix3d DN = (c.cn * I - At) * (N * V.transpose() + Vn * I);
  out.GY = D * dLY.transpose() + L * (DV / s.dt + DN * dNY);
  out.GN = D * dLN.transpose() + L * DN * dNN;
  return out;
}

}  // namespace dissipation_kernels
}  // namespace superdex
