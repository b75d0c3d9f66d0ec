// Enums and parameter types of the spec, with snake_case properties that validate on assignment.
#include <pybind11/stl.h>

#include <cmath>
#include <sstream>

#include "bindings.h"
#include "core/model/collider_params.h"
#include "core/model/contact_params.h"
#include "core/model/enums.h"
#include "core/model/eval_params.h"
#include "core/model/soft_body.h"
#include "energies/contact_dissipation.h"
#include "energies/stable_neo_hookean.h"

namespace superdex::python {
namespace {

// The rules BuildSoftBody applies to a soft actor's material (core/model/soft_body.cpp), so that a bad
// value is refused where it is assigned, with the same message.
std::string Validate(const SoftMaterial& m) {
  std::string e = ValidateElasticMaterial(m.youngsModulus, m.poissonRatio, m.density);
  if (e.empty() && !(std::isfinite(m.stiffnessDamping) && m.stiffnessDamping >= 0)) {
    std::ostringstream s;
    s << "stiffness_damping: must be >= 0 and finite, got " << m.stiffnessDamping;
    e = s.str();
  }
  return e;
}

// A property that validates the whole object after the assignment and rolls back on failure.
template <typename Class, typename T>
void Field(py::class_<Class>& c, const char* name, T Class::*member, const char* doc) {
  c.def_property(
      name, [member](const Class& p) { return p.*member; },
      [member](Class& p, T v) {
        Class q = p;
        q.*member = v;
        CheckValue(Validate(q));
        p = q;
      },
      doc);
}

}  // namespace

void BindParams(py::module_& m) {
  py::enum_<ColliderType>(m, "ColliderType",
                          "How an actor supplies its distance field (spec: Collider "
                          "Representations). PointCloud is not implemented yet; soft actors "
                          "accept None, Sdf and Auto. `None` is a Python keyword: write "
                          "getattr(ColliderType, 'None').")
      .value("Auto", ColliderType::Auto, "by actor and shape: analytic for sphere, box, plane")
      .value("None", ColliderType::None, "no collider role (the actor may still collide)")
      .value("Sphere", ColliderType::Sphere)
      .value("Box", ColliderType::Box)
      .value("Plane", ColliderType::Plane)
      .value("Mesh", ColliderType::Mesh)
      .value("Sdf", ColliderType::Sdf)
      .value("PointCloud", ColliderType::PointCloud);
  py::enum_<ActorBoundaryElementType>(m, "ActorBoundaryElementType",
                                      "Surface quadrature rule per boundary triangle.")
      .value("P1Q1", ActorBoundaryElementType::P1Q1, "1 point, exact for degree 1")
      .value("P1Q3", ActorBoundaryElementType::P1Q3, "3 points, degree 2 (default)")
      .value("P1Q6", ActorBoundaryElementType::P1Q6, "6 points, degree 4")
      .value("ExperimentalP1Q7", ActorBoundaryElementType::ExperimentalP1Q7, "7 points, degree 5")
      .value("ExperimentalP1Q12", ActorBoundaryElementType::ExperimentalP1Q12, "12 points, degree 6")
      .value("ExperimentalP1Q16", ActorBoundaryElementType::ExperimentalP1Q16, "16 points, degree 8");
  py::enum_<IntegrationMethod>(m, "IntegrationMethod",
                               "Time integrators; every stage is an incremental-potential stage.")
      .value("BackwardEuler", IntegrationMethod::BackwardEuler, "order 1, L-stable")
      .value("BDF2", IntegrationMethod::BDF2, "order 2, A-stable (default)")
      .value("BDF3", IntegrationMethod::BDF3, "order 3")
      .value("DIRK22", IntegrationMethod::DIRK22, "order 2, L-stable")
      .value("DIRK23", IntegrationMethod::DIRK23, "order 3, A-stable")
      .value("DIRK33", IntegrationMethod::DIRK33, "order 3, L-stable")
      .value("SymplecticDIRK12", IntegrationMethod::SymplecticDIRK12, "implicit midpoint")
      .value("SymplecticDIRK22", IntegrationMethod::SymplecticDIRK22, "order 2, symplectic");
  py::enum_<IncludeNestedActors>(m, "IncludeNestedActors",
                                 "Whether actor-pair filtering also applies to nested actors.")
      .value("No", IncludeNestedActors::No)
      .value("Yes", IncludeNestedActors::Yes);
  py::enum_<GridSdfResolutionMode>(m, "GridSdfResolutionMode",
                                   "Reference length that sizes a grid SDF's voxels.")
      .value("MeanEdgeLength", GridSdfResolutionMode::MeanEdgeLength)
      .value("BoundingExtent", GridSdfResolutionMode::BoundingExtent);

  py::class_<ContactParams> cp(m, "ContactParams",
                               "Contact response of one actor (spec: ContactParams). Every "
                               "assignment is validated; a bad value raises ValueError naming "
                               "the field and the rule.");
  cp.def(py::init<>());
  Field(cp, "penalty_coefficient", &ContactParams::penaltyCoefficient,
        "Penalty coefficient k [Pa/m], > 0. Default 1e9.");
  Field(cp, "penalty_smoothing_half_distance", &ContactParams::penaltySmoothingHalfDistance,
        "Smoothing half-width eps of the ramp [m], > 0. Default 0.005.");
  Field(cp, "penalty_threshold_default", &ContactParams::penaltyThresholdDefault,
        "Contact threshold delta at which the penalty activates [m]. Default 0.001.");
  Field(cp, "penalty_threshold_extra_padding", &ContactParams::penaltyThresholdExtraPadding,
        "Extra delta when the colliding actor uses None or PointCloud [m], >= 0. Default 0.");
  Field(cp, "friction_with_collider_normal", &ContactParams::frictionWithColliderNormal,
        "Split on the collider-field direction N_B (True) or -N_A. Default True.");
  Field(cp, "max_alignment_normals", &ContactParams::maxAlignmentNormals,
        "Maximum normal alignment m in [-1, 1]; contact rejected when s > m. Default 0.");
  Field(cp, "viscous_friction_coefficient", &ContactParams::viscousFrictionCoefficient,
        "Tangential viscous friction coefficient c_t [s/m], >= 0. Default 0.");
  Field(cp, "coulomb_friction_coefficient", &ContactParams::coulombFrictionCoefficient,
        "Coulomb friction coefficient mu [-], >= 0. Default 0.5.");
  Field(cp, "friction_falloff_vel", &ContactParams::frictionFalloffVel,
        "Falloff velocity V_f of the regularized Coulomb ramp [m/s], > 0. Default 0.01.");
  Field(cp, "normal_viscous_damping_coefficient", &ContactParams::normalViscousDampingCoefficient,
        "Normal viscous damping coefficient c_n [s/m], >= 0 (Hunt-Crossley restitution). "
        "Default 0.");
  Field(cp, "distance_error_bound", &ContactParams::distanceErrorBound,
        "Experimental: extra collider bounding-volume padding [m], >= 0. Default 0.");
  Field(cp, "colliding_penalty_length_scale", &ContactParams::collidingPenaltyLengthScale,
        "Experimental: penalty correction scale for lower-dimensional colliding manifolds [m], "
        "> 0; taken from the colliding actor. Default 1.");
  cp.def("__repr__", [](const ContactParams& p) {
    return "ContactParams(penalty_coefficient=" + std::to_string(p.penaltyCoefficient) +
           ", coulomb_friction_coefficient=" + std::to_string(p.coulombFrictionCoefficient) +
           ", normal_viscous_damping_coefficient=" +
           std::to_string(p.normalViscousDampingCoefficient) + ", ...)";
  });

  py::class_<ExperimentalEvalParams> ep(
      m, "ExperimentalEvalParams",
      "Time levels of the dissipative terms (spec: Stage-Discrete Dissipation).\n"
      "explicit_normals=True: stage-start normals and load; the dissipation is an exact\n"
      "potential (stages are minimizations). False (default): current geometry with the\n"
      "stage-start load reconstructed; not a potential (residual solve). The combination\n"
      "(explicit_normals=True, implicit_normal_force_for_dissipation=True) is refused.");
  ep.def(py::init<>());
  Field(ep, "explicit_normals", &ExperimentalEvalParams::explicitNormals,
        "Stage-start normals, alignment, friction plane and load. Default False.");
  Field(ep, "implicit_normal_force_for_dissipation",
        &ExperimentalEvalParams::implicitNormalForceForDissipation,
        "Scale dissipation by the current normal load. Default False.");
  Field(ep, "fade_friction", &ExperimentalEvalParams::fadeFriction,
        "Alignment-based attenuation a = (m - s)/(m + 1) of dissipation. Default True.");

  py::class_<GridSdfParams> gp(m, "GridSdfParams",
                               "Grid SDF construction for Sdf colliders (RigidActorDesc.grid_sdf, "
                               "SoftActorDesc.grid_sdf).");
  gp.def(py::init<>());
  Field(gp, "resolution_mode", &GridSdfParams::resolutionMode,
        "Reference length for the voxel size. Default MeanEdgeLength.");
  Field(gp, "resolution_delta", &GridSdfParams::resolutionDelta,
        "Voxel size as a multiple of the reference length [-], > 0. Default 1.");
  Field(gp, "min_grid_resolution", &GridSdfParams::minGridResolution,
        "Minimum voxel count per axis, >= 2. Default 16.");
  Field(gp, "boundary_padding_dist", &GridSdfParams::boundaryPaddingDist,
        "Grid extension beyond the shape bounds [m], >= 0. Default 0.01.");

  py::class_<SoftMaterial> sm(m, "SoftMaterial",
                              "Bulk material of a soft actor (stable neo-Hookean). Every assignment "
                              "is validated; a bad value raises ValueError naming the field and "
                              "the rule.");
  sm.def(py::init([](double youngsModulus, double poissonRatio, double density,
                     double stiffnessDamping) {
           SoftMaterial s;
           s.youngsModulus = youngsModulus;
           s.poissonRatio = poissonRatio;
           s.density = density;
           s.stiffnessDamping = stiffnessDamping;
           CheckValue(Validate(s));
           return s;
         }),
         py::arg("youngs_modulus") = SoftMaterial().youngsModulus,
         py::arg("poisson_ratio") = SoftMaterial().poissonRatio,
         py::arg("density") = SoftMaterial().density,
         py::arg("stiffness_damping") = SoftMaterial().stiffnessDamping);
  Field(sm, "youngs_modulus", &SoftMaterial::youngsModulus,
        "Young's modulus E [Pa], finite and > 0. Default 1e5.");
  Field(sm, "poisson_ratio", &SoftMaterial::poissonRatio,
        "Poisson's ratio nu [-], in (-1, 0.5). Default 0.3.");
  Field(sm, "density", &SoftMaterial::density,
        "Density rho [kg/m^3], finite and > 0. Default 1000.");
  Field(sm, "stiffness_damping", &SoftMaterial::stiffnessDamping,
        "Rayleigh stiffness damping beta [s], >= 0 (dissipation R = beta/2 v^T K v). Default 0.");
  sm.def("__repr__", [](const SoftMaterial& s) {
    std::ostringstream o;
    o << "SoftMaterial(youngs_modulus=" << s.youngsModulus << ", poisson_ratio=" << s.poissonRatio
      << ", density=" << s.density << ", stiffness_damping=" << s.stiffnessDamping << ")";
    return o.str();
  });

  py::class_<PointCloudColliderParams> pc(
      m, "PointCloudColliderParams",
      "Point-cloud collider parameters (the PointCloud collider is not implemented yet).");
  pc.def(py::init<>());
  Field(pc, "radius", &PointCloudColliderParams::radius,
        "Interaction range L_B [m], > 0. Default 0.01.");
  Field(pc, "self_contact_exclusion_ratio", &PointCloudColliderParams::selfContactExclusionRatio,
        "Self-contact exclusion ratio r [-], > 0. Default 1.5.");
  Field(pc, "spatial_hash_load_factor", &PointCloudColliderParams::spatialHashLoadFactor,
        "Load factor of the collision-detection spatial hash [-], > 0. Default 0.0625.");
  Field(pc, "self_contact", &PointCloudColliderParams::selfContact,
        "Whether to enable self-contact. Default False.");
  Field(pc, "collider_triangle_element_type", &PointCloudColliderParams::colliderTriangleElementType,
        "Optional quadrature-based collider discretization for surfaces; None uses mesh nodes.");

  m.def("hunt_crossley_damping_from_restitution", &HuntCrossleyDampingFromRestitution,
        py::arg("e"), py::arg("v"),
        "Rational Hunt-Crossley approximation c_n = (1 - e)(1 + 9e/2) / (e v (1 + 8e/3)) [s/m]\n"
        "for a coefficient of restitution e in (0, 1] at impact speed v > 0 [m/s]; NaN outside.");
  m.def("hunt_crossley_restitution_from_damping", &HuntCrossleyRestitutionFromDamping,
        py::arg("cn"), py::arg("v"),
        "Closed-form inverse: e = 2 / (B + sqrt(B^2 + 4A)), A = 8a/3 + 9/2, B = a - 7/2, a = cn v.");
}

}  // namespace superdex::python
