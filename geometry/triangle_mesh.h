// Triangle surface meshes: storage, generators, OBJ reading, mass properties.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "geometry/aabb.h"

namespace superdex {

/// The vertices of a mesh (TriangleMesh, TetMesh) [m].
struct MeshVertices {
  std::vector<Eigen::Vector3d> vertices;

  int NumVertices() const { return static_cast<int>(vertices.size()); }
  /// Bounding box of all vertices (empty box for an empty mesh).
  Aabb Bounds() const;
};

/// A triangle surface mesh. Faces are counter-clockwise seen from outside (outward normals by
/// the right-hand rule) for closed meshes. Units: metres.
struct TriangleMesh : MeshVertices {
  std::vector<Eigen::Vector3i> faces;

  int NumFaces() const { return static_cast<int>(faces.size()); }
  /// Area of face f [m^2].
  double FaceArea(int f) const;
  /// Outward unit normal of face f (zero vector for a degenerate face).
  Eigen::Vector3d FaceNormal(int f) const;
  double SurfaceArea() const;
};

/// Icosphere of the given radius [m]: an icosahedron subdivided `subdivisions` times (each
/// subdivision splits every triangle in four), vertices projected onto the sphere.
/// 20 * 4^subdivisions faces.
TriangleMesh MakeIcosphere(double radius, int subdivisions);

/// Axis-aligned box centred at the origin with the given half extents [m]; every face split into
/// a `divisions` x `divisions` grid of quads, two triangles each (divisions >= 1).
TriangleMesh MakeBoxMesh(const Eigen::Vector3d& halfExtents, int divisions = 1);

/// Square patch in the z = 0 plane centred at the origin, side `size` [m], `divisions` x
/// `divisions` quads, normals +z (an open surface).
TriangleMesh MakePlanePatch(double size, int divisions);

/// Across each face's edges: (*opposite)[f][i] is the vertex of the other face on the edge opposite
/// faces[f][i] (between faces[f][i+1] and faces[f][i+2]), −1 on a boundary edge. False, with the
/// edge's two vertices in *badEdge, when an edge has more than two faces (not a manifold).
/// *oppositeFace (may be null) gets the other face's index the same way.
bool FaceOppositeVertices(const std::vector<Eigen::Vector3i>& faces,
                          std::vector<Eigen::Vector3i>* opposite, std::pair<int, int>* badEdge,
                          std::vector<Eigen::Vector3i>* oppositeFace = nullptr);

/// Rectangle [lo, hi] in the z = 0 plane, cells.x() × cells.y() quads (at least 1 each), each
/// split into two triangles along its (−,−)→(+,+) diagonal, counter-clockwise seen from +z.
/// Vertex (i, j) has index i + (cells.x() + 1) j.
TriangleMesh MakeRectangleMesh(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                               const Eigen::Vector2i& cells);

/// Annular sector in the z = 0 plane about the origin: radii innerRadius < outerRadius [m],
/// angles θ ∈ [0, angle] (0 < angle <= 2π) from +x towards +y, cells.x() radial by cells.y()
/// angular quads, each split in two, counter-clockwise seen from +z. Vertex (i, j) (radius i,
/// angle j) has index i + (cells.x() + 1) j. With angle = 2π the ends θ = 0 and 2π stay
/// separate vertices: an annulus with a slit.
TriangleMesh MakeAnnulusMesh(double innerRadius, double outerRadius, double angle,
                             const Eigen::Vector2i& cells);

/// Disk of `radius` [m] in the z = 0 plane about the origin: a centre vertex and `rings` (>= 1)
/// rings, ring k of 6k vertices at radius k·radius/rings (vertex 0 the centre, ring k's first at
/// angle 0 on +x), neighbouring rings zipped into triangles by angle (6 k² triangles inside ring
/// k; nearly equilateral), counter-clockwise seen from +z.
TriangleMesh MakeDiskMesh(double radius, int rings);

/// Closed cylinder along x centred at the origin: radius [m], half length [m], `segments` around
/// (>= 3), `rings` side rows (>= 1), fan-triangulated caps; outward oriented.
TriangleMesh MakeCylinderMesh(double radius, double halfLength, int segments, int rings);

/// Closed capsule along z centred at the origin: radius [m], half length of the straight part
/// [m]; `segments` around (>= 3), `capRings` latitude rings per end cap (>= 1, the last on the
/// cap's equator), `rows` side rows (>= 1); poles as fans; outward oriented. Its vertices lie on
/// the capsule.
TriangleMesh MakeCapsuleMesh(double radius, double halfLength, int segments, int capRings,
                             int rows);
/// The capsule as the writers draw it (VTK frames, the trajectory's header): 24 around, 6 rings
/// per cap, 8 side rows.
inline TriangleMesh MakeCapsuleDrawing(double radius, double halfLength) {
  return MakeCapsuleMesh(radius, halfLength, 24, 6, 8);
}

/// Reads vertices ("v") and faces ("f", polygons fan-triangulated, "v/vt/vn" forms and negative
/// indices accepted) from a Wavefront OBJ file. Returns false and fills *error (naming the file,
/// the line and the problem) on failure.
bool ReadObj(const std::string& path, TriangleMesh* mesh, std::string* error);
/// Writes the mesh as a Wavefront OBJ file ("v x y z", "f a b c"), numbers that read back
/// exactly: ReadObj gives the same vertices and faces.
bool WriteObj(const TriangleMesh& mesh, const std::string& path, std::string* error);

/// Mass properties of the solid bounded by a closed, outward-oriented mesh of uniform density
/// [kg/m^3]: mass [kg], centre of mass [m], and the second-moment matrix about the centre of mass
/// J = ∫ (x - c)(x - c)^T dm [kg m^2] (the inertia tensor is tr(J) I - J).
struct MassProperties {
  double volume = 0.0;
  double mass = 0.0;
  Eigen::Vector3d centerOfMass = Eigen::Vector3d::Zero();
  Eigen::Matrix3d secondMoment = Eigen::Matrix3d::Zero();
};
MassProperties ComputeMassProperties(const TriangleMesh& mesh, double density);

}  // namespace superdex
