// Fuzz target: the observed-trajectory reader of `fit` and `gradient` (ReadObservedTrajectory on a
// JSON Lines file).
#include <cstdint>
#include <string>

#include "fuzz/fuzz_input.h"
#include "scenes/fit.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = superdex::fuzz::WriteInput(data, size, "observed", "jsonl");
  superdex::ObservedTrajectory observed;
  superdex::Error error;
  superdex::fuzz::RequireMessage(superdex::ReadObservedTrajectory(path, &observed, &error),
                                 error.message);
  return 0;
}
