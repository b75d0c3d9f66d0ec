// Fuzz target: the OBJ surface mesh reader (ReadMeshFile on a .obj file).
#include <cstdint>

#include "fuzz/fuzz_input.h"
#include "geometry/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return superdex::fuzz::FuzzMeshFile(data, size, "obj", superdex::ReadMeshFile);
}
