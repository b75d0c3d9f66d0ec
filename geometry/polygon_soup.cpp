#include "geometry/polygon_soup.h"

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "geometry/mesh_limits.h"

namespace superdex {

bool PolygonSoup::Fail(const std::string& place, const std::string& what) const {
  if (error_) *error_ = path_ + ": " + (place.empty() ? "" : place + ": ") + what;
  return false;
}

bool PolygonSoup::ReadNonEmptyFile(std::string* text) const {
  if (!ReadWholeFile(path_, text, error_)) return false;
  if (text->empty()) return Fail("", "the file is empty");
  return true;
}

bool PolygonSoup::AddVertex(double x, double y, double z, const std::string& place) {
  if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z)))
    return Fail(place, "vertex coordinates must be finite numbers");
  if (static_cast<double>(vertices_.size()) >= limits::kMaxMeshVertices)
    return Fail(place, "more than " + std::to_string(long(limits::kMaxMeshVertices)) +
                           " vertices (the limit per mesh file)");
  vertices_.emplace_back(x, y, z);
  return true;
}

bool PolygonSoup::AddPolygon(const std::vector<long long>& corners, const std::string& place) {
  if (corners.size() < 3)
    return Fail(place, "a face needs at least 3 vertices, got " + std::to_string(corners.size()));
  triangles_ += static_cast<double>(corners.size()) - 2;
  if (triangles_ > limits::kMaxMeshElements)
    return Fail(place, "more than " + std::to_string(long(limits::kMaxMeshElements)) +
                           " triangles (the limit per mesh file)");
  polygonStart_.push_back(corners_.size());
  corners_.insert(corners_.end(), corners.begin(), corners.end());
  places_.push_back(place);
  return true;
}

bool PolygonSoup::Finish(TriangleMesh* mesh) {
  if (polygonStart_.empty()) return Fail("", "no faces");
  const long long nv = static_cast<long long>(vertices_.size());
  TriangleMesh m;
  m.faces.reserve(static_cast<size_t>(triangles_));
  for (size_t p = 0; p < polygonStart_.size(); ++p) {
    const size_t begin = polygonStart_[p];
    const size_t end = p + 1 < polygonStart_.size() ? polygonStart_[p + 1] : corners_.size();
    for (size_t k = begin; k < end; ++k)
      if (corners_[k] < 0 || corners_[k] >= nv)
        return Fail(places_[p], "face " + std::to_string(p) + ": vertex index " +
                                    std::to_string(corners_[k]) + " out of range (" +
                                    std::to_string(nv) + " vertices, numbered from 0)");
    for (size_t k = begin + 1; k + 1 < end; ++k)
      m.faces.emplace_back(int(corners_[begin]), int(corners_[k]), int(corners_[k + 1]));
  }
  m.vertices = std::move(vertices_);
  *mesh = std::move(m);
  return true;
}

TokenLines::TokenLines(const std::string& text, bool hashComments, int firstLine, size_t start)
    : text_(text), hashComments_(hashComments), pos_(start), line_(firstLine - 1) {}

bool TokenLines::Next(std::vector<std::string>* tokens) {
  tokens->clear();
  while (pos_ < text_.size()) {
    size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    ++line_;
    size_t stop = end;
    if (hashComments_) {
      const size_t hash = text_.find('#', pos_);
      if (hash < end) stop = hash;
    }
    for (size_t i = pos_; i < stop;) {
      while (i < stop && std::isspace(static_cast<unsigned char>(text_[i]))) ++i;
      size_t j = i;
      while (j < stop && !std::isspace(static_cast<unsigned char>(text_[j]))) ++j;
      if (j > i) tokens->push_back(text_.substr(i, j - i));
      i = j;
    }
    pos_ = end + 1;
    if (!tokens->empty()) return true;
  }
  return false;
}

bool ReadWholeFile(const std::string& path, std::string* text, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *error = path + ": cannot open file";
    return false;
  }
  in.seekg(0, std::ios::end);
  const double bytes = static_cast<double>(in.tellg());
  in.seekg(0, std::ios::beg);
  if (bytes > limits::kMaxMeshFileBytes) {
    *error = path + ": the file holds " + std::to_string(long(bytes)) + " bytes (limit " +
             std::to_string(long(limits::kMaxMeshFileBytes)) + " per mesh file)";
    return false;
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) {
    *error = path + ": read error";
    return false;
  }
  *text = buffer.str();
  return true;
}

}  // namespace superdex
