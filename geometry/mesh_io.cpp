#include "geometry/mesh_io.h"

#include <algorithm>
#include <cctype>

#include "geometry/mesh_readers.h"

namespace superdex {

bool ReadMeshFile(const std::string& path, TriangleMesh* mesh, std::string* error) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  std::string ext = dot == std::string::npos || (slash != std::string::npos && dot < slash)
                        ? std::string()
                        : path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == "obj") return ReadObj(path, mesh, error);
  if (ext == "off") return ReadOff(path, mesh, error);
  if (ext == "stl") return ReadStl(path, mesh, error);
  if (ext == "ply") return ReadPly(path, mesh, error);
  *error = path + ": unknown mesh format \"." + ext + "\" (supported: .obj, .off, .stl, .ply)";
  return false;
}

}  // namespace superdex
