// Numbers as messages print them.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace superdex {

/// x with `significantDigits` significant digits, as an ostream prints it (1e+09, 0.001, 2.5).
inline std::string NumberText(double x, int significantDigits = 6) {
  std::ostringstream s;
  s.precision(significantDigits);
  s << x;
  return s.str();
}

/// The shortest decimal text (15 to 17 significant digits) that reads back to exactly v.
inline std::string RoundTrip(double v) {
  char buf[40];
  for (int p = 15; p <= 17; ++p) {
    std::snprintf(buf, sizeof buf, "%.*g", p, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

}  // namespace superdex
