// The error out-parameter of the public API (spec: "..., error)"). Nothing throws across the API.
#pragma once

#include <string>

namespace superdex {

struct Error {
  std::string message;  ///< empty when no error occurred
  bool ok() const { return message.empty(); }
};

/// Stores `message` in *error (if given) and returns false, for `return Fail(error, "...");`.
inline bool Fail(Error* error, std::string message) {
  if (error) error->message = std::move(message);
  return false;
}

}  // namespace superdex
