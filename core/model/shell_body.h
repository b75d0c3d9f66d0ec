// Shell actors: triangle meshes with a thickness (energies/shell_energies.h: the StVK membrane per
// triangle, the hinge bending per interior edge). Description (what a user gives), model (fixed
// during a run) and the builder. Units: SI (m, kg, s, Pa).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/model/collider_params.h"
#include "core/model/contact_params.h"
#include "core/model/enums.h"
#include "core/model/error.h"
#include "core/model/soft_body.h"
#include "core/model/vector_state.h"
#include "energies/shell_energies.h"
#include "energies/shell_midedge.h"
#include "geometry/quadrature.h"
#include "geometry/triangle_mesh.h"

namespace superdex {

/// Material of a shell: the membrane and the plate it makes with its thickness h.
struct ShellMaterial {
  double youngsModulus = 1e6;  ///< E
  double poissonRatio = 0.3;   ///< ν
  double density = 1000.0;     ///< ρ
  double thickness = 1e-3;     ///< h
  double stiffnessDamping = 0.0;  ///< β [s]: Rayleigh stiffness-proportional damping
};

inline constexpr auto kShellMaterialFields = std::make_tuple(
    MakeField("youngs_modulus", &ShellMaterial::youngsModulus, "Pa",
              PositiveRule().Worded("finite and > 0"), "Young's modulus E"),
    MakeField("poisson_ratio", &ShellMaterial::poissonRatio, "-", InOpen(-1, 0.5),
              "Poisson's ratio ν"),
    MakeField("density", &ShellMaterial::density, "kg/m^3", PositiveRule().Worded("finite and > 0"),
              "Density ρ (the shell's mass is ρ h A)"),
    MakeField("thickness", &ShellMaterial::thickness, "m", PositiveRule().Worded("finite and > 0"),
              "Thickness h (membrane stiffness E h, plate stiffness E h³ / (12 (1 − ν²)))"),
    MakeField("stiffness_damping", &ShellMaterial::stiffnessDamping, "s", NonNegativeRule(),
              "Rayleigh stiffness damping β: dissipation β/2 vᵀ K v, K the elastic Hessian "
              "(membrane and bending) at the stage's predictor"));

/// The table of Validate (optim/field_table.h).
constexpr const auto& FieldsOf(const ShellMaterial&) { return kShellMaterialFields; }

/// The bending model of a shell (energies/shell_midedge.h, energies/shell_energies.h):
///   Midedge: Kirchhoff–Love bending from each triangle's mid-edge shape operator, with the
///            plate's Poisson term (plates and shells; the default);
///   Hinge:   the discrete-shells hinge on every interior edge, D/2 (κ₁ + κ₂)² only: cheaper,
///            closed form, for cloth; a plate's free edges are too soft with it (it has no
///            Poisson term: a square cantilever deflects 28 % more than Kirchhoff's at ν = 0).
enum class ShellBendingModel { Midedge, Hinge };
/// "Midedge", "Hinge"
EnumNames<ShellBendingModel> NamesOf(ShellBendingModel);

/// What a user gives to create a shell actor. The triangle mesh is the rest shape (in its own
/// frame; flat or curved: its rest dihedral angles are the natural ones); position and
/// orientation place it; every node starts with `linearVelocity`.
struct ShellActorDesc {
  std::string name;
  std::shared_ptr<const TriangleMesh> mesh;
  std::string meshSource;  ///< the mesh's file or generator, for messages
  Eigen::Vector3d position = Eigen::Vector3d::Zero();               ///< [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();         ///< [m/s]
  ShellMaterial material;
  ShellBendingModel bending = ShellBendingModel::Midedge;
  ContactParams contact;
  /// The quadrature rule per triangle of the colliding role (spec: a shell's contactElementType).
  ActorBoundaryElementType contactElementType = ActorBoundaryElementType::P1Q3;
  /// Its collider role: Auto and PointCloud make it a PointCloud collider (spec: a shell's
  /// default), None none; a shell has no field of its own, so no other type.
  ColliderType colliderType = ColliderType::Auto;
  PointCloudColliderParams pointCloud;  ///< L_B, self-contact, the collider points' rule
  std::string contactLayer = "default";
  std::vector<NodeConstraint> constraints;  ///< pinned or driven nodes
  std::vector<NodeLoad> loads;              ///< dead loads on nodes (e.g. a line load, lumped)
  /// Clamped nodes: pinned, and every edge between two of them holds its rest mid-edge normal
  /// (Midedge bending), so that the shell cannot turn about a clamped edge.
  std::vector<int> clampedNodes;
};

/// An interior edge: nodes 0, 1 the hinge (in the order of its first triangle), 2 and 3 the
/// wings; its stiffness k_e [J/rad²] and rest angle θ̄ [rad].
struct ShellHinge {
  int node[4] = {0, 0, 0, 0};
  double stiffness = 0.0;
  double restAngle = 0.0;
};

/// A colliding sample on triangle `face`: y = Σ_a b_a x_a, weight w = A w_q [m²].
struct ShellSample {
  int face = 0;
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
  double weight = 0.0;
};

/// A collider point of the PointCloud collider (spec: "Double-Integral Generalization"): mesh node
/// `node` (face −1) with its lumped area, or a quadrature point of triangle `face` (barycentrics
/// `bary`, pointCloud.colliderTriangleElementType) with A w_q; weight w_B [m²].
struct ShellCloudPoint {
  int node = -1;
  int face = -1;
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
  double weight = 0.0;
};

/// Everything about a shell that stays fixed during a run.
struct ShellModel {
  std::string name;
  std::vector<Eigen::Vector3i> faces;
  std::vector<ShellTriangle> triangles;  ///< rest data per face
  ShellBendingModel bending = ShellBendingModel::Midedge;
  std::vector<ShellHinge> hinges;                 ///< Hinge: the interior edges
  /// Midedge: per face, the vertex across each edge (−1: boundary) and the rest data.
  std::vector<Eigen::Vector3i> opposite;
  std::vector<MidedgeTriangle> bendingTriangles;
  ShellMaterial material;
  LameParameters lame;                   ///< plane stress
  double plateStiffness = 0.0;           ///< D [N·m]
  Eigen::VectorXd nodeMass;              ///< lumped: ρ h A / 3 from each adjacent triangle [kg]
  double mass = 0.0;                     ///< [kg]
  std::vector<ShellSample> samples;      ///< grouped face by face
  std::vector<int> faceSampleBegin;      ///< samples of face f: [begin[f], begin[f+1])
  bool pointCloud = false;               ///< a PointCloud collider (colliderType Auto or PointCloud)
  PointCloudColliderParams cloud;
  std::vector<ShellCloudPoint> cloudPoints;
  std::vector<int> freeIndex;            ///< per node: index among the free nodes, −1 if prescribed
  std::vector<NodeConstraint> constraints;
  std::vector<NodeLoad> loads;
  int NumNodes() const { return static_cast<int>(nodeMass.size()); }
};

/// A face's mid-edge stencil from node positions X: its corners, then the vertex across each edge
/// (zeros where there is none), and which of those exist.
MidedgeStencil MidedgeNodes(const std::vector<Eigen::Vector3d>& X, const Eigen::Vector3i& face,
                            const Eigen::Vector3i& opposite);
std::array<bool, 3> Has(const Eigen::Vector3i& opposite);

/// Builds the model and the initial state (node positions in the world, their velocities),
/// validating the description: the material's fields, a mesh of at least one triangle, every
/// triangle non-degenerate, every edge shared by at most two triangles (a manifold with
/// boundary) that traverse it in opposite directions (consistently oriented), constraints on
/// existing nodes, loads on existing nodes with valid keyframes, a collider type a shell can provide (Auto, None, PointCloud) and valid
/// point-cloud parameters. False with *error naming the field (`prefix` + its
/// snake_case name) and the rule.
bool BuildShell(const ShellActorDesc& desc, const std::string& prefix, ShellModel* model,
                VectorState* state, Error* error);

}  // namespace superdex
