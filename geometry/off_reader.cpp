// OFF surface meshes (see mesh_readers.h).
#include <string>
#include <vector>

#include "geometry/mesh_limits.h"
#include "geometry/mesh_readers.h"
#include "geometry/polygon_soup.h"
#include "geometry/token_parsing.h"

namespace superdex {

bool ReadOff(const std::string& path, TriangleMesh* mesh, std::string* error) {
  std::string text;
  if (!ReadWholeFile(path, &text, error)) return false;
  PolygonSoup soup(path, error);
  TokenLines lines(text, true);
  std::vector<std::string> t;
  if (!lines.Next(&t)) return soup.Fail("", "the file is empty (expected the OFF keyword)");
  // The keyword: [ST][C][N][4][n]OFF; the counts may follow it on the same line.
  const std::string& key = t[0];
  if (key.size() < 3 || key.compare(key.size() - 3, 3, "OFF") != 0)
    return soup.Fail(lines.Place(), "expected the OFF keyword, got \"" + key.substr(0, 40) + "\"");
  if (key.find('4') != std::string::npos || key.find('n') != std::string::npos)
    return soup.Fail(lines.Place(), key + ": only 3-dimensional OFF files are supported");
  if (t.size() > 1 && t[1] == "BINARY")
    return soup.Fail(lines.Place(), "binary OFF files are not supported");
  const std::string countsPlace = t.size() > 1 ? lines.Place() : "";
  std::vector<std::string> counts(t.begin() + 1, t.end());
  if (counts.empty() && !lines.Next(&counts))
    return soup.Fail("", "the file ends before the counts \"vertices faces edges\"");
  const std::string place = countsPlace.empty() ? lines.Place() : countsPlace;
  long nv = 0, nf = 0;
  if (counts.size() < 2 || !ParseLong(counts[0], &nv) || !ParseLong(counts[1], &nf) || nv < 0 ||
      nf < 0)
    return soup.Fail(place, "malformed counts (expected \"vertices faces edges\")");
  const double bytes = static_cast<double>(text.size());
  for (const std::string& m :
       {limits::CheckDeclaredCount(nv, limits::kMaxMeshVertices, 6, bytes, "vertices"),
        limits::CheckDeclaredCount(nf, limits::kMaxMeshElements, 8, bytes, "faces")})
    if (!m.empty()) return soup.Fail(place, "the header " + m);
  for (long i = 0; i < nv; ++i) {
    if (!lines.Next(&t))
      return soup.Fail("", "the file ends after " + std::to_string(i) + " of " +
                               std::to_string(nv) + " vertices");
    double x[3];
    if (t.size() < 3 || !ParseDouble(t[0], &x[0]) || !ParseDouble(t[1], &x[1]) ||
        !ParseDouble(t[2], &x[2]))
      return soup.Fail(lines.Place(), "malformed vertex (expected \"x y z\" with finite numbers)");
    if (!soup.AddVertex(x[0], x[1], x[2], lines.Place())) return false;
  }
  std::vector<long long> corners;
  for (long i = 0; i < nf; ++i) {
    if (!lines.Next(&t))
      return soup.Fail("", "the file ends after " + std::to_string(i) + " of " +
                               std::to_string(nf) + " faces");
    long n = 0;
    if (!ParseLong(t[0], &n) || n < 0 || static_cast<size_t>(n) + 1 > t.size())
      return soup.Fail(lines.Place(), "malformed face (expected \"n i_1 ... i_n\")");
    corners.clear();
    for (long k = 1; k <= n; ++k) {
      long v = 0;
      if (!ParseLong(t[k], &v))
        return soup.Fail(lines.Place(), "malformed vertex index \"" + t[k].substr(0, 40) + "\"");
      corners.push_back(v);
    }
    if (!soup.AddPolygon(corners, lines.Place())) return false;
  }
  return soup.Finish(mesh);
}

}  // namespace superdex
