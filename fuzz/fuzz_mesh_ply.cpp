// Fuzz target: the PLY surface mesh reader (ReadMeshFile on a .ply file).
#include <cstdint>
#include <string>

#include "fuzz/fuzz_input.h"
#include "geometry/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = superdex::fuzz::WriteInput(data, size, "mesh", "ply");
  superdex::TriangleMesh mesh;
  std::string error;
  superdex::fuzz::RequireMessage(superdex::ReadMeshFile(path, &mesh, &error), error);
  return 0;
}
