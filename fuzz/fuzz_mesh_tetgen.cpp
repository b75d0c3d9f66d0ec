// Fuzz target: the TetGen tet mesh reader (ReadTetMeshFile on a .node / .ele pair). The input is
// the .node file, a NUL byte, then the .ele file (no NUL: an empty .ele file).
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz/fuzz_input.h"
#include "geometry/tet_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const void* nul = std::memchr(data, 0, size);
  const size_t nodeSize = nul ? static_cast<const uint8_t*>(nul) - data : size;
  const size_t eleStart = nul ? nodeSize + 1 : size;
  const std::string path = superdex::fuzz::WriteInput(data, nodeSize, "tetgen", "node");
  superdex::fuzz::WriteInput(data + eleStart, size - eleStart, "tetgen", "ele");
  superdex::fuzz::RequireReadMessage(superdex::ReadTetMeshFile, path);
  return 0;
}
