#include "scenes/json_text.h"

#include <vector>

#include "scenes/limits.h"

namespace superdex {
namespace {

using json = nlohmann::json;
using DomParser = nlohmann::detail::json_sax_dom_parser<json>;

// "line L, column C" of byte `offset` of `text` (both from 1; the column counts bytes).
std::string LineColumn(const std::string& text, size_t offset) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// The DOM parser of json::parse, plus the JSON path of the value being read and a depth limit.
class PathTrackingSax {
 public:
  explicit PathTrackingSax(json* out) : dom_(*out, false) {}

  bool null() { return Value(dom_.null()); }
  bool boolean(bool v) { return Value(dom_.boolean(v)); }
  bool number_integer(json::number_integer_t v) { return Value(dom_.number_integer(v)); }
  bool number_unsigned(json::number_unsigned_t v) { return Value(dom_.number_unsigned(v)); }
  bool number_float(json::number_float_t v, const json::string_t& s) {
    return Value(dom_.number_float(v, s));
  }
  bool string(json::string_t& v) { return Value(dom_.string(v)); }
  bool binary(json::binary_t& v) { return Value(dom_.binary(v)); }
  bool start_object(std::size_t n) { return Open(false) && dom_.start_object(n); }
  bool key(json::string_t& k) {
    frames_.back().key = k;
    return dom_.key(k);
  }
  bool end_object() { return Close(dom_.end_object()); }
  bool start_array(std::size_t n) { return Open(true) && dom_.start_array(n); }
  bool end_array() { return Close(dom_.end_array()); }
  bool parse_error(std::size_t position, const std::string& token,
                   const nlohmann::detail::exception& e) {
    offset_ = position;
    if (e.id == 406) {  // out_of_range.406: a number beyond double's range; point at its start
      offset_ = position >= token.size() ? position - token.size() : 0;
      rule_ = "number " + token + " is out of range";
    } else {
      syntax_ = e.what();
    }
    return false;
  }

  // After a failed parse: the message (see ParseJsonText).
  std::string Message(const std::string& text) const {
    if (!syntax_.empty()) return "not valid JSON: " + syntax_;
    const std::string place = Path();
    return (place.empty() ? std::string("(top level)") : place) + ": " + rule_ + " (" +
           LineColumn(text, offset_) + ")";
  }

 private:
  struct Frame {
    bool array = false;
    size_t index = 0;  // arrays: the element being read
    std::string key;   // objects: the member being read
  };
  bool Value(bool ok) {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return ok;
  }
  bool Open(bool array) {
    frames_.push_back({array, 0, ""});
    return true;
  }
  bool Close(bool ok) {
    frames_.pop_back();
    return Value(ok);
  }
  std::string Path() const {
    std::string p;
    for (const Frame& f : frames_) {
      if (f.array) p += "[" + std::to_string(f.index) + "]";
      else if (!f.key.empty()) p += (p.empty() ? "" : ".") + f.key;
    }
    return p;
  }

  DomParser dom_;
  std::vector<Frame> frames_;
  size_t offset_ = 0;
  std::string rule_, syntax_;
};

// The offset of the first '[' or '{' (outside strings) nested deeper than the limit, or npos.
// Checked before parsing, so that no deep value is built (and none recursed into later).
size_t TooDeep(const std::string& text) {
  int depth = 0;
  bool inString = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') ++i;
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limits::kMaxJsonDepth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

}  // namespace

bool ParseJsonText(const std::string& text, nlohmann::json* out, std::string* error) {
  if (const size_t at = TooDeep(text); at != std::string::npos) {
    *error = "nested deeper than " + std::to_string(limits::kMaxJsonDepth) + " levels (" +
             LineColumn(text, at) + ")";
    return false;
  }
  json result;
  PathTrackingSax sax(&result);
  bool ok = false;
  try {
    ok = json::sax_parse(text, &sax);
  } catch (const json::exception& e) {  // the DOM parser's own limits (e.g. sizes)
    *error = std::string("not valid JSON: ") + e.what();
    return false;
  }
  if (!ok) {
    *error = sax.Message(text);
    return false;
  }
  *out = std::move(result);
  return true;
}

}  // namespace superdex
