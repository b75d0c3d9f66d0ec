// Shell actors: ShellActorDesc and Scene.add_shell_actor (core/model/shell_kind.h).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>

#include "actor.h"
#include "bindings.h"
#include "core/model/shell_kind.h"
#include "core/scene.h"
#include "geometry/mesh_io.h"

namespace superdex::python {

void BindShellActorDesc(py::module_& m) {
  py::class_<TriangleMesh, std::shared_ptr<TriangleMesh>>(
      m, "TriangleMesh",
      "A triangle mesh [m]: vertices (n, 3) and faces (f, 3) of 0-based vertex indices. The array\n"
      "properties are copies: assign a whole array to change them. Make one from arrays, with\n"
      "read_triangle_mesh() or make_rectangle_mesh(); a shell checks it when it is added.")
      .def(py::init([](const py::object& vertices, const py::object& faces) {
             auto mesh = std::make_shared<TriangleMesh>();
             if (!vertices.is_none()) mesh->vertices = RowsFromArray<3>(vertices, "vertices");
             if (!faces.is_none()) mesh->faces = IndexRowsFromArray<3>(faces, "faces");
             return mesh;
           }),
           py::arg("vertices") = py::none(), py::arg("faces") = py::none())
      .def_property(
          "vertices", [](const TriangleMesh& t) { return RowsToArray(t.vertices); },
          [](TriangleMesh& t, const py::object& v) { t.vertices = RowsFromArray<3>(v, "vertices"); },
          "(n, 3) float array of vertex positions [m] (a copy).")
      .def_property(
          "faces", [](const TriangleMesh& t) { return RowsToArray(t.faces); },
          [](TriangleMesh& t, const py::object& v) { t.faces = IndexRowsFromArray<3>(v, "faces"); },
          "(f, 3) int array of vertex indices per triangle (a copy).")
      .def_property_readonly("num_vertices", &TriangleMesh::NumVertices)
      .def_property_readonly("num_faces", &TriangleMesh::NumFaces)
      .def("__repr__", [](const TriangleMesh& t) {
        return "<superdex.TriangleMesh " + std::to_string(t.NumVertices()) + " vertices, " +
               std::to_string(t.NumFaces()) + " faces>";
      });
  m.def(
      "read_triangle_mesh",
      [](const std::string& path) {
        auto mesh = std::make_shared<TriangleMesh>();
        std::string error;
        if (!ReadMeshFile(path, mesh.get(), &error)) throw py::value_error(error);
        return mesh;
      },
      py::arg("path"), "Reads an OBJ, OFF, STL or PLY triangle mesh; ValueError naming the problem.");
  py::class_<ShellActorDesc> desc(
      m, "ShellActorDesc",
      "What a shell actor is made from: a triangle mesh (rest shape, a manifold, consistently\n"
      "oriented) with a thickness. position and orientation place it; every node starts with\n"
      "velocity. Units: m, m/s, Pa, kg/m^3. Validated by Scene.add_shell_actor.");
  desc.def(py::init([](const std::string& name, const std::shared_ptr<TriangleMesh>& mesh,
                       const ShellMaterial& material) {
             ShellActorDesc d;
             d.name = name;
             d.mesh = mesh;
             d.material = material;
             return d;
           }),
           py::arg("name"), py::arg("mesh") = py::none(), py::arg("material") = ShellMaterial())
      .def_readwrite("name", &ShellActorDesc::name)
      .def_property(
          "mesh",
          [](const ShellActorDesc& d) { return std::const_pointer_cast<TriangleMesh>(d.mesh); },
          [](ShellActorDesc& d, const std::shared_ptr<TriangleMesh>& mesh) { d.mesh = mesh; },
          "TriangleMesh (rest shape) or None")
      .def_readwrite("mesh_source", &ShellActorDesc::meshSource,
                     "the mesh's file or generator, for messages")
      .def_readwrite("position", &ShellActorDesc::position, "mesh frame origin [m]");
  DefOrientation(desc, "quaternion [x, y, z, w] of the mesh frame");
  desc.def_readwrite("velocity", &ShellActorDesc::linearVelocity,
                     "initial velocity of every free node [m/s]")
      .def_readwrite("material", &ShellActorDesc::material, "ShellMaterial")
      .def_readwrite("bending", &ShellActorDesc::bending,
                     "ShellBendingModel: Midedge (default, Kirchhoff-Love) or Hinge (cloth)")
      .def_readwrite("contact", &ShellActorDesc::contact, "ContactParams")
      .def_readwrite("contact_element_type", &ShellActorDesc::contactElementType,
                     "quadrature rule per triangle of the colliding role. Default P1Q3.")
      .def_readwrite("collider_type", &ShellActorDesc::colliderType,
                     "ColliderType: Auto or PointCloud (the point cloud), or None")
      .def_readwrite("point_cloud", &ShellActorDesc::pointCloud,
                     "PointCloudColliderParams: L_B, self-contact, the collider points' rule")
      .def_readwrite("contact_layer", &ShellActorDesc::contactLayer)
      .def_readwrite("constraints", &ShellActorDesc::constraints,
                     "list of NodeConstraint (a copy: assign a whole list)")
      .def_readwrite("loads", &ShellActorDesc::loads,
                     "list of NodeLoad: dead loads on nodes (a copy: assign a whole list)")
      .def_readwrite("clamped_nodes", &ShellActorDesc::clampedNodes,
                     "pinned nodes whose edges also hold their rest normals (a copy: assign a "
                     "whole list)");
  m.def(
      "make_rectangle_mesh",
      [](const Eigen::Vector2d& size, const Eigen::Vector2i& cells) {
        if (!(size.minCoeff() > 0.0)) throw py::value_error("size: must be > 0 in both components");
        if (!(cells.minCoeff() >= 1)) throw py::value_error("cells: must be >= 1 in both components");
        return std::make_shared<TriangleMesh>(MakeRectangleMesh(-0.5 * size, 0.5 * size, cells));
      },
      py::arg("size"), py::arg("cells"),
      "A rectangle of size [a, b] [m] centred at the origin in the z = 0 plane, cells [nx, ny]\n"
      "quads split in two triangles each (vertex (i, j) has index i + (nx + 1) j).");
  m.def(
      "make_disk_mesh",
      [](double radius, int rings) {
        if (!(radius > 0.0)) throw py::value_error("radius: must be > 0");
        if (rings < 1 || rings > 500) throw py::value_error("rings: must be in [1, 500]");
        return std::make_shared<TriangleMesh>(MakeDiskMesh(radius, rings));
      },
      py::arg("radius"), py::arg("rings"),
      "A disk of `radius` [m] about the origin in the z = 0 plane: a centre vertex and `rings`\n"
      "rings of 6k vertices (nearly equilateral triangles).");
  m.def(
      "make_annulus_mesh",
      [](double inner, double outer, const Eigen::Vector2i& cells, double angle) {
        if (!(inner > 0.0 && outer > inner)) throw py::value_error("radii: must be 0 < inner < outer");
        if (!(angle > 0.0 && angle <= 2.0 * M_PI)) throw py::value_error("angle: must be in (0, 2 pi]");
        if (!(cells.minCoeff() >= 1)) throw py::value_error("cells: must be >= 1 in both components");
        return std::make_shared<TriangleMesh>(MakeAnnulusMesh(inner, outer, angle, cells));
      },
      py::arg("inner_radius"), py::arg("outer_radius"), py::arg("cells"),
      py::arg("angle") = 2.0 * M_PI,
      "An annular sector in the z = 0 plane: radii [m], cells [radial, angular], angles [0, angle]\n"
      "[rad]; at 2 pi an annulus with a slit (its two sides separate vertices).");
}

void BindShellMethods(py::class_<Scene>& scene) {
  scene.def(
      "add_shell_actor",
      [](Scene& s, const ShellActorDesc& d, std::optional<Actor> parent) {
        Error e;
        std::unique_ptr<ShellKind> kind = ShellKind::Build(d, &e);
        const ActorHandle h =
            kind ? s.AddActor(std::move(kind), &e, d.contactLayer,
                              parent ? parent->Handle() : ActorHandle())
                 : ActorHandle();
        if (!h.IsValid()) throw py::value_error(e.message);
        return Actor{&s, h.index};
      },
      py::arg("desc"), py::arg("parent") = py::none(), py::keep_alive<0, 1>(),
      "Adds a shell actor (nested under `parent` if given); raises ValueError naming the field\n"
      "and the rule on bad input. The mesh is copied.");
}

}  // namespace superdex::python
