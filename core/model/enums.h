// The spec's enums that core owns, with their names as strings (scene files, Python, messages).
#pragma once

#include <string>

#include "geometry/quadrature.h"
#include "optim/field_table.h"

namespace superdex {

/// How an actor supplies distance fields (spec: "Collider Representations").
/// Capsule is superdex's, beyond the spec's values: the analytic field of a capsule shape.
enum class ColliderType { Auto, None, Sphere, Box, Plane, Mesh, Sdf, PointCloud, Capsule };

/// Time integrators (the reference engine's family). Every stage is an incremental-potential
/// minimization in q with v = (q − q⁰)/Δt_i.
enum class IntegrationMethod {
  BackwardEuler,
  BDF2,
  BDF3,
  DIRK22,
  DIRK23,
  DIRK33,
  SymplecticDIRK12,
  SymplecticDIRK22,
};

/// Whether actor-pair filtering applies to nested actors too (spec: "Contact Filtering").
enum class IncludeNestedActors { No, Yes };

/// How a rigid colliding actor integrates its normal penalty over its surface (superdex's own
/// option, not a spec parameter). Quadrature: the spec's rule (boundaryElementType) on the
/// sampled surface. ExactSphere (sphere shapes): the exact integral over the sphere against a
/// plane's, a box face's or a sphere's field (energies/sphere_penalty.h), the rule elsewhere; the
/// dissipation on a quadrature of the active cap where the mode allows it
/// (core/contact/sphere_cap.h), else on the rule's samples.
enum class SurfaceIntegral { Quadrature, ExactSphere };

/// The name tables (optim/field_table.h: ToString, Parse, AllNames work through them).
EnumNames<ColliderType> NamesOf(ColliderType);
EnumNames<IntegrationMethod> NamesOf(IntegrationMethod);
EnumNames<ActorBoundaryElementType> NamesOf(ActorBoundaryElementType);
EnumNames<IncludeNestedActors> NamesOf(IncludeNestedActors);
EnumNames<SurfaceIntegral> NamesOf(SurfaceIntegral);

}  // namespace superdex
