// The viewer page's files (scenes/viewer/), built into the binary by
// scenes/viewer/embed_assets.cmake: the page needs no file and no network at view time.
#pragma once

#include <string_view>

namespace superdex::viewer_assets {

std::string_view Template();  ///< viewer.html, with the markers the page writer fills in
std::string_view Script();    ///< viewer.js
std::string_view Three();     ///< vendor/three.min.js: three.js and OrbitControls, global THREE

}  // namespace superdex::viewer_assets
