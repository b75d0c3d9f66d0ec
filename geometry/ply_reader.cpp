// PLY surface meshes, ASCII and binary (see mesh_readers.h).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "geometry/mesh_limits.h"
#include "geometry/mesh_readers.h"
#include "geometry/polygon_soup.h"
#include "geometry/token_parsing.h"

namespace superdex {
namespace {

enum class Encoding { Ascii, LittleEndian, BigEndian };

// A value's binary type: bytes, integer or floating, signed or not.
struct Scalar {
  int size = 0;  // 0: unknown type name
  bool integer = true;
  bool isSigned = true;
};

struct Property {
  std::string name;
  Scalar type;
  bool list = false;
  Scalar count;  // lists: the type of the count
};

struct Element {
  std::string name;
  long count = 0;
  std::vector<Property> properties;
  int line = 0;  // of its "element" line
};

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  size_t dataStart = 0;  // byte offset after "end_header\n"
  int dataLine = 0;      // line number of the first data line
};

// The PLY scalar type of a name ("uchar", "float32", ...); size 0 for an unknown name.
Scalar ScalarOf(const std::string& name) {
  static const struct {
    const char* names[2];
    Scalar type;
  } kTypes[] = {{{"char", "int8"}, {1, true, true}},      {{"uchar", "uint8"}, {1, true, false}},
                {{"short", "int16"}, {2, true, true}},    {{"ushort", "uint16"}, {2, true, false}},
                {{"int", "int32"}, {4, true, true}},      {{"uint", "uint32"}, {4, true, false}},
                {{"float", "float32"}, {4, false, true}}, {{"double", "float64"}, {8, false, true}}};
  for (const auto& t : kTypes)
    if (name == t.names[0] || name == t.names[1]) return t.type;
  return Scalar{0, true, true};
}

bool ParseProperty(const std::vector<std::string>& t, Property* p, std::string* why) {
  if (t.size() == 3) {
    p->type = ScalarOf(t[1]);
    p->name = t[2];
    if (p->type.size == 0) *why = "unknown property type \"" + t[1].substr(0, 40) + "\"";
    return p->type.size != 0;
  }
  if (t.size() == 5 && t[1] == "list") {
    p->list = true;
    p->count = ScalarOf(t[2]);
    p->type = ScalarOf(t[3]);
    p->name = t[4];
    if (p->count.size == 0 || !p->count.integer) *why = "a list count must have an integer type";
    else if (p->type.size == 0) *why = "unknown property type \"" + t[3].substr(0, 40) + "\"";
    return p->count.size != 0 && p->count.integer && p->type.size != 0;
  }
  *why = "malformed property (expected \"property TYPE NAME\" or \"property list COUNT-TYPE "
         "TYPE NAME\")";
  return false;
}

bool ReadHeader(const std::string& text, PolygonSoup* soup, Header* h) {
  size_t pos = 0;
  int line = 0;
  bool haveFormat = false;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    const std::string raw = text.substr(pos, end - pos);
    pos = end + 1;
    ++line;
    std::vector<std::string> t;
    TokenLines(raw, false).Next(&t);
    const std::string place = "line " + std::to_string(line);
    if (line == 1) {
      if (t.size() != 1 || t[0] != "ply") return soup->Fail(place, "not a PLY file (no \"ply\")");
      continue;
    }
    if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
    std::string why;
    if (t[0] == "format") {
      haveFormat = true;
      if (t.size() != 3) return soup->Fail(place, "malformed format line");
      if (t[1] == "ascii") h->encoding = Encoding::Ascii;
      else if (t[1] == "binary_little_endian") h->encoding = Encoding::LittleEndian;
      else if (t[1] == "binary_big_endian") h->encoding = Encoding::BigEndian;
      else return soup->Fail(place, "unknown format \"" + t[1].substr(0, 40) + "\"");
    } else if (t[0] == "element") {
      Element e;
      e.line = line;
      if (t.size() != 3 || !ParseLong(t[2], &e.count) || e.count < 0)
        return soup->Fail(place, "malformed element line (expected \"element NAME COUNT\")");
      e.name = t[1];
      h->elements.push_back(e);
    } else if (t[0] == "property") {
      Property p;
      if (h->elements.empty()) return soup->Fail(place, "a property before any element");
      if (!ParseProperty(t, &p, &why)) return soup->Fail(place, why);
      h->elements.back().properties.push_back(p);
    } else if (t[0] == "end_header") {
      if (!haveFormat) return soup->Fail(place, "no format line before end_header");
      h->dataStart = std::min(pos, text.size());
      h->dataLine = line + 1;
      return true;
    } else {
      return soup->Fail(place, "unknown header line \"" + t[0].substr(0, 40) + "\"");
    }
  }
  return soup->Fail("", "the file ends inside the header (no end_header)");
}

// The data of the elements, one value at a time, from ASCII lines or binary bytes.
class DataReader {
 public:
  DataReader(const std::string& text, const Header& h, PolygonSoup* soup)
      : text_(text), h_(h), soup_(soup), lines_(text_, false, h.dataLine, h.dataStart), pos_(h.dataStart) {}

  // Starts item `index` of element e (ASCII: reads its line).
  bool BeginItem(const Element& e, long index) {
    place_ = e.name + " " + std::to_string(index);
    next_ = 0;
    if (h_.encoding != Encoding::Ascii) return true;
    if (!lines_.Next(&tokens_))
      return soup_->Fail(place_, "the file ends (" + std::to_string(e.count) + " declared)");
    place_ = lines_.Place();
    return true;
  }
  // The next value of the item, of type `type`.
  bool Value(const Scalar& type, double* v) {
    if (h_.encoding == Encoding::Ascii) {
      if (next_ >= tokens_.size()) return soup_->Fail(place_, "too few values on the line");
      const std::string& tok = tokens_[next_++];
      long l = 0;
      if (type.integer ? !ParseLong(tok, &l) : !ParseDouble(tok, v))
        return soup_->Fail(place_, "malformed " +
                                       std::string(type.integer ? "integer" : "number") + " \"" +
                                       tok.substr(0, 40) + "\"");
      if (type.integer) *v = static_cast<double>(l);
      return true;
    }
    const size_t size = static_cast<size_t>(type.size);
    if (text_.size() - pos_ < size)
      return soup_->Fail(place_, "the file ends inside it (binary data truncated)");
    unsigned char b[8];
    std::memcpy(b, text_.data() + pos_, size);
    pos_ += size;
    if (h_.encoding == Encoding::BigEndian)
      for (size_t k = 0; k < size / 2; ++k) std::swap(b[k], b[size - 1 - k]);
    *v = Decode(b, type);
    return true;
  }
  // Bytes (binary) or values (ASCII) left, to bound a list's count.
  double Left() const {
    return h_.encoding == Encoding::Ascii ? double(tokens_.size() - next_)
                                          : double(text_.size() - pos_);
  }
  const std::string& Place() const { return place_; }

 private:
  // The value of little-endian bytes (the host is little endian).
  static double Decode(const unsigned char* b, const Scalar& type) {
    const int size = type.size;
    if (!type.integer) {
      if (size == 4) {
        float f;
        std::memcpy(&f, b, 4);
        return f;
      }
      double d;
      std::memcpy(&d, b, 8);
      return d;
    }
    int64_t v = 0;
    std::memcpy(&v, b, size);
    const int64_t sign = int64_t(1) << (8 * size - 1);
    if (type.isSigned && (v & sign)) v -= sign << 1;  // sign-extend
    return static_cast<double>(v);
  }

  const std::string& text_;
  const Header& h_;
  PolygonSoup* soup_;
  TokenLines lines_;
  size_t pos_;
  std::vector<std::string> tokens_;
  size_t next_ = 0;
  std::string place_;
};

bool ReadElements(const std::string& text, const Header& h, PolygonSoup* soup) {
  DataReader r(text, h, soup);
  std::vector<long long> corners;
  for (const Element& e : h.elements) {
    const bool vertex = e.name == "vertex", face = e.name == "face";
    int xyz[3] = {-1, -1, -1}, indices = -1;
    for (size_t k = 0; k < e.properties.size(); ++k) {
      const Property& p = e.properties[k];
      for (int a = 0; a < 3; ++a)
        if (vertex && !p.list && p.name == std::string(1, char('x' + a))) xyz[a] = int(k);
      if (face && p.list && (p.name == "vertex_indices" || p.name == "vertex_index"))
        indices = int(k);
    }
    const std::string place = "line " + std::to_string(e.line);
    if (vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0))
      return soup->Fail(place, "element vertex has no x, y and z properties");
    if (face && indices < 0)
      return soup->Fail(place, "element face has no list property vertex_indices");
    if (face && !e.properties[indices].type.integer)
      return soup->Fail(place, "vertex_indices must be a list of integers");
    for (long i = 0; i < e.count; ++i) {
      if (!r.BeginItem(e, i)) return false;
      double x[3] = {0, 0, 0};
      for (size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        double v = 0;
        if (!p.list) {
          if (!r.Value(p.type, &v)) return false;
          for (int a = 0; a < 3; ++a)
            if (int(k) == xyz[a]) x[a] = v;
          continue;
        }
        double n = 0;
        if (!r.Value(p.count, &n)) return false;
        if (n < 0 || n * (h.encoding == Encoding::Ascii ? 1 : p.type.size) > r.Left())
          return soup->Fail(r.Place(), "a list of " + std::to_string(long(n)) +
                                           " values does not fit in the rest of the data");
        if (int(k) == indices) corners.clear();
        for (long c = 0; c < long(n); ++c) {
          if (!r.Value(p.type, &v)) return false;
          if (int(k) == indices) corners.push_back(static_cast<long long>(v));
        }
      }
      if (vertex && !soup->AddVertex(x[0], x[1], x[2], r.Place())) return false;
      if (face && !soup->AddPolygon(corners, r.Place())) return false;
    }
  }
  return true;
}

}  // namespace

bool ReadPly(const std::string& path, TriangleMesh* mesh, std::string* error) {
  PolygonSoup soup(path, error);
  std::string text;
  if (!soup.ReadNonEmptyFile(&text)) return false;
  Header h;
  if (!ReadHeader(text, &soup, &h)) return false;
  const double bytes = static_cast<double>(text.size());
  for (const Element& e : h.elements) {
    double itemBytes = 0;  // the least an item takes: ASCII 2 per value, binary its sizes
    for (const Property& p : e.properties)
      itemBytes += h.encoding == Encoding::Ascii ? 2 : (p.list ? p.count.size : p.type.size);
    if (e.count > 0 && e.properties.empty())
      return soup.Fail("line " + std::to_string(e.line),
                       "element " + e.name + " declares items but no properties");
    const double limit = e.name == "vertex" ? limits::kMaxMeshVertices : limits::kMaxMeshElements;
    const std::string m = limits::CheckDeclaredCount(e.count, limit, itemBytes, bytes,
                                                     "items of element " + e.name);
    if (!m.empty()) return soup.Fail("line " + std::to_string(e.line), m);
  }
  return ReadElements(text, h, &soup) && soup.Finish(mesh);
}

}  // namespace superdex
