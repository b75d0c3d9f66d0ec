// Fuzz target: the Gmsh tet mesh reader, formats 2.2 and 4.1 (ReadTetMeshFile on a .msh file).
#include <cstdint>

#include "fuzz/fuzz_input.h"
#include "geometry/tet_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return superdex::fuzz::FuzzMeshFile(data, size, "msh", superdex::ReadTetMeshFile);
}
