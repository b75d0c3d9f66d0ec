// PointCloud pairs (spec: "Double-Integral Generalization"): colliding actor A's surface samples
// against collider B's points X_B, each a moving sphere of radius L_B about its current place
// x_B that follows only x_B's translation (no rotation, stretch or twist of its own):
//
//   φ_XB(x) = ‖x − x_B‖ − L_B                                                          [m]
//   Π_A,B  ≈ L_B^(−d) Σ_j w_B,j Σ_q w_q (k/2) h_ε,δ(−φ_XB,j(x_A,q))²                     [J]
//
// (d the dimension of Ω_B, w_B,j [m^d] the outer quadrature's weights, w_q [m²] A's surface
// weights). Each sphere is a frame of the one contact assembler (core/contact/kind_contact.h):
// a FrameSide translating with x_B (its Jacobian the point's map on B's node blocks), an exact
// sphere field of radius L_B, and A's samples weighted by w_q w_B,j / L_B^d. So each sphere's own
// normal traction is the load of its friction and damping, and the factor w_B,j / L_B^d
// multiplies its complete conservative and dissipative contribution before the sum over j, as
// the spec asks; every dissipation mode is the assembler's (ExplicitNormals an exact potential,
// the current-geometry modes residuals; the spec recommends the current load,
// implicitNormalForceForDissipation, for frictional point clouds). The normal force of a pair
// (sample, sphere) is central (along x_A − x_B), so it conserves angular momentum exactly; the
// friction pair is not (its moment arm is O(L_B)).
//
// Broad phase: A's samples in a spatial hash (geometry/spatial_hash.h, sized by B's
// spatialHashLoadFactor) with cells of the pair's reach L_B + δ; each sphere asks the cells
// within its reach, grown by how far the samples and the point moved since x_n where the mode
// reads x_n's geometry. Self-contact (A = B, selfContact): a pair (X_A, X_B) counts only when
// ‖X_B − X_A‖ >= r L_B in the reference configuration.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/contact/contact_stencil.h"
#include "core/contact/dissipation_setup.h"
#include "core/contact/kind_contact.h"
#include "core/model/actor_kind.h"
#include "geometry/spatial_hash.h"

namespace superdex {

/// A colliding kind's samples for its point-cloud pairs at one evaluation: every sample as a
/// PairSample (y, y_n, y⁰, map, stage offsets), its reference place X_A, and the hash over y.
struct CloudSamples {
  std::vector<PairSample> samples;
  std::vector<Eigen::Vector3d> reference;  ///< X_A per sample (self-contact; empty without)
  std::vector<Eigen::Vector3d> places;     ///< y per sample (the hash's points)
  SpatialHash hash;
  double motion = 0.0;  ///< max ‖y_n − y‖ over the samples [m]
  /// Forms them for kind A at q (x_n: qLast, x⁰: q0; either may be null), the hash with cells of
  /// side `cell` [m] and `loadFactor`; the reference places when `reference`.
  void Form(const ActorKind& A, const Eigen::VectorXd& q, const Eigen::VectorXd* qLast,
            const Eigen::VectorXd* q0, const std::vector<int>& stageDof, double cell,
            double loadFactor, bool reference);
};

/// A PointCloud kind's points at one evaluation: each as a sample (y, map, dofs, weight w_B), its
/// place at x_n and x⁰, its reference place X_B; and the sphere field of radius L_B.
struct CloudPoints {
  std::vector<KindSample> now;
  std::vector<Eigen::Vector3d> last, start, reference;
  RigidCollider sphere;
  double radius = 0.0;        ///< L_B [m]
  double weightScale = 0.0;   ///< L_B^(−d)
  bool hasLast = false, hasStart = false;
  /// Forms them for PointCloud kind B at q (qLast, q0 may be null); the reference places when
  /// `reference`.
  void Form(const ActorKind& B, const Eigen::VectorXd& q, const Eigen::VectorXd* qLast,
            const Eigen::VectorXd* q0, bool reference);
  /// Point j's sphere as a translating frame, its blocks at the stage offsets `stageDof`.
  void Side(int j, const std::vector<int>& stageDof, FrameSide* side) const;
};

/// How many points one piece of a point-cloud pair evaluates (the pair is cut into pieces that
/// run in parallel and are reduced in order).
constexpr int kCloudPiece = 256;

/// The terms of B's points begin .. end−1 on A's samples, appended to *out (order, dissipation
/// and records as EvaluateSamplesOnFrame takes them). `self`: A and B are one actor (the
/// exclusion ‖X_B − X_A‖ >= r L_B applies, r = `exclusionRatio`). `stageDofB`: B's stage offsets.
void EvaluateCloudPoints(const CloudSamples& A, const CloudPoints& B,
                         const std::vector<int>& stageDofB, bool self, double exclusionRatio,
                         int begin, int end, const PenaltyParams& penalty,
                         const DissipationSetup* dissipation, int order, PairStencils* out,
                         std::vector<ContactSampleRecord>* records = nullptr);

}  // namespace superdex
