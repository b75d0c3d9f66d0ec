// Collider construction parameters named by the spec (GridSdfParams, PointCloudColliderParams) and
// the grid sizing shared by rigid and soft Sdf colliders. The PointCloud collider is a shell's
// (core/model/shell_kind.h; its pairs: core/contact/point_cloud.h); rigid and soft actors refuse it.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "core/model/enums.h"
#include "geometry/grid_sdf.h"
#include "geometry/quadrature.h"
#include "geometry/triangle_mesh.h"
#include "optim/field_table.h"

namespace superdex {

/// The reference length that sizes a grid SDF's voxels (GridSdfParams::resolutionMode).
enum class GridSdfResolutionMode {
  MeanEdgeLength,   ///< the shape mesh's mean edge length
  BoundingExtent,   ///< the longest side of the shape's bounding box, divided by 64
};
EnumNames<GridSdfResolutionMode> NamesOf(GridSdfResolutionMode);

/// Grid SDF construction (spec: "Collider Representations").
/// Fields: kGridSdfFields.
struct GridSdfParams {
  GridSdfResolutionMode resolutionMode = GridSdfResolutionMode::MeanEdgeLength;
  double resolutionDelta = 1.0;  ///< voxel size = resolutionDelta × reference length
  int minGridResolution = 16;
  double boundaryPaddingDist = 0.01;
};

inline constexpr auto kGridSdfFields = std::make_tuple(
    MakeField("resolution_mode", &GridSdfParams::resolutionMode, "", NoRule(),
              "Reference length for the voxel size"),
    MakeField("resolution_delta", &GridSdfParams::resolutionDelta, "-", PositiveRule(),
              "Voxel size as a multiple of the reference length"),
    MakeField("min_grid_resolution", &GridSdfParams::minGridResolution, "", AtLeast(2, 4096),
              "Minimum voxel count per axis"),
    MakeField("boundary_padding_dist", &GridSdfParams::boundaryPaddingDist, "m", NonNegativeRule(),
              "Grid extension beyond the shape bounds"));

/// Point-cloud colliders (spec: "PointCloudColliderParams"); defaults are the spec's. Fields:
/// kPointCloudColliderFields.
struct PointCloudColliderParams {
  double radius = 0.01;  ///< L_B
  double selfContactExclusionRatio = 1.5;
  double spatialHashLoadFactor = 0.0625;
  bool selfContact = false;
  std::optional<ActorBoundaryElementType> colliderTriangleElementType;
};

inline constexpr auto kPointCloudColliderFields = std::make_tuple(
    MakeField("radius", &PointCloudColliderParams::radius, "m", PositiveRule(),
              "Interaction range L_B"),
    MakeField("self_contact_exclusion_ratio", &PointCloudColliderParams::selfContactExclusionRatio,
              "-", Above(1.0),
              "Self-contact exclusion ratio r: points closer than r L_B in the reference "
              "configuration do not touch"),
    MakeField("spatial_hash_load_factor", &PointCloudColliderParams::spatialHashLoadFactor, "-",
              PositiveRule(), "Load factor of the collision-detection spatial hash"),
    MakeField("self_contact", &PointCloudColliderParams::selfContact, "", NoRule(),
              "Whether to enable self-contact"),
    MakeField("collider_triangle_element_type",
              &PointCloudColliderParams::colliderTriangleElementType, "", NoRule(),
              "Quadrature-based collider discretization for surfaces; none: the mesh nodes"));

/// The tables of Validate (optim/field_table.h).
constexpr const auto& FieldsOf(const GridSdfParams&) { return kGridSdfFields; }
constexpr const auto& FieldsOf(const PointCloudColliderParams&) {
  return kPointCloudColliderFields;
}

/// A grid SDF of the solid bounded by `mesh` (its frame), sampling `phi` (the exact field): voxel
/// h = resolutionDelta × reference length (MeanEdgeLength: the mesh's mean edge length;
/// BoundingExtent: the bounding box's longest side / 64), reduced so that every axis of the box
/// padded by boundaryPaddingDist holds at least minGridResolution voxels. Null (and *error) for
/// invalid params or a grid above 64e6 nodes.
std::shared_ptr<GridSdf> BuildGridSdf(const TriangleMesh& mesh,
                                      const std::function<double(const Eigen::Vector3d&)>& phi,
                                      const GridSdfParams& params, std::string* error);

}  // namespace superdex
