// Collider construction parameters named by the spec (GridSdfParams, PointCloudColliderParams) and
// the grid sizing shared by rigid and soft Sdf colliders. The PointCloud collider itself is not
// implemented yet: an actor that requests it gets a clear error; its parameter type exists so that
// the C++ and Python APIs carry the spec's names, defaults and validation from the start.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "geometry/grid_sdf.h"
#include "geometry/quadrature.h"
#include "geometry/triangle_mesh.h"

namespace superdex {

/// The reference length that sizes a grid SDF's voxels (GridSdfParams::resolutionMode).
enum class GridSdfResolutionMode {
  MeanEdgeLength,   ///< the shape mesh's mean edge length
  BoundingExtent,   ///< the longest side of the shape's bounding box, divided by 64
};

/// Grid SDF construction (spec: "Collider Representations").
struct GridSdfParams {
  GridSdfResolutionMode resolutionMode = GridSdfResolutionMode::MeanEdgeLength;
  double resolutionDelta = 1.0;      ///< voxel size = resolutionDelta × reference length [-], > 0
  int minGridResolution = 16;        ///< minimum voxel count per axis, >= 2
  double boundaryPaddingDist = 0.01; ///< grid extension beyond the shape bounds [m], >= 0
};

/// Point-cloud colliders (spec: "PointCloudColliderParams"); defaults are the spec's.
struct PointCloudColliderParams {
  double radius = 0.01;                     ///< interaction range L_B [m], > 0
  double selfContactExclusionRatio = 1.5;   ///< r [-], > 0
  double spatialHashLoadFactor = 0.0625;    ///< [-], > 0
  bool selfContact = false;
  /// Quadrature-based collider discretization for surfaces; otherwise mesh nodes.
  std::optional<ActorBoundaryElementType> colliderTriangleElementType;
};

const char* ToString(GridSdfResolutionMode mode);

/// "" when valid, else "<prefix><snake_case field>: <rule>, got <value>".
std::string Validate(const GridSdfParams& params, const std::string& prefix = "");
std::string Validate(const PointCloudColliderParams& params, const std::string& prefix = "");

/// A grid SDF of the solid bounded by `mesh` (its frame), sampling `phi` (the exact field): voxel
/// h = resolutionDelta × reference length (MeanEdgeLength: the mesh's mean edge length;
/// BoundingExtent: the bounding box's longest side / 64), reduced so that every axis of the box
/// padded by boundaryPaddingDist holds at least minGridResolution voxels. Null (and *error) for
/// invalid params or a grid above 64e6 nodes.
std::shared_ptr<GridSdf> BuildGridSdf(const TriangleMesh& mesh,
                                      const std::function<double(const Eigen::Vector3d&)>& phi,
                                      const GridSdfParams& params, std::string* error);

}  // namespace superdex
