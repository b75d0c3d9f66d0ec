// Tetrahedral volume meshes for soft bodies: storage, validation, boundary extraction, a
// structured box generator, Gmsh / TetGen file reading, and meshing of closed surfaces with CGAL
// Mesh_3 (geometry/tet_mesher.cpp).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "geometry/aabb.h"
#include "geometry/mesh_limits.h"
#include "geometry/triangle_mesh.h"

namespace superdex {

/// A tetrahedral mesh. Tet t has the vertices tets[t][0..3] (0-based indices into `vertices`);
/// it is positively oriented when its signed volume (see TetVolume) is positive, which every
/// generator and mesher here produces and ValidateTetMesh requires. Units: metres.
struct TetMesh : MeshVertices {
  std::vector<Eigen::Vector4i> tets;

  int NumTets() const { return static_cast<int>(tets.size()); }
  /// Signed volume of tet t [m^3]: (x1 − x0) · ((x2 − x0) × (x3 − x0)) / 6; positive when x3 is
  /// on the side of the plane (x0, x1, x2) that (x1 − x0) × (x2 − x0) points to. No range checks.
  double TetVolume(int t) const;
};

/// Reads a tetrahedral mesh file, the format chosen by the (case-insensitive) extension:
///  - `.msh`: Gmsh ASCII, format 2.x (2.2) or 4.1. Reads $MeshFormat, $Nodes and $Elements and
///    skips every other section. Keeps the 4-node tetrahedra (element type 4) and ignores all
///    other element types (points, lines, triangles, ...); Gmsh node tags are mapped to 0-based
///    indices in the order the nodes appear, and every node of the file becomes a vertex (also
///    nodes no tet uses). Binary files, format 4.0 and older formats are refused.
///  - `.node` / `.ele`: a TetGen pair with the same stem (reading either reads both). Points are
///    numbered from 0 or 1 as the first point says (consecutively); point attributes, boundary
///    markers and tet attributes are ignored; of 10-node tets the 4 corners are kept.
/// The tets are stored as written: orientation and degeneracy are not checked here (call
/// ValidateTetMesh). Returns false and fills *error with "<path>: <defect>" or
/// "<path>: line <n>: <defect>" on failure: missing or empty file, unknown extension, binary or
/// unsupported format version, malformed or truncated line, duplicate node, a tet referencing a
/// node that does not exist, no tets.
bool ReadTetMeshFile(const std::string& path, TetMesh* mesh, std::string* error);

/// Writes `mesh` as a Gmsh 2.2 ASCII file (node tags and element tags 1-based, one type-4
/// element per tet, physical and elementary tag 1, coordinates with round-trip precision).
/// Returns false with "<path>: cannot write file" in *error if the file cannot be written.
bool WriteGmsh22(const TetMesh& mesh, const std::string& path, std::string* error);

/// Checks that `mesh` can be simulated: at least one tet, finite coordinates, vertex indices in
/// range, no vertex repeated within a tet, and every tet positively oriented with a signed volume
/// above 1e-12 × (bounding-box diagonal)^3. Returns false and fills *error, prefixed with `name`
/// (e.g. the file name), for the first offending tet (lowest index) together with how many tets
/// are affected, e.g. "NAME: tet T is degenerate (volume V); ..." (|V| at most the tolerance) or
/// "NAME: tet T is inverted (signed volume V < 0); ..." (below minus the tolerance).
/// Vertices used by no tet are allowed.
bool ValidateTetMesh(const TetMesh& mesh, const std::string& name, std::string* error);

/// Boundary of the mesh: the tet faces that belong to exactly one tet, oriented counter-clockwise
/// seen from outside (outward normal by the right-hand rule) for positively oriented tets (an
/// inverted tet yields its faces inward). Ordered by tet index, then by local face index k
/// (face k is the face opposite tets[t][k]). Faces shared by three or more tets (a non-manifold
/// mesh) are not boundary faces. Indices refer to mesh.vertices.
std::vector<Eigen::Vector3i> BoundaryFaces(const TetMesh& mesh);

/// Structured box centred at the origin with the given half extents [m] and cells.x() ×
/// cells.y() × cells.z() hexahedral cells (components below 1 are treated as 1), each split into 6
/// tets along its (−,−,−)→(+,+,+) diagonal (Kuhn / Freudenthal split, the same in every cell, so
/// the mesh is conforming). All tets positively oriented; vertices on the box faces are exactly at
/// ±halfExtents. Vertex (i, j, k) of the lattice has index i + (nx + 1) (j + (ny + 1) k).
TetMesh MakeTetBox(const Eigen::Vector3d& halfExtents, const Eigen::Vector3i& cells);

/// Bounds on one meshing run (the defaults are geometry/mesh_limits.h's).
struct MeshingLimits {
  /// The largest tet count accepted, estimated from the enclosed volume before meshing.
  double maxTets = limits::kMaxMesherTets;
  /// The wall-clock budget [s] of the run; negative: limits::kMesherMinSeconds +
  /// limits::kMesherSecondsPerTet per estimated tet.
  double seconds = -1.0;
};

/// Tetrahedralizes the solid bounded by a closed surface (either orientation) with CGAL Mesh_3 (a
/// polyhedral domain, Delaunay refinement, then sliver perturbation and exudation run to
/// completion). Criteria, with h = edgeLength [m]: facet_size = cell_size = h (upper bounds on
/// surface Delaunay ball and tet circumradii), facet_distance = h/20, facet_angle = 25°,
/// cell_radius_edge_ratio = 3; surface vertices lie on the input surface. The result keeps only the
/// vertices of the tets, all tets positively oriented; mean edge length about 1.3 h. The boundary
/// is made of chords of the surface, so curved solids lose volume: a sphere of radius 3.3 h about
/// 5 %, of radius 6.7 h about 2 %. Deterministic: same input, same output (fixed random seed; the
/// time budget only ever fails a run). A surface far from unit scale is meshed in normalized
/// coordinates (geometry/mesher_input.h). Returns false and fills *error ("MeshTetsFromSurface:
/// <defect>") if edgeLength is not positive and finite, the surface is empty, has an index out of
/// range or a non-finite coordinate, is not closed (an edge not shared by exactly two faces, or two
/// faces traversing it in the same direction), is non-manifold at a vertex, encloses no volume,
/// would need more than `bounds.maxTets` tets, or Mesh_3 fails, produces no tets, or is stopped
/// ("CGAL Mesh_3 stopped: ...") because a stage ran past the time or vertex budget.
/// Self-intersections are not detected (a self-touching surface ends at the budget).
bool MeshTetsFromSurface(const TriangleMesh& surface, double edgeLength, TetMesh* out,
                         std::string* error, const MeshingLimits& bounds = MeshingLimits());

/// A mesh size h(x) [m] as a function of the position x [m].
using MeshSizeField = std::function<double(const Eigen::Vector3d&)>;

/// MeshTetsFromSurface with a position-dependent mesh size: facet_size = cell_size = h(x) and
/// facet_distance = h(x)/20 at the Delaunay ball or circumcentre x (the other criteria and
/// properties as there). Keep |∇h| below about 0.5 for well-shaped tets across the grading.
/// Fails as MeshTetsFromSurface does, also when `edgeLength` is empty, when h is not positive and
/// finite at the surface vertices or at the centres of a 24³ grid over the surface's bounding box
/// (the size guard integrates 1/h³ over that grid).
bool MeshTetsFromSurfaceSized(const TriangleMesh& surface, const MeshSizeField& edgeLength,
                              TetMesh* out, std::string* error,
                              const MeshingLimits& bounds = MeshingLimits());

/// Tet mesh of a ball of the given radius [m] centred at the origin, graded toward the surface
/// point p = radius · pole/|pole|: MeshTetsFromSurfaceSized of an icosphere subdivided until its
/// edges are at most fineEdgeLength/2 (at most 7 subdivisions) with the size
///   h(x) = min(coarseEdgeLength, fineEdgeLength + grading · max(0, |x − p| − fineRadius)) [m].
/// (For a contact patch at the pole: fine within fineRadius of it, coarse far away.) Returns an
/// empty mesh on invalid arguments (radius, fineEdgeLength, grading not positive, fineRadius
/// negative, coarseEdgeLength < fineEdgeLength, pole zero or not finite) or if meshing fails.
TetMesh MakeGradedTetSphere(double radius, const Eigen::Vector3d& pole, double fineEdgeLength,
                            double fineRadius, double grading, double coarseEdgeLength);

/// Tet mesh of a ball of the given radius [m] centred at the origin: MeshTetsFromSurface of an
/// icosphere subdivided until its edges are at most edgeLength/2 (at most 7 subdivisions), with
/// edgeLength [m] as the mesh size. The boundary is inscribed in the sphere (less volume than
/// 4/3 π r³, see MeshTetsFromSurface). Returns an empty mesh if radius or edgeLength is not
/// positive or meshing fails (also beyond radius/edgeLength ≈ 65, the 10-million-tet guard).
TetMesh MakeTetSphere(double radius, double edgeLength);
/// MakeTetSphere with the reason of a failure in *error and explicit bounds.
bool MeshTetSphere(double radius, double edgeLength, TetMesh* out, std::string* error,
                   const MeshingLimits& bounds = MeshingLimits());

}  // namespace superdex
