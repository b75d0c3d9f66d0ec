// Numbers as messages print them.
#pragma once

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

}  // namespace superdex
