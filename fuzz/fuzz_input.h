// The fuzz targets' shared helper: the readers that take a path read the input from a file
// written to the system's temporary directory (one name per process and extension).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace superdex::fuzz {

/// Writes bytes [data, data + size) to "$TMPDIR/superdex-fuzz-<pid>-<stem>.<ext>" (TMPDIR
/// defaults to /tmp) and returns the path; aborts when the file cannot be written (that is not a
/// finding of the reader).
inline std::string WriteInput(const uint8_t* data, size_t size, const std::string& stem,
                              const std::string& ext) {
  const char* dir = std::getenv("TMPDIR");
  const std::string path = std::string(dir && *dir ? dir : "/tmp") + "/superdex-fuzz-" +
                           std::to_string(getpid()) + "-" + stem + "." + ext;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
    std::perror(path.c_str());
    std::abort();
  }
  return path;
}

/// A reader that returned false must say why: an empty message is a finding.
inline void RequireMessage(bool ok, const std::string& message) {
  if (!ok && message.empty()) {
    std::fprintf(stderr, "the reader failed without a message\n");
    std::abort();
  }
}

/// Reads the file at `path` with `read` (ReadMeshFile, ReadTetMeshFile) and requires a message
/// when it fails.
template <typename Mesh>
void RequireReadMessage(bool (*read)(const std::string&, Mesh*, std::string*),
                        const std::string& path) {
  Mesh mesh;
  std::string error;
  RequireMessage(read(path, &mesh, &error), error);
}

/// A mesh reader's fuzz target whose input is the whole file: writes it as
/// "superdex-fuzz-<pid>-mesh.<ext>" and reads it with `read` (RequireReadMessage).
template <typename Mesh>
int FuzzMeshFile(const uint8_t* data, size_t size, const std::string& ext,
                 bool (*read)(const std::string&, Mesh*, std::string*)) {
  RequireReadMessage(read, WriteInput(data, size, "mesh", ext));
  return 0;
}

}  // namespace superdex::fuzz
