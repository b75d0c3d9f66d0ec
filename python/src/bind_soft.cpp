// Soft (tet FEM) actors: tet meshes and their generators, node constraints and SoftActorDesc.
// SoftMaterial is bound with the other parameter types (bind_params.cpp); the soft properties of
// Actor and Scene.add_soft_actor with the scene (bind_scene.cpp).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>

#include "bindings.h"
#include "core/model/soft_body.h"
#include "geometry/number_text.h"
#include "geometry/tet_mesh.h"
#include "geometry/triangle_mesh.h"

namespace superdex::python {

// TetMesh and the functions that make or read one.
void BindTetMesh(py::module_& m) {
  py::class_<TetMesh, std::shared_ptr<TetMesh>>(
      m, "TetMesh",
      "A tetrahedral mesh [m]: vertices (n, 3) and tets (m, 4) of 0-based vertex indices, every\n"
      "tet positively oriented ((x1 - x0) . ((x2 - x0) x (x3 - x0)) > 0). The array properties\n"
      "are copies: assign a whole array to change them. Make one with read_tet_mesh(),\n"
      "make_tet_box(), make_tet_sphere() or tet_mesh_from_surface(); it is validated when an\n"
      "actor is made from it (Scene.add_soft_actor).")
      .def(py::init([](const py::object& vertices, const py::object& tets) {
             auto mesh = std::make_shared<TetMesh>();
             if (!vertices.is_none()) mesh->vertices = RowsFromArray<3>(vertices, "vertices");
             if (!tets.is_none()) mesh->tets = IndexRowsFromArray<4>(tets, "tets");
             return mesh;
           }),
           py::arg("vertices") = py::none(), py::arg("tets") = py::none())
      .def_property(
          "vertices", [](const TetMesh& t) { return RowsToArray(t.vertices); },
          [](TetMesh& t, const py::object& v) { t.vertices = RowsFromArray<3>(v, "vertices"); },
          "(n, 3) float array of vertex positions [m] (a copy).")
      .def_property(
          "tets", [](const TetMesh& t) { return RowsToArray(t.tets); },
          [](TetMesh& t, const py::object& v) { t.tets = IndexRowsFromArray<4>(v, "tets"); },
          "(m, 4) int array of vertex indices per tet (a copy).")
      .def_property_readonly("num_vertices", &TetMesh::NumVertices)
      .def_property_readonly("num_tets", &TetMesh::NumTets)
      .def("__repr__", [](const TetMesh& t) {
        return "<superdex.TetMesh " + std::to_string(t.NumVertices()) + " vertices, " +
               std::to_string(t.NumTets()) + " tets>";
      });

  m.def(
      "read_tet_mesh",
      [](const std::string& path) {
        auto mesh = std::make_shared<TetMesh>();
        std::string error;
        const bool ok = WithoutGil([&] { return ReadTetMeshFile(path, mesh.get(), &error); });
        if (!ok) throw py::value_error(error);
        return mesh;
      },
      py::arg("path"),
      "Reads a Gmsh ASCII .msh (2.2 or 4.1) file or a TetGen .node/.ele pair (the extension\n"
      "chooses). Raises ValueError \"<path>: <defect>\" on failure.");
  m.def(
      "write_gmsh22",
      [](const TetMesh& mesh, const std::string& path) {
        std::string error;
        if (!WriteGmsh22(mesh, path, &error)) throw py::value_error(error);
      },
      py::arg("mesh"), py::arg("path"), "Writes the mesh as a Gmsh 2.2 ASCII file.");
  m.def(
      "make_tet_box",
      [](const Eigen::Vector3d& halfExtents, const Eigen::Vector3i& cells) {
        if (!(halfExtents.allFinite() && halfExtents.minCoeff() > 0))
          throw py::value_error("half_extents: must be finite and > 0");
        if (!(cells.minCoeff() >= 1))
          throw py::value_error("cells: must be >= 1, got [" + std::to_string(cells.x()) + ", " +
                                std::to_string(cells.y()) + ", " + std::to_string(cells.z()) +
                                "]");
        return std::make_shared<TetMesh>(MakeTetBox(halfExtents, cells));
      },
      py::arg("half_extents"), py::arg("cells"),
      "Structured box centred at the origin, half extents [hx, hy, hz] [m], cells [nx, ny, nz]\n"
      "hexahedral cells each split into 6 tets. Vertex (i, j, k) of the lattice has index\n"
      "i + (nx + 1) (j + (ny + 1) k).");
  m.def(
      "make_tet_sphere",
      [](double radius, double edgeLength) {
        if (!(std::isfinite(radius) && radius > 0))
          throw py::value_error("radius: must be finite and > 0, got " + NumberText(radius));
        if (!(std::isfinite(edgeLength) && edgeLength > 0))
          throw py::value_error("edge_length: must be finite and > 0, got " +
                                NumberText(edgeLength));
        auto mesh = std::make_shared<TetMesh>();
        {
          py::gil_scoped_release release;
          *mesh = MakeTetSphere(radius, edgeLength);
        }
        if (mesh->NumTets() == 0)
          throw py::value_error("make_tet_sphere: meshing failed (radius/edge_length = " +
                                NumberText(radius / edgeLength) +
                                "; above about 65 exceeds the 10-million-tet guard)");
        return mesh;
      },
      py::arg("radius"), py::arg("edge_length"),
      "Tet mesh of a ball centred at the origin (CGAL Mesh_3 of an icosphere) with mesh size\n"
      "edge_length [m]. The boundary is inscribed in the sphere. Deterministic.");
  m.def(
      "tet_mesh_from_surface",
      [](const py::object& vertices, const py::object& faces, double edgeLength) {
        TriangleMesh surface;
        surface.vertices = RowsFromArray<3>(vertices, "vertices");
        surface.faces = IndexRowsFromArray<3>(faces, "faces");
        auto mesh = std::make_shared<TetMesh>();
        std::string error;
        const bool ok = WithoutGil(
            [&] { return MeshTetsFromSurface(surface, edgeLength, mesh.get(), &error); });
        if (!ok) throw py::value_error(error);
        return mesh;
      },
      py::arg("vertices"), py::arg("faces"), py::arg("edge_length"),
      "Tetrahedralizes the solid bounded by a closed triangle surface (vertices (n, 3) [m],\n"
      "faces (f, 3) int) with CGAL Mesh_3, mesh size edge_length [m]. Raises ValueError\n"
      "\"MeshTetsFromSurface: <defect>\" (e.g. a surface that is not closed).");
  m.def(
      "boundary_faces", [](const TetMesh& mesh) { return RowsToArray(BoundaryFaces(mesh)); },
      py::arg("mesh"),
      "(f, 3) int array: the faces that belong to exactly one tet, counter-clockwise seen from\n"
      "outside, ordered by tet, then by local face.");
}

// NodeConstraint and SoftActorDesc.
void BindSoftActorDesc(py::module_& m) {
  py::class_<NodeConstraint>(
      m, "NodeConstraint",
      "Nodes of a soft actor whose positions are prescribed: pinned at their initial positions\n"
      "(empty path) or driven along a piecewise-linear path of displacements from them.")
      .def(py::init([](const std::vector<int>& nodes,
                       const std::vector<std::pair<double, Eigen::Vector3d>>& path) {
             NodeConstraint c;
             c.nodes = nodes;
             c.path = path;
             return c;
           }),
           py::arg("nodes") = std::vector<int>(),
           py::arg("path") = std::vector<std::pair<double, Eigen::Vector3d>>())
      .def_readwrite("nodes", &NodeConstraint::nodes,
                     "node indices of the tet mesh (a copy: assign a whole list)")
      .def_readwrite("path", &NodeConstraint::path,
                     "keyframes [(t [s], [dx, dy, dz] [m]), ...] with increasing t; empty: "
                     "pinned. Before the first keyframe the first displacement holds, after the "
                     "last the last one.")
      .def("displacement", &NodeConstraint::Displacement, py::arg("t"),
           "Displacement at time t [m] (zero when pinned).")
      .def("__repr__", [](const NodeConstraint& c) {
        return "NodeConstraint(" + std::to_string(c.nodes.size()) + " nodes, " +
               (c.path.empty() ? std::string("pinned")
                               : std::to_string(c.path.size()) + " keyframes") +
               ")";
      });

  py::class_<NodeLoad>(m, "NodeLoad",
                       "A dead load on nodes: each node carries the force f(t) [N], keyframes\n"
                       "[(t [s], [fx, fy, fz] [N]), ...] linear in between (one keyframe: constant).")
      .def(py::init([](const std::vector<int>& nodes,
                       const std::vector<std::pair<double, Eigen::Vector3d>>& force) {
             NodeLoad l;
             l.nodes = nodes;
             l.force = force;
             return l;
           }),
           py::arg("nodes"), py::arg("force"))
      .def_readwrite("nodes", &NodeLoad::nodes, "node indices (a copy: assign a whole list)")
      .def_readwrite("force", &NodeLoad::force,
                     "keyframes [(t [s], [fx, fy, fz] [N]), ...] with increasing t");

  py::class_<SkinBinding>(
      m, "SkinBinding",
      "A soft skin's binding to a link of its skeleton (the articulated actor given as the soft\n"
      "actor's parent): the nodes it selects move with the link (eliminated dofs), the union\n"
      "of the listed nodes, those inside the region (min, max) of the link frame [m], and those\n"
      "within shape_distance [m] of the link's collision shapes (< 0: not used), at the\n"
      "configuration the skin is added in. Validated by Scene.add_soft_actor.")
      .def(py::init([](const std::string& link, const std::vector<int>& nodes,
                       const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& region,
                       double shapeDistance) {
             SkinBinding b;
             b.link = link;
             b.nodes = nodes;
             if (region) {
               b.hasRegion = true;
               b.regionMin = region->first;
               b.regionMax = region->second;
             }
             b.shapeDistance = shapeDistance;
             return b;
           }),
           py::arg("link"), py::arg("nodes") = std::vector<int>(), py::arg("region") = py::none(),
           py::arg("shape_distance") = -1.0)
      .def_readwrite("link", &SkinBinding::link, "the link's name")
      .def_readwrite("nodes", &SkinBinding::nodes, "node indices (a copy: assign a whole list)")
      .def_property(
          "region",
          [](const SkinBinding& b) -> std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> {
            if (!b.hasRegion) return std::nullopt;
            return std::make_pair(b.regionMin, b.regionMax);
          },
          [](SkinBinding& b, const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& r) {
            b.hasRegion = r.has_value();
            if (r) {
              b.regionMin = r->first;
              b.regionMax = r->second;
            }
          },
          "(min, max) of a box in the link frame [m], or None")
      .def_readwrite("shape_distance", &SkinBinding::shapeDistance,
                     "bind the nodes within this distance of the link's shapes [m]; < 0: not used")
      .def("__repr__", [](const SkinBinding& b) {
        return "SkinBinding('" + b.link + "', " + std::to_string(b.nodes.size()) + " nodes" +
               (b.hasRegion ? ", region" : "") +
               (b.shapeDistance >= 0 ? ", shape_distance " + std::to_string(b.shapeDistance) : "") +
               ")";
      });

  py::class_<SoftActorDesc> desc(
      m, "SoftActorDesc",
      "What a soft (tet FEM) actor is made from. The tet mesh is the rest shape in its own\n"
      "frame; position and orientation place it in the world; every free node starts with\n"
      "velocity (the name RigidActorDesc and scene files use). Units: m, m/s, Pa, kg/m^3.\n"
      "Validated by Scene.add_soft_actor.");
  desc.def(py::init([](const std::string& name, const std::shared_ptr<TetMesh>& mesh,
                       const SoftMaterial& material) {
             SoftActorDesc d;
             d.name = name;
             d.mesh = mesh;
             d.material = material;
             return d;
           }),
           py::arg("name"), py::arg("mesh") = py::none(), py::arg("material") = SoftMaterial())
      .def_readwrite("name", &SoftActorDesc::name)
      .def_property(
          "mesh", [](const SoftActorDesc& d) { return std::const_pointer_cast<TetMesh>(d.mesh); },
          [](SoftActorDesc& d, const std::shared_ptr<TetMesh>& mesh) { d.mesh = mesh; },
          "TetMesh (rest shape, shared, not copied until the actor is added) or None")
      .def_readwrite("mesh_source", &SoftActorDesc::meshSource,
                     "the mesh's file or generator, for messages")
      .def_readwrite("position", &SoftActorDesc::position, "mesh frame origin [m]");
  DefOrientation(desc, "quaternion [x, y, z, w] of the mesh frame");
  desc.def_readwrite("velocity", &SoftActorDesc::linearVelocity,
                     "initial velocity of every free node [m/s]")
      .def_readwrite("material", &SoftActorDesc::material, "SoftMaterial")
      .def_readwrite("contact", &SoftActorDesc::contact, "ContactParams")
      .def_readwrite("collider_type", &SoftActorDesc::colliderType,
                     "None (default: colliding only), or Sdf / Auto (experimental: also a "
                     "collider, a grid SDF of the reference surface mapped by the deformation)")
      .def_readwrite("grid_sdf", &SoftActorDesc::gridSdf, "GridSdfParams for an Sdf collider")
      .def_readwrite("boundary_element_type", &SoftActorDesc::boundaryElementType,
                     "surface quadrature per boundary face. Default P1Q3.")
      .def_readwrite("contact_layer", &SoftActorDesc::contactLayer)
      .def_readwrite("constraints", &SoftActorDesc::constraints,
                     "list of NodeConstraint (a copy: assign a whole list)")
      .def_readwrite("skin", &SoftActorDesc::skin,
                     "list of SkinBinding (a copy: assign a whole list); non-empty: a "
                     "soft-skinned actor, added with its skeleton (an articulated actor) as "
                     "parent");
}

}  // namespace superdex::python
