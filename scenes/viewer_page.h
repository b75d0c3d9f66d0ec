// The viewer page: one self-contained HTML file that plays a trajectory in the browser
// (three.js, embedded; docs/viewer.md). The page's template and script are scenes/viewer/, built
// into the binary, so that the page opens from disk without a network.
#pragma once

#include <string>
#include <vector>

#include "core/model/error.h"

namespace superdex {

struct ViewerPageInfo {
  std::string path;          ///< the page written
  int frames = 0;
  int actors = 0;
  long contactSamples = 0;   ///< summed over the frames (0: the trajectory has none)
  long bytes = 0;            ///< size of the page
  std::vector<std::string> notes;  ///< what the reader skipped (a truncated last line)
};

/// Where `superdex view` and `run --view` put the page: the trajectory's path with the extension
/// replaced by ".html" (out/drop.jsonl -> out/drop.html).
std::string ViewerPagePath(const std::string& trajectoryPath);

/// Reads a trajectory (docs/trajectory-format.md) and writes the page to `pagePath`. Frames are
/// embedded as little-endian Float32 arrays in base64: the poses of every actor, the soft
/// surfaces' nodes, the contact samples (position, normal traction) and the net contact force
/// of each touching actor pair. A last line without its newline that is not valid JSON (a killed
/// run's) is skipped and noted in info->notes. The page is written whole (through a temporary
/// file and a rename). Returns false with *error naming the file, the line and the field on a bad
/// trajectory, or "view: cannot write ..." with the system's reason.
bool WriteViewerPage(const std::string& trajectoryPath, const std::string& pagePath,
                     ViewerPageInfo* info, Error* error);

}  // namespace superdex
