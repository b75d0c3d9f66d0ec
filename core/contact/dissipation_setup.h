// The data one ordered pair's dissipation needs besides the two actors (spec: "Stage-Discrete
// Dissipation"): the dissipation mode's setup and a rigid body's stage-start pose. Seen by the
// per-pair evaluations and the scalar-generic kernels (core/contact/dissipation_kernels.h) alike.
#pragma once

#include <Eigen/Core>

#include "core/contact/slip_tape.h"
#include "core/model/eval_params.h"
#include "core/model/rigid_body.h"
#include "energies/contact_dissipation.h"
#include "energies/normal_penalty.h"

namespace superdex {

/// A body's stage-start pose x⁰ = (p⁰, R⁰) with (R⁰)⁻¹, and its last actual pose x_n.
struct RigidStageStart {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d Rinv = Eigen::Matrix3d::Identity();  ///< R⁻¹: a collider frame's (Y⁰ = R⁻¹(y⁰ − p))
  RigidPose last;  ///< x_n: the geometry reference (a rotation)
};

/// Everything one ordered pair needs besides the bodies.
struct DissipationSetup {
  DissipationMode mode = DissipationMode::ReconstructedLoad;
  bool fadeFriction = true;                ///< alignment factor a = (m − s)/(m + 1)
  double dt = 0.0;                         ///< stage step Δt_i [s]
  PenaltyParams penalty;                   ///< for λ_n = −W'(φ)
  DissipationCoefficients coefficients;
  double maxAlignment = 0.0;               ///< m, the collider's
  bool frictionWithColliderNormal = true;  ///< split on N_B (true) or −N_A (false)
  /// ExplicitNormals Hessians with the Coulomb term's isotropic majorizer
  /// (DissipationHessian::Isotropic) instead of the exact curvature: the contact pipeline sets
  /// it when the caller asks for projected Hessians (the globalization phase of projected Newton).
  bool isotropicFrictionHessian = false;
  /// Sensitivities: the samples' recorded slips, recorded or linearized about (core/contact/slip_tape.h).
  PairSlipUse slips;
  /// The kind of EvaluateDissipation Hessian a sample needs (`wanted`: a Hessian at all).
  DissipationHessian HessianKind(bool wanted) const {
    if (!wanted) return DissipationHessian::None;
    return isotropicFrictionHessian ? DissipationHessian::Isotropic : DissipationHessian::Exact;
  }
};

}  // namespace superdex
