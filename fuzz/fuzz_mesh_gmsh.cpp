// Fuzz target: the Gmsh tet mesh reader, formats 2.2 and 4.1 (ReadTetMeshFile on a .msh file).
#include <cstdint>
#include <string>

#include "fuzz/fuzz_input.h"
#include "geometry/tet_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = superdex::fuzz::WriteInput(data, size, "mesh", "msh");
  superdex::TetMesh mesh;
  std::string error;
  superdex::fuzz::RequireMessage(superdex::ReadTetMeshFile(path, &mesh, &error), error);
  return 0;
}
