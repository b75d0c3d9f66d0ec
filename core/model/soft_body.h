// Soft actors: tetrahedral finite elements with the stable neo-Hookean material. Description
// (what a user gives), model (fixed during a run) and state (node positions and velocities).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/model/vector_state.h"
#include "core/model/collider_params.h"
#include "core/model/contact_params.h"
#include "core/model/enums.h"
#include "core/model/keyframes.h"
#include "core/model/error.h"
#include "energies/stable_neo_hookean.h"
#include "geometry/aabb.h"
#include "geometry/quadrature.h"
#include "geometry/tet_mesh.h"

namespace superdex {

/// Bulk material of a soft actor. Restitution of a soft body comes from its bulk (spec:
/// "Friction and Damping"): `stiffnessDamping` β adds the Rayleigh dissipation R = β/2 vᵀ K v.
struct SoftMaterial {
  double youngsModulus = 1e5;     ///< E
  double poissonRatio = 0.3;      ///< ν
  double density = 1000.0;        ///< ρ
  double stiffnessDamping = 0.0;  ///< β
};

inline constexpr auto kSoftMaterialFields = std::make_tuple(
    MakeField("youngs_modulus", &SoftMaterial::youngsModulus, "Pa",
              PositiveRule().Worded("finite and > 0"), "Young's modulus E"),
    MakeField("poisson_ratio", &SoftMaterial::poissonRatio, "-", InOpen(-1, 0.5),
              "Poisson's ratio ν"),
    MakeField("density", &SoftMaterial::density, "kg/m^3", PositiveRule().Worded("finite and > 0"),
              "Density ρ"),
    MakeField("stiffness_damping", &SoftMaterial::stiffnessDamping, "s",
              NonNegativeRule().Worded(">= 0 and finite"),
              "Rayleigh stiffness damping β (dissipation R = β/2 vᵀ K v)"));

/// The table of Validate (optim/field_table.h).
constexpr const auto& FieldsOf(const SoftMaterial&) { return kSoftMaterialFields; }

/// A set of nodes whose positions are prescribed: pinned (held at their initial positions) or
/// driven along a piecewise-linear path of displacements from the initial positions.
struct NodeConstraint {
  std::vector<int> nodes;  ///< node indices of the tet mesh
  /// Keyframes (t [s], displacement [m]) with increasing times; empty: pinned. Before the first
  /// keyframe the first displacement holds, after the last the last one.
  VectorKeyframes path;
  /// Displacement at time t [m] (zero when pinned).
  Eigen::Vector3d Displacement(double t) const;
};

/// A dead load on nodes: each of `nodes` carries the force `force`(t) [N] (keyframes (t [s],
/// force [N]), linear in between, the first before and the last after them; one keyframe: a
/// constant load). Its potential −f(t)·x enters each stage at the stage's time.
struct NodeLoad {
  std::vector<int> nodes;
  VectorKeyframes force;
};

/// A soft skin's binding to a link of its skeleton (the articulated actor the soft actor is nested
/// under, Scene::AddSoftActor): the nodes it selects move with that link's rigid transform
/// (eliminated dofs, core/model/actor_kind.h CarriedPart), the union of
///   the listed nodes,
///   the nodes inside the region, the box [regionMin, regionMax] of the link frame (the link's
///   joint frame, as URDF's), where regionMin < regionMax [m], and
///   the nodes within `shapeDistance` of the link's collision shapes (Φ <= shapeDistance, each
///   shape's field; < 0: not used) [m],
/// at the configuration the skin is added in. A binding that selects no node is an error.
struct SkinBinding {
  std::string link;
  std::vector<int> nodes;
  bool hasRegion = false;
  Eigen::Vector3d regionMin = Eigen::Vector3d::Zero();  ///< [m], link frame
  Eigen::Vector3d regionMax = Eigen::Vector3d::Zero();  ///< [m], link frame
  double shapeDistance = -1.0;                        ///< [m]; < 0: not used
};

/// A body of nodes' placement: position, orientation (nonzero) and velocity finite; false with
/// *error naming them (`prefix`) otherwise.
bool ValidatePlacement(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                       const Eigen::Vector3d& velocity, const std::string& prefix, Error* error);
/// Empty constraints' nodes, nodes outside [0, n) and bad paths: false with *error naming the
/// field (`prefix` + "constraints[i]...") and the rule.
bool ValidateNodeConstraints(const std::vector<NodeConstraint>& constraints, int n,
                             const std::string& prefix, Error* error);

/// What a user gives to create a soft actor. The tet mesh is the rest shape (in its own frame);
/// position and orientation place it in the world; every node starts with `linearVelocity`.
struct SoftActorDesc {
  std::string name;
  std::shared_ptr<const TetMesh> mesh;
  std::string meshSource;  ///< the mesh's file or generator, for messages
  Eigen::Vector3d position = Eigen::Vector3d::Zero();               ///< [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();         ///< [m/s]
  SoftMaterial material;
  ContactParams contact;
  /// Soft actors are colliding only by default (spec: "Default Roles by Actor Type"). Sdf or Auto
  /// (experimental) make the actor a collider too: a grid SDF of its reference surface, mapped by
  /// the deformation (core/contact/tet_field.h). Other types are refused.
  ColliderType colliderType = ColliderType::None;
  GridSdfParams gridSdf;  ///< sizes the collider grid
  ActorBoundaryElementType boundaryElementType = ActorBoundaryElementType::P1Q3;
  std::string contactLayer = "default";
  std::vector<NodeConstraint> constraints;
  /// A soft-skinned actor's bindings to the links of its skeleton (its parent, an articulated
  /// actor); empty: a free soft body. Bound nodes may not be pinned or driven.
  std::vector<SkinBinding> skin;
};

/// One colliding quadrature sample on a boundary face: y = Σ_a b_a x_{face[a]}.
struct SoftSurfaceSample {
  int face = 0;              ///< index into SoftBodyModel::faces
  Eigen::Vector3d bary;      ///< barycentric coordinates
  double weight = 0.0;       ///< reference-area weight w_q [m²]
};

/// Everything about a soft actor that stays fixed during a run.
struct SoftBodyModel {
  std::string name;
  TetMesh rest;                          ///< reference configuration [m]
  std::vector<TetElement> elements;      ///< per tet: Dm⁻¹, rest volume
  LameParameters lame;                   ///< μ, λ [Pa]
  SoftMaterial material;
  Eigen::VectorXd nodeMass;              ///< lumped: ρ V/4 from each adjacent tet [kg]
  double mass = 0.0;                     ///< [kg]
  std::vector<Eigen::Vector3i> faces;    ///< boundary faces, outward (counter-clockwise)
  std::vector<double> faceArea;          ///< reference area [m²]
  std::vector<SoftSurfaceSample> samples;///< grouped face by face
  std::vector<int> faceSampleBegin;      ///< samples of face f: [begin[f], begin[f+1])
  std::vector<int> freeIndex;            ///< per node: index among the free nodes, −1 if prescribed
  int numFree = 0;
  std::vector<NodeConstraint> constraints;
  ContactParams contact;
  ActorBoundaryElementType boundaryElementType = ActorBoundaryElementType::P1Q3;
  std::string contactLayer;
  /// Collider role: None, or Sdf with the grid of Φ_B over the reference configuration.
  ColliderType collider = ColliderType::None;
  std::shared_ptr<const GridSdf> colliderGrid;
  double colliderLipschitz = std::sqrt(3.0);  ///< bound on |∇Φ_B| of the trilinear grid
  std::string notice;                          ///< grid size and memory, for the run log
  int NumNodes() const { return rest.NumVertices(); }
};

/// Node positions x and velocities v, stacked [x_0; x_1; …] (3n entries) [m], [m/s].
using SoftBodyState = VectorState;

/// Builds the model and initial state, validating the description (fields named with `prefix`).
bool BuildSoftBody(const SoftActorDesc& desc, const std::string& prefix, SoftBodyModel* model,
                   SoftBodyState* state, Error* error);

/// Positions of the prescribed nodes at time t written into *x (others untouched); `initial` is
/// the state the actor was created with.
void ApplyNodeConstraints(const SoftBodyModel& model, const Eigen::VectorXd& initial, double t,
                          Eigen::VectorXd* x);
/// The same for any body of nodes (3 entries each in x and initial).
void ApplyNodeConstraints(const std::vector<NodeConstraint>& constraints,
                          const Eigen::VectorXd& initial, double t, Eigen::VectorXd* x);

/// Kinetic energy ½ Σ m_a |v_a|² [J].
double KineticEnergy(const SoftBodyModel& model, const SoftBodyState& state);
/// Elastic energy Σ_t V_t Ψ(F_t) [J] and the smallest det F over the tets at positions x.
double ElasticEnergy(const SoftBodyModel& model, const Eigen::VectorXd& x, double* minDetF);
/// World bounds of the nodes.
Aabb SoftBounds(const Eigen::VectorXd& x);
/// The centroid *c of the triangle F of nodes at positions x and its largest distance to a
/// corner [m] (the ball that holds the triangle's samples).
double TriangleBall(const Eigen::VectorXd& x, const Eigen::Vector3i& F, Eigen::Vector3d* c);
/// Outward unit normal of boundary face f at positions x (zero for a degenerate face).
Eigen::Vector3d SoftFaceNormal(const SoftBodyModel& model, const Eigen::VectorXd& x, int f);

}  // namespace superdex
