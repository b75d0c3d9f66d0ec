// Exact signed distance to a closed triangle mesh: the closest point from CGAL's AABB tree, the
// sign from CGAL's Side_of_triangle_mesh (ray-casting inside test), negative inside.
#pragma once

#include <memory>
#include <string>

#include "geometry/analytic_sdf.h"
#include "geometry/triangle_mesh.h"

namespace superdex {

class MeshSdf {
 public:
  /// Builds the distance structure; returns null and fills *error ("<what>: <defect>") if the
  /// mesh is empty, not closed (a boundary edge), or inward oriented (negative volume).
  static std::shared_ptr<const MeshSdf> Build(const TriangleMesh& mesh, std::string* error);
  ~MeshSdf();

  /// Φ = ±|X − c| with c the closest surface point; ∇Φ = ±(X − c)/|X − c| (the face normal when
  /// X is on the surface); ∇∇Φ from the closest feature: 0 on a face interior,
  /// Φ⁻¹(1 − ∇Φ∇Φᵀ − t tᵀ) on an edge (t its direction), Φ⁻¹(1 − ∇Φ∇Φᵀ) at a vertex. [m, -, 1/m]
  SdfSample Evaluate(const Eigen::Vector3d& X) const;
  /// Distance only (for grid construction).
  double Value(const Eigen::Vector3d& X) const;
  /// Largest |X| over the vertices [m].
  double BoundingRadius() const { return radius_; }

 private:
  struct Impl;
  explicit MeshSdf(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  double radius_ = 0.0;
};

}  // namespace superdex
