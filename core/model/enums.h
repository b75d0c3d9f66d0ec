// The spec's enums that core owns, with their names as strings (scene files, Python, messages).
#pragma once

#include <string>

#include "geometry/quadrature.h"

namespace superdex {

/// How an actor supplies distance fields (spec: "Collider Representations").
enum class ColliderType { Auto, None, Sphere, Box, Plane, Mesh, Sdf, PointCloud };

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

const char* ToString(ColliderType v);
const char* ToString(IntegrationMethod v);
const char* ToString(ActorBoundaryElementType v);
const char* ToString(IncludeNestedActors v);

/// Parses the exact enum name (e.g. "BDF2", "P1Q3"). Returns false if unknown.
bool Parse(const std::string& s, ColliderType* v);
bool Parse(const std::string& s, IntegrationMethod* v);
bool Parse(const std::string& s, ActorBoundaryElementType* v);

/// "A, B, C": every valid name, for error messages.
std::string AllNames(ColliderType);
std::string AllNames(IntegrationMethod);
std::string AllNames(ActorBoundaryElementType);

}  // namespace superdex
