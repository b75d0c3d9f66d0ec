// STL surface meshes, ASCII and binary (see mesh_readers.h).
#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "geometry/mesh_limits.h"
#include "geometry/mesh_readers.h"
#include "geometry/polygon_soup.h"
#include "geometry/token_parsing.h"

namespace superdex {
namespace {

// The soup's vertex index of a point, adding it the first time it is seen (exact equality).
class PointMerger {
 public:
  explicit PointMerger(PolygonSoup* soup) : soup_(soup) {}
  bool Index(double x, double y, double z, const std::string& place, long long* index) {
    const auto [it, added] = index_.emplace(std::array<double, 3>{x, y, z}, soup_->NumVertices());
    *index = it->second;
    return !added || soup_->AddVertex(x, y, z, place);
  }

 private:
  PolygonSoup* soup_;
  std::map<std::array<double, 3>, int> index_;
};

bool ReadBinaryStl(const std::string& text, PolygonSoup* soup) {
  uint32_t count = 0;
  std::memcpy(&count, text.data() + 80, 4);  // little endian, as the format says
  PointMerger merge(soup);
  std::vector<long long> corners(3);
  for (uint32_t i = 0; i < count; ++i) {
    const char* record = text.data() + 84 + 50 * size_t(i);  // normal, 3 corners, attribute
    const std::string place = "triangle " + std::to_string(i);
    for (int k = 0; k < 3; ++k) {
      float x[3];
      std::memcpy(x, record + 12 * (k + 1), 12);
      if (!merge.Index(x[0], x[1], x[2], place, &corners[k])) return false;
    }
    if (!soup->AddPolygon(corners, place)) return false;
  }
  return true;
}

// Expects the next line to start with `want` (e.g. "outer loop"); *t holds its tokens.
bool Expect(TokenLines* lines, PolygonSoup* soup, const std::vector<std::string>& want,
            std::vector<std::string>* t) {
  std::string words;
  for (const auto& w : want) words += (words.empty() ? "" : " ") + w;
  if (!lines->Next(t)) return soup->Fail("", "the file ends where \"" + words + "\" was expected");
  bool ok = t->size() >= want.size();
  for (size_t k = 0; ok && k < want.size(); ++k) ok = (*t)[k] == want[k];
  return ok || soup->Fail(lines->Place(), "expected \"" + words + "\", got \"" +
                                              (*t)[0].substr(0, 40) + "\"");
}

bool ReadAsciiStl(const std::string& text, PolygonSoup* soup) {
  TokenLines lines(text, false);
  std::vector<std::string> t;
  if (!Expect(&lines, soup, {"solid"}, &t)) return false;
  PointMerger merge(soup);
  std::vector<long long> corners(3);
  while (lines.Next(&t)) {
    if (t[0] == "endsolid") return true;
    if (t[0] != "facet")
      return soup->Fail(lines.Place(), "expected \"facet\" or \"endsolid\", got \"" +
                                           t[0].substr(0, 40) + "\"");
    const std::string facet = lines.Place();
    if (!Expect(&lines, soup, {"outer", "loop"}, &t)) return false;
    for (int k = 0; k < 3; ++k) {
      if (!Expect(&lines, soup, {"vertex"}, &t)) return false;
      double x[3];
      if (t.size() != 4 || !ParseDouble(t[1], &x[0]) || !ParseDouble(t[2], &x[1]) ||
          !ParseDouble(t[3], &x[2]))
        return soup->Fail(lines.Place(),
                          "malformed vertex (expected \"vertex x y z\" with finite numbers)");
      if (!merge.Index(x[0], x[1], x[2], lines.Place(), &corners[k])) return false;
    }
    if (!Expect(&lines, soup, {"endloop"}, &t) || !Expect(&lines, soup, {"endfacet"}, &t))
      return false;
    if (!soup->AddPolygon(corners, facet)) return false;
  }
  return soup->Fail("", "the file ends without \"endsolid\"");
}

}  // namespace

bool ReadStl(const std::string& path, TriangleMesh* mesh, std::string* error) {
  PolygonSoup soup(path, error);
  std::string text;
  if (!soup.ReadNonEmptyFile(&text)) return false;
  // Binary when the size matches the triangle count of the header (some binary files also
  // begin with "solid"); ASCII when it begins with "solid".
  uint32_t count = 0;
  if (text.size() >= 84) std::memcpy(&count, text.data() + 80, 4);
  const double binaryBytes = 84.0 + 50.0 * count;
  if (text.size() >= 84 && static_cast<double>(text.size()) == binaryBytes) {
    const std::string m = limits::CheckDeclaredCount(count, limits::kMaxMeshElements, 50,
                                                     double(text.size()), "triangles");
    if (!m.empty()) return soup.Fail("binary header", m);
    return ReadBinaryStl(text, &soup) && soup.Finish(mesh);
  }
  if (text.compare(0, 5, "solid") == 0) return ReadAsciiStl(text, &soup) && soup.Finish(mesh);
  if (text.size() < 84)
    return soup.Fail("", "neither ASCII (\"solid\" ...) nor binary STL (" +
                             std::to_string(text.size()) + " bytes, shorter than the 84-byte "
                                                           "binary header)");
  return soup.Fail("binary header",
                   "declares " + std::to_string(count) + " triangles, which need " +
                       std::to_string(long(binaryBytes)) + " bytes (84 + 50 per triangle), but "
                       "the file holds " + std::to_string(text.size()) + " (truncated, or not "
                       "an STL file)");
}

}  // namespace superdex
