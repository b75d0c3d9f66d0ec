// What both peer adapters share: the command line (--scene, --dt, --duration, ...), the record
// of the tracked body, the scene metrics (defined once here, mirrored by sweep_peers.py for
// superdex's trajectories) and the one-line JSON result.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "peer_scene.h"

namespace superdex::peers {

struct PeerOptions {
  std::string scene;
  double dt = 0.0;
  double duration = 0.0;    ///< <= 0: the scene file's
  std::string solver;       ///< engine-specific (MuJoCo: newton, cg, pgs)
  int iterations = 0;       ///< <= 0: the adapter's default
  double timeconst = 0.0;   ///< MuJoCo: > 0 replaces the matched contact time constant [s]
  std::string out;          ///< optional trajectory of the tracked body (JSON Lines)
  std::string model;        ///< MuJoCo: also write the generated MJCF model here
};

/// Parses argv; returns false (with a message) on bad input.
bool ParseOptions(int argc, char** argv, PeerOptions* options, std::string* message);

/// Parses argv and loads the scene it names; on bad input prints the reason to stderr and
/// returns false (the adapter then exits with status 2).
bool StartRun(int argc, char** argv, PeerOptions* options, PeerScene* scene);

/// State of the tracked body at the end of a step.
struct TrackSample {
  double t = 0.0;
  Eigen::Vector3d p, v, w;  ///< position, velocity, angular velocity (world)
  Eigen::Quaterniond q;
};

/// Collects the tracked body's states and the maximal penetration, then prints the result.
class Recorder {
 public:
  Recorder(const PeerScene& scene, const PeerOptions& options, std::string engine);
  /// Returns false once the state is not finite (the run should stop).
  bool Add(const TrackSample& s, double penetration);
  /// Marks the run as failed for a reason of the engine's (e.g. a full contact buffer).
  void Fail(const std::string& reason) { failure_ = reason; }
  /// Prints the JSON result line to stdout; `settings` documents the engine parameters used.
  void Print(double wallSeconds, double simulatedSeconds, const nlohmann::json& settings) const;

 private:
  const PeerScene& scene_;
  PeerOptions options_;
  std::string engine_;
  std::vector<TrackSample> track_;
  double maxPenetration_ = 0.0;
  bool nan_ = false;
  std::string failure_;
};

/// The scene's metrics from the tracked body's samples (first sample: initial state), with
/// "error" the one plotted against wall time.
nlohmann::json SceneMetrics(const PeerScene& scene, const std::vector<TrackSample>& track);

}  // namespace superdex::peers
