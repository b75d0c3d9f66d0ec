// Helpers of the scene-file tests: editing a scene text and the error loading it gives.
#pragma once

#include <catch2/catch.hpp>

#include <string>

#include "scenes/scene_file.h"

namespace superdex::test {

/// s with the first occurrence of `from` replaced by `to` (which must occur).
inline std::string Replace(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

/// The error message of loading `text` (meshes relative to baseDir), or "<loaded>".
inline std::string LoadError(const std::string& text, const std::string& baseDir = ".") {
  SceneFile f;
  Error e;
  return LoadSceneText(text, baseDir, &f, &e) ? "<loaded>" : e.message;
}

}  // namespace superdex::test
