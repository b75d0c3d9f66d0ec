// Parsing JSON text with errors that name the place: the JSON path and the line and column of a
// number beyond double's range, or of a value nested too deeply; nlohmann's own message (which
// names line and column) for a syntax error.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace superdex {

/// Parses `text` as one JSON value into *out. False with *error set to
///   "<json path>: number <token> is out of range (line L, column C)",
///   "nested deeper than <limit> levels (line L, column C)" (limits::kMaxJsonDepth) or
///   "not valid JSON: <nlohmann's message with line and column>".
bool ParseJsonText(const std::string& text, nlohmann::json* out, std::string* error);

}  // namespace superdex
