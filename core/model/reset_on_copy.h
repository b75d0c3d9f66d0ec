// A flag that a copy does not inherit: the copy starts false (e.g. "configured for this object's
// own members", which a copy must redo because the configuration holds pointers to them).
#pragma once

namespace superdex {

struct ResetOnCopy {
  bool value = false;
  ResetOnCopy() = default;
  ResetOnCopy(const ResetOnCopy&) {}
  ResetOnCopy& operator=(const ResetOnCopy&) {
    value = false;
    return *this;
  }
  ResetOnCopy& operator=(bool v) {
    value = v;
    return *this;
  }
  operator bool() const { return value; }
};

}  // namespace superdex
