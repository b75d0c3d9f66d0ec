#include "core/model/enums.h"

namespace superdex {

SUPERDEX_ENUM_NAMES(ColliderType,
    {ColliderType::Auto, "Auto", "by actor and shape: analytic for sphere, box, plane, capsule"},
    {ColliderType::None, "None", "no collider role (the actor may still collide)"},
    {ColliderType::Sphere, "Sphere"},
    {ColliderType::Box, "Box"},
    {ColliderType::Plane, "Plane"},
    {ColliderType::Mesh, "Mesh"},
    {ColliderType::Sdf, "Sdf"},
    {ColliderType::PointCloud, "PointCloud"},
    {ColliderType::Capsule, "Capsule", "analytic capsule field (superdex's; not in the spec)"})

SUPERDEX_ENUM_NAMES(IntegrationMethod,
    {IntegrationMethod::BackwardEuler, "BackwardEuler", "order 1, L-stable"},
    {IntegrationMethod::BDF2, "BDF2", "order 2, A-stable (default)"},
    {IntegrationMethod::BDF3, "BDF3", "order 3"},
    {IntegrationMethod::DIRK22, "DIRK22", "order 2, L-stable"},
    {IntegrationMethod::DIRK23, "DIRK23", "order 3, A-stable"},
    {IntegrationMethod::DIRK33, "DIRK33", "order 3, L-stable"},
    {IntegrationMethod::SymplecticDIRK12, "SymplecticDIRK12", "implicit midpoint"},
    {IntegrationMethod::SymplecticDIRK22, "SymplecticDIRK22", "order 2, symplectic"})

SUPERDEX_ENUM_NAMES(ActorBoundaryElementType,
    {ActorBoundaryElementType::P1Q1, "P1Q1", "1 point, exact for degree 1"},
    {ActorBoundaryElementType::P1Q3, "P1Q3", "3 points, degree 2 (default)"},
    {ActorBoundaryElementType::P1Q6, "P1Q6", "6 points, degree 4"},
    {ActorBoundaryElementType::ExperimentalP1Q7, "ExperimentalP1Q7", "7 points, degree 5"},
    {ActorBoundaryElementType::ExperimentalP1Q12, "ExperimentalP1Q12", "12 points, degree 6"},
    {ActorBoundaryElementType::ExperimentalP1Q16, "ExperimentalP1Q16", "16 points, degree 8"})

SUPERDEX_ENUM_NAMES(IncludeNestedActors,
    {IncludeNestedActors::No, "No"},
    {IncludeNestedActors::Yes, "Yes"})

SUPERDEX_ENUM_NAMES(SurfaceIntegral,
    {SurfaceIntegral::Quadrature, "Quadrature", "the spec's rule on the sampled surface (default)"},
    {SurfaceIntegral::ExactSphere, "ExactSphere",
     "a sphere's penalty integrated exactly against plane, box-face and sphere fields"})

}  // namespace superdex
