// Fuzz target: a scene file's JSON text through the scene-file reader (LoadSceneText: parsing,
// every field's rule, building the Scene, meshing soft actors), without running it. Relative
// mesh paths resolve against the shipped scenes' folder (scenes/data).
#include <cstdint>
#include <string>

#include "fuzz/fuzz_input.h"
#include "scenes/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  superdex::SceneFile file;
  superdex::Error error;
  const bool ok = superdex::LoadSceneText(text, SUPERDEX_SOURCE_DIR "/scenes/data", &file, &error);
  superdex::fuzz::RequireMessage(ok, error.message);
  return 0;
}
