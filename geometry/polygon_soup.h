// What the OFF, STL and PLY readers share (geometry/mesh_readers.h): the file's text split into
// numbered lines, and a polygon soup that checks vertices and faces as they are added and
// fan-triangulates at the end. Internal to geometry/.
#pragma once

#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace superdex {

/// A polygon soup under construction for the file `path`. Every failure leaves a message
/// "<path>: <place>: <what>" in *error and returns false.
class PolygonSoup {
 public:
  PolygonSoup(const std::string& path, std::string* error) : path_(path), error_(error) {}

  /// A vertex: finite coordinates, at most limits::kMaxMeshVertices.
  bool AddVertex(double x, double y, double z, const std::string& place);
  /// A polygon of corner indices (0-based, checked against the vertices in Finish): at least 3
  /// corners, at most limits::kMaxMeshElements triangles in all.
  bool AddPolygon(const std::vector<long long>& corners, const std::string& place);
  /// Checks every index, fan-triangulates, and moves the result to *mesh (not on failure).
  bool Finish(TriangleMesh* mesh);

  int NumVertices() const { return static_cast<int>(vertices_.size()); }
  /// Fails with "<path>: <place>: <what>".
  bool Fail(const std::string& place, const std::string& what) const;
  /// Reads the whole file `path` into *text (ReadWholeFile); an empty file fails with
  /// "<path>: the file is empty".
  bool ReadNonEmptyFile(std::string* text) const;

 private:
  std::string path_;
  std::string* error_;
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<long long> corners_;     // all polygons' corners, back to back
  std::vector<size_t> polygonStart_;   // into corners_
  std::vector<std::string> places_;    // per polygon, for messages
  double triangles_ = 0;
};

/// A text file's lines with their numbers, for the text readers: comments from '#' dropped (if
/// `hashComments`), blank lines skipped, tokens split at whitespace.
class TokenLines {
 public:
  /// `text` must outlive the reader; reading starts at byte `start`, numbered line firstLine.
  TokenLines(const std::string& text, bool hashComments, int firstLine = 1, size_t start = 0);
  /// The tokens of the next non-blank line (false at the end).
  bool Next(std::vector<std::string>* tokens);
  /// "line N" of the last line returned.
  std::string Place() const { return "line " + std::to_string(line_); }

 private:
  const std::string& text_;
  bool hashComments_;
  size_t pos_ = 0;
  int line_ = 0;
};

/// Reads a whole file into *text; false with "<path>: cannot open file" (or "read error").
bool ReadWholeFile(const std::string& path, std::string* text, std::string* error);

}  // namespace superdex
