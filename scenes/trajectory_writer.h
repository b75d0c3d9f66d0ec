// The trajectory format (README "Trajectory format"): JSON Lines, one header line, then one line
// per output frame.
#pragma once

#include <fstream>
#include <string>

#include "core/scene.h"

namespace superdex {

class TrajectoryWriter {
 public:
  /// Opens `path` (creating parent folders) and writes the header line.
  bool Open(const std::string& path, const Scene& scene, const std::vector<std::string>& names,
            double dt, Error* error);
  /// Writes one frame: time, every actor's pose and velocity, energies, step statistics.
  void WriteFrame(Scene& scene, int step, const StepReport* report);
  bool IsOpen() const { return out_.is_open(); }

 private:
  std::ofstream out_;
};

}  // namespace superdex
