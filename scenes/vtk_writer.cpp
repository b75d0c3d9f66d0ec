#include "scenes/vtk_writer.h"

#include "core/model/articulated_kind.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace superdex {
namespace {

struct Surface {
  std::vector<Eigen::Vector3d> points, displacement;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<Eigen::Vector3d> traction;  // per reference area (nominal)
  std::vector<double> referenceArea;
  std::vector<int> actor;

  void AddRigid(const TriangleMesh& mesh, const Eigen::Vector3d& offset, const RigidBodyState& s,
                int index) {
    const int base = static_cast<int>(points.size());
    for (const Eigen::Vector3d& v : mesh.vertices) {
      points.push_back(s.p + s.R * (v - offset));
      displacement.push_back(Eigen::Vector3d::Zero());
    }
    for (const Eigen::Vector3i& f : mesh.faces) {
      triangles.push_back(f + Eigen::Vector3i::Constant(base));
      traction.push_back(Eigen::Vector3d::Zero());
      referenceArea.push_back(0.0);
      actor.push_back(index);
    }
  }
};

void WriteVector(std::ofstream& out, const Eigen::Vector3d& v) {
  out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
}

// Writes `path` through write(stream) into path.part, renamed when complete (a killed run
// leaves no partial file); false with the reason when it cannot be written.
template <typename Write>
bool WriteAtomically(const std::string& path, Error* error, Write&& write) {
  std::error_code ec;
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
  const std::string part = path + ".part";
  errno = 0;
  std::ofstream out(part);
  if (!out)
    return Fail(error, "vtk: cannot write \"" + path + "\": " +
                           (errno ? std::strerror(errno) : "open failed"));
  out.precision(9);
  write(out);
  errno = 0;
  out.close();
  if (!out || std::rename(part.c_str(), path.c_str()) != 0) {
    const std::string why = errno ? std::strerror(errno) : "write error";
    std::remove(part.c_str());
    return Fail(error, "vtk: writing \"" + path + "\" failed: " + why);
  }
  return true;
}

}  // namespace

bool WriteVtkFrame(Scene& scene, const std::string& path, Error* error) {
  Surface s;
  std::vector<ContactSampleRecord> records;  // a kind's surface's samples (read once)
  bool recorded = false;
  for (int i = 0; i < scene.NumActors(); ++i) {
    const ActorHandle h{i};
    if (scene.IsSoft(h)) {
      const SoftBodyModel& m = scene.SoftModel(h);
      const Eigen::VectorXd& x = scene.SoftState(h).x;
      std::vector<Eigen::Vector3d> t;
      if (!scene.SoftFaceTractions(h, &t, error)) return false;
      const int base = static_cast<int>(s.points.size());
      for (int a = 0; a < m.NumNodes(); ++a) {
        s.points.push_back(x.segment<3>(3 * a));
        s.displacement.push_back(x.segment<3>(3 * a) - m.rest.vertices[a]);
      }
      for (size_t f = 0; f < m.faces.size(); ++f) {
        s.triangles.push_back(m.faces[f] + Eigen::Vector3i::Constant(base));
        s.traction.push_back(t[f]);
        s.referenceArea.push_back(m.faceArea[f]);
        s.actor.push_back(i);
      }
      continue;
    }
    if (const std::vector<Eigen::Vector3i>* tri = scene.Kind(h).SurfaceTriangles()) {
      // A kind's triangles (a shell's): its samples' contact tractions (normal, friction and
      // damping) per reference area of their face, displacements from its reference shape.
      const Eigen::VectorXd& x = scene.KindStateOf(h).x;
      const Eigen::VectorXd* ref = scene.Kind(h).ReferenceConfiguration();
      const Eigen::VectorXd& x0 = ref ? *ref : scene.Kind(h).InitialState().x;
      const int base = static_cast<int>(s.points.size());
      for (Eigen::Index a = 0; a < x.size() / 3; ++a) {
        s.points.push_back(x.segment<3>(3 * a));
        s.displacement.push_back(x.segment<3>(3 * a) - x0.segment<3>(3 * a));
      }
      if (!recorded) records = scene.ContactSamples();
      recorded = true;
      const size_t first = s.traction.size();
      for (const Eigen::Vector3i& f : *tri) {
        s.triangles.push_back(f + Eigen::Vector3i::Constant(base));
        s.traction.push_back(Eigen::Vector3d::Zero());
        const Eigen::Vector3d a = x0.segment<3>(3 * f[0]), b = x0.segment<3>(3 * f[1]),
                              c = x0.segment<3>(3 * f[2]);
        s.referenceArea.push_back(0.5 * (b - a).cross(c - a).norm());
        s.actor.push_back(i);
      }
      for (const ContactSampleRecord& r : records)
        if (r.colliding == i && r.face >= 0 && r.face < static_cast<int>(tri->size()))
          s.traction[first + r.face] +=
              r.weight * (r.traction + r.friction + r.damping) / s.referenceArea[first + r.face];
      continue;
    }
    if (const auto* art = dynamic_cast<const ArticulatedKind*>(&scene.Kind(h))) {
      // The links' shapes are actors of their own; without any, each massive link is drawn as
      // a sphere of its RMS radius about its centre of mass.
      if (!scene.AttachedActors(h).empty()) continue;
      const Eigen::VectorXd& q = scene.KindStateOf(h).x;
      const std::vector<RigidPose> poses = art->LinkPoses(q);
      for (int l = 0; l < art->NumLinks(); ++l) {
        if (!(art->LinkRadius(l) > 0.0)) continue;
        RigidBodyState st;
        st.R = poses[l].R;
        st.p = art->LinkCenter(q, l);
        s.AddRigid(MakeIcosphere(art->LinkRadius(l), 2), Eigen::Vector3d::Zero(), st, i);
      }
      continue;
    }
    if (!scene.BodyModel(h)) continue;  // a kind the writer cannot draw
    const RigidBodyModel& m = *scene.BodyModel(h);
    const RigidBodyState st = scene.BodyState(h);
    switch (m.shape.kind) {
      case RigidShapeKind::Sphere:
        s.AddRigid(MakeIcosphere(m.shape.radius, 3), Eigen::Vector3d::Zero(), st, i);
        break;
      case RigidShapeKind::Box:
        s.AddRigid(MakeBoxMesh(m.shape.halfExtents, 1), Eigen::Vector3d::Zero(), st, i);
        break;
      case RigidShapeKind::Capsule:
        s.AddRigid(MakeCapsuleDrawing(m.shape.radius, m.shape.halfLength),
                   Eigen::Vector3d::Zero(), st, i);
        break;
      case RigidShapeKind::Mesh: s.AddRigid(*m.shape.mesh, m.shapeOffset, st, i); break;
      case RigidShapeKind::Plane: break;
    }
  }

  return WriteAtomically(path, error, [&](std::ofstream& out) {
  out << "# vtk DataFile Version 3.0\nsuperdex frame t = " << scene.Time()
      << " s\nASCII\nDATASET POLYDATA\n";
  out << "POINTS " << s.points.size() << " double\n";
  for (const auto& v : s.points) out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  out << "POLYGONS " << s.triangles.size() << ' ' << 4 * s.triangles.size() << '\n';
  for (const auto& f : s.triangles) out << "3 " << f.x() << ' ' << f.y() << ' ' << f.z() << '\n';
  out << "CELL_DATA " << s.triangles.size() << "\nVECTORS traction double\n";
  for (const auto& t : s.traction) out << t.x() << ' ' << t.y() << ' ' << t.z() << '\n';
  out << "SCALARS pressure double 1\nLOOKUP_TABLE default\n";
  for (size_t f = 0; f < s.triangles.size(); ++f) {
    // True pressure: the face's normal force over its current area.
    const Eigen::Vector3i& F = s.triangles[f];
    const Eigen::Vector3d a =
        0.5 * (s.points[F[1]] - s.points[F[0]]).cross(s.points[F[2]] - s.points[F[0]]);
    const double area = a.norm();
    out << (area > 0 ? -s.traction[f].dot(a / area) * s.referenceArea[f] / area : 0.0) << '\n';
  }
  out << "SCALARS actor int 1\nLOOKUP_TABLE default\n";
  for (int a : s.actor) out << a << '\n';
  out << "POINT_DATA " << s.points.size() << "\nVECTORS displacement double\n";
  for (const auto& d : s.displacement) out << d.x() << ' ' << d.y() << ' ' << d.z() << '\n';
  });
}

bool WriteVtkContacts(Scene& scene, const std::string& path, Error* error) {
  const std::vector<ContactSampleRecord> records = scene.ContactSamples();
  const size_t n = records.size();
  return WriteAtomically(path, error, [&](std::ofstream& out) {
    out << "# vtk DataFile Version 3.0\nsuperdex contact samples t = " << scene.Time()
        << " s\nASCII\nDATASET POLYDATA\nPOINTS " << n << " double\n";
    for (const ContactSampleRecord& r : records) WriteVector(out, r.position);
    out << "VERTICES " << n << ' ' << 2 * n << '\n';
    for (size_t i = 0; i < n; ++i) out << "1 " << i << '\n';
    out << "POINT_DATA " << n << '\n';
    auto vectors = [&](const char* name, auto value) {
      out << "VECTORS " << name << " double\n";
      for (const ContactSampleRecord& r : records) WriteVector(out, value(r));
    };
    auto scalars = [&](const char* name, const char* type, auto value) {
      out << "SCALARS " << name << ' ' << type << " 1\nLOOKUP_TABLE default\n";
      for (const ContactSampleRecord& r : records) out << value(r) << '\n';
    };
    vectors("normal_traction", [](const ContactSampleRecord& r) { return r.traction; });
    vectors("friction", [](const ContactSampleRecord& r) { return r.friction; });
    vectors("damping", [](const ContactSampleRecord& r) { return r.damping; });
    vectors("force", [](const ContactSampleRecord& r) {
      return Eigen::Vector3d(r.weight * (r.traction + r.friction + r.damping));
    });
    vectors("normal", [](const ContactSampleRecord& r) { return r.normal; });
    scalars("phi", "double", [](const ContactSampleRecord& r) { return r.phi; });
    scalars("weight", "double", [](const ContactSampleRecord& r) { return r.weight; });
    scalars("colliding", "int", [](const ContactSampleRecord& r) { return r.colliding; });
    scalars("collider", "int", [](const ContactSampleRecord& r) { return r.collider; });
  });
}

}  // namespace superdex
