// The trajectory format (docs/trajectory-format.md): JSON Lines, one header line, then one line
// per output frame. Every line is flushed as it is written, so a killed run leaves complete
// lines up to its last frame; a failed write is an error.
#pragma once

#include <cstdio>
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
  TrajectoryWriter() = default;
  TrajectoryWriter(const TrajectoryWriter&) = delete;
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;
  ~TrajectoryWriter();

  /// Opens `path` (creating parent folders) and writes the header line: settings and every
  /// actor with its shape (rigid) or boundary surface (soft).
  bool Open(const std::string& path, const Scene& scene, const std::vector<std::string>& names,
            double dt, Error* error, const TrajectoryOptions& options = TrajectoryOptions());
  /// Continues the file a checkpoint left (scenes/checkpoint.h): checks that its header line is
  /// the one Open would write, cuts it to `bytes` and appends from there. False (and *error)
  /// when it is missing, shorter, or has another header.
  bool Reopen(const std::string& path, long long bytes, const Scene& scene,
              const std::vector<std::string>& names, double dt, Error* error,
              const TrajectoryOptions& options = TrajectoryOptions());
  /// The bytes written so far (the file's length once flushed).
  long long Bytes() const;
  /// Writes and flushes one frame: time, every actor's pose and velocity (soft: also the
  /// boundary nodes' positions), energies, step statistics and, if asked for, the contact
  /// samples. False (and *error, with the system's reason) when the write fails.
  bool WriteFrame(Scene& scene, long long step, const StepReport* report, Error* error);
  /// Closes the file; false (and *error) when the last data cannot be written.
  bool Close(Error* error);
  bool IsOpen() const { return file_ != nullptr; }

 private:
  bool WriteLine(const std::string& line, Error* error);
  // The header line (settings, actors); sets options_ and surfaceNodes_.
  std::string Header(const Scene& scene, const std::vector<std::string>& names, double dt,
                     const TrajectoryOptions& options);
  std::FILE* file_ = nullptr;
  std::string path_;
  TrajectoryOptions options_;
  /// Per actor (empty for rigid ones): the soft boundary's nodes, in the header's order.
  std::vector<std::vector<int>> surfaceNodes_;
};

}  // namespace superdex
