// Whole-token number parsing for the mesh file readers.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace superdex {

/// Parses a whole token as a base-10 integer; false for anything else (or out of range).
inline bool ParseLong(const std::string& s, long* out) {
  if (s.empty()) return false;
  errno = 0;
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (errno != 0 || end != s.c_str() + s.size()) return false;
  *out = v;
  return true;
}

/// Parses a whole token as a finite double; false for anything else.
inline bool ParseDouble(const std::string& s, double* out) {
  if (s.empty()) return false;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (errno != 0 || end != s.c_str() + s.size() || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

}  // namespace superdex
