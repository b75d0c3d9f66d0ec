// The trajectory format (docs/trajectory-format.md): JSON Lines, one header line, then one line
// per output frame.
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "core/scene.h"

namespace superdex {

struct TrajectoryOptions {
  /// Every active contact sample in each frame (position, normal traction, force): what the
  /// viewer page colours and draws as arrows. Off by default: a pile at rest has ~80 samples per
  /// sphere.
  bool contacts = false;
};

class TrajectoryWriter {
 public:
  /// Opens `path` (creating parent folders) and writes the header line: settings and every
  /// actor with its shape (rigid) or boundary surface (soft).
  bool Open(const std::string& path, const Scene& scene, const std::vector<std::string>& names,
            double dt, Error* error, const TrajectoryOptions& options = TrajectoryOptions());
  /// Writes one frame: time, every actor's pose and velocity (soft: also the boundary nodes'
  /// positions), energies, step statistics and, if asked for, the contact samples.
  void WriteFrame(Scene& scene, int step, const StepReport* report);
  bool IsOpen() const { return out_.is_open(); }
  void Close() { out_.close(); }

 private:
  std::ofstream out_;
  TrajectoryOptions options_;
  /// Per actor (empty for rigid ones): the soft boundary's nodes, in the header's order.
  std::vector<std::vector<int>> surfaceNodes_;
};

}  // namespace superdex
