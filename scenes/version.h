// The version of superdex: the CMake project's version (SUPERDEX_VERSION, set by
// scenes/CMakeLists.txt), one number for `superdex --version`, superdex.__version__, the
// trajectory header and the scene writer.
#pragma once

namespace superdex {

inline constexpr const char* kVersion = SUPERDEX_VERSION;

}  // namespace superdex
