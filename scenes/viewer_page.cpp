#include "scenes/viewer_page.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <vector>

#include "scenes/json_text.h"
#include "scenes/viewer_assets.h"

namespace superdex {
namespace {

using json = nlohmann::json;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
const char* const kEnergies[] = {"kinetic", "gravity", "contact", "elastic", "total"};

// A bad trajectory line: the message names the file, the line and the field.
struct BadInput {
  std::string message;
};

std::string Base64(const std::vector<float>& values) {
  static const char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes(values.size() * sizeof(float));
  for (size_t i = 0; i < values.size(); ++i) {  // little-endian, as Float32Array reads them
    uint32_t u;
    std::memcpy(&u, &values[i], sizeof(u));
    for (int k = 0; k < 4; ++k) bytes[4 * i + k] = static_cast<unsigned char>(u >> (8 * k));
  }
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = (uint32_t(bytes[i]) << 16) |
                       (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? uint32_t(bytes[i + 2]) : 0);
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

constexpr size_t kAnyMultiple = static_cast<size_t>(-1);

// Appends the numbers of j[key] (an array of n numbers; n = kAnyMultiple: of any multiple of
// `multiple`) to *out; returns how many.
size_t Numbers(const json& j, const char* key, size_t n, size_t multiple, const std::string& where,
               std::vector<float>* out) {
  const json& a = j.at(key);
  const bool sized = n != kAnyMultiple ? a.is_array() && a.size() == n
                                       : a.is_array() && a.size() % multiple == 0;
  if (!sized)
    throw BadInput{where + key + ": expected " +
                   (n != kAnyMultiple ? std::to_string(n) + " numbers"
                                      : "an array of numbers, a multiple of " +
                                            std::to_string(multiple))};
  for (const json& v : a) {
    if (v.is_null()) {
      out->push_back(kNaN);
    } else if (v.is_number()) {
      out->push_back(v.get<float>());
    } else {
      throw BadInput{where + key + ": expected numbers"};
    }
  }
  return a.size();
}

bool Has(const json& j, const char* key) { return j.is_object() && j.contains(key); }

// Checks a rigid actor's "shape" (docs/trajectory-format.md) as far as the page relies on it.
void CheckShape(const json& s, const std::string& where) {
  if (!s.is_object() || !Has(s, "type") || !s["type"].is_string())
    throw BadInput{where + "type: expected a string"};
  const std::string type = s["type"];
  std::vector<float> v;
  if (type == "sphere") {
    if (!Has(s, "radius") || !s["radius"].is_number() || !(s["radius"].get<double>() > 0))
      throw BadInput{where + "radius: expected a number > 0"};
  } else if (type == "box") {
    Numbers(s, "half_extents", 3, 1, where, &v);
  } else if (type == "plane") {
    Numbers(s, "normal", 3, 1, where, &v);
  } else if (type == "mesh") {
    const size_t vertices = Numbers(s, "vertices", kAnyMultiple, 3, where, &v) / 3;
    for (const json& f : s.value("faces", json::array()))
      if (!f.is_number_integer() || f.get<long>() < 0 || f.get<size_t>() >= vertices)
        throw BadInput{where + "faces: expected vertex indices below " + std::to_string(vertices)};
    if (!Has(s, "faces") || s["faces"].size() % 3 != 0)
      throw BadInput{where + "faces: expected an array of index triples"};
  } else {
    throw BadInput{where + "type: unknown shape \"" + type + "\" (sphere, box, plane, mesh)"};
  }
}

// The trajectory read into the page's data: the header's actors, and per frame the time, the
// energies and the base64 Float32 blocks.
class PageData {
 public:
  void ReadHeader(const json& h, const std::string& where) {
    if (!Has(h, "actors") || !h["actors"].is_array() || h["actors"].empty())
      throw BadInput{where + "the header line needs \"actors\": [{\"name\": …}, …]"};
    for (size_t i = 0; i < h["actors"].size(); ++i) AddActor(h["actors"][i], where, i);
    for (const char* key : {"dt", "integrator", "gravity", "contacts"})
      if (Has(h, key)) settings_[key] = h[key];
  }

  void ReadFrame(const json& f, const std::string& where) {
    if (!Has(f, "t") || !f["t"].is_number()) throw BadInput{where + "a frame needs a number \"t\""};
    const json& actors = f.value("actors", json());
    if (!actors.is_array() || actors.size() != actors_.size())
      throw BadInput{where + "a frame needs \"actors\" with one entry per header actor (" +
                     std::to_string(actors_.size()) + ")"};
    std::vector<float> pose, surface;
    for (size_t i = 0; i < actors.size(); ++i) {
      const std::string at = where + "actors[" + std::to_string(i) + "].";
      ReadPose(actors[i], at, &pose);
      if (softNodes_[i] > 0) ReadSurface(actors[i], at, softNodes_[i], &surface);
    }
    json frame = {{"pose", Base64(pose)}, {"surface", Base64(surface)}, {"contacts", ""},
                  {"forces", ""}};
    if (Has(f, "contacts")) ReadContacts(f["contacts"], where + "contacts.", &frame);
    frames_.push_back(frame);
    times_.push_back(f["t"]);
    const json& e = f.value("energy", json::object());
    for (const char* k : kEnergies)
      energy_[k].push_back(Has(e, k) && e[k].is_number() ? e[k] : json(nullptr));
  }

  int Frames() const { return static_cast<int>(frames_.size()); }
  int Actors() const { return static_cast<int>(actors_.size()); }
  long ContactSamples() const { return samples_; }

  json Page(const std::string& title) const {
    return {{"format", "superdex-viewer/1"}, {"title", title}, {"settings", settings_},
            {"actors", actors_}, {"times", times_}, {"energy", energy_}, {"frames", frames_},
            {"contact_samples", samples_}, {"max_pair_force", maxPairForce_},
            {"max_traction", maxTraction_}};
  }

 private:
  void AddActor(const json& a, const std::string& where, size_t i) {
    const std::string at = where + "header actors[" + std::to_string(i) + "].";
    if (!a.is_object() || !Has(a, "name") || !a["name"].is_string())
      throw BadInput{at + "name: every actor needs a string \"name\""};
    json actor = {{"name", a["name"]}, {"type", a.value("type", "rigid")},
                  {"dynamic", a.value("dynamic", true)}};
    int nodes = 0;
    if (Has(a, "shape")) {
      CheckShape(a["shape"], at + "shape.");
      actor["shape"] = a["shape"];
    }
    if (Has(a, "surface")) {
      const json& s = a["surface"];
      nodes = static_cast<int>(s.value("nodes", json::array()).size());
      if (!Has(s, "faces") || !s["faces"].is_array() || s["faces"].size() % 3 != 0)
        throw BadInput{at + "surface.faces: expected an array of index triples"};
      for (const json& f : s["faces"])
        if (!f.is_number_integer() || f.get<long>() < 0 || f.get<long>() >= nodes)
          throw BadInput{at + "surface.faces: expected indices below " + std::to_string(nodes)};
      actor["surface"] = {{"nodes", nodes}, {"faces", s["faces"]}};
    }
    actors_.push_back(actor);
    softNodes_.push_back(nodes);
  }

  // p and q of one actor (NaN position: not in this frame; no q: identity).
  static void ReadPose(const json& a, const std::string& at, std::vector<float>* pose) {
    if (Has(a, "p")) {
      Numbers(a, "p", 3, 1, at, pose);
    } else {
      pose->insert(pose->end(), {kNaN, kNaN, kNaN});
    }
    if (Has(a, "q")) {
      Numbers(a, "q", 4, 1, at, pose);
    } else {
      pose->insert(pose->end(), {0.f, 0.f, 0.f, 1.f});
    }
  }

  static void ReadSurface(const json& a, const std::string& at, int nodes,
                          std::vector<float>* surface) {
    if (Has(a, "surface")) {
      Numbers(a, "surface", 3 * nodes, 1, at, surface);
    } else {
      surface->insert(surface->end(), 3 * nodes, kNaN);
    }
  }

  // The frame's "contacts" block, per sample [p (3), tn]: position [m], normal traction [Pa];
  // and its "forces" block, per actor pair [point (3), net force (3)]: the
  // pair's force on its colliding actor at the force-weighted mean of its samples.
  void ReadContacts(const json& c, const std::string& at, json* frame) {
    std::vector<float> p, f, tn, pairs;
    const size_t n = Numbers(c, "tn", kAnyMultiple, 1, at, &tn);
    Numbers(c, "p", 3 * n, 1, at, &p);
    Numbers(c, "f", 3 * n, 1, at, &f);
    if (Has(c, "pairs")) Numbers(c, "pairs", 2 * n, 1, at, &pairs);
    std::vector<float> samples;
    samples.reserve(4 * n);
    std::map<std::pair<int, int>, Eigen::Matrix<double, 7, 1>> net;  // Σ|f| p, Σ f, Σ|f|
    for (size_t s = 0; s < n; ++s) {
      const Eigen::Vector3d ps(p[3 * s], p[3 * s + 1], p[3 * s + 2]);
      const Eigen::Vector3d fs(f[3 * s], f[3 * s + 1], f[3 * s + 2]);
      samples.insert(samples.end(), {p[3 * s], p[3 * s + 1], p[3 * s + 2], tn[s]});
      if (std::isfinite(tn[s])) maxTraction_ = std::max(maxTraction_, double(tn[s]));
      if (!ps.allFinite() || !fs.allFinite()) continue;
      const std::pair<int, int> pair =
          pairs.empty() ? std::make_pair(0, 0)
                        : std::make_pair(static_cast<int>(pairs[2 * s]), static_cast<int>(pairs[2 * s + 1]));
      auto& sum = net.try_emplace(pair, Eigen::Matrix<double, 7, 1>::Zero()).first->second;
      sum.head<3>() += fs.norm() * ps;
      sum.segment<3>(3) += fs;
      sum[6] += fs.norm();
    }
    std::vector<float> forces;
    for (const auto& [pair, sum] : net) {
      if (!(sum[6] > 0)) continue;
      const Eigen::Vector3d point = sum.head<3>() / sum[6];
      for (int k = 0; k < 3; ++k) forces.push_back(static_cast<float>(point[k]));
      for (int k = 0; k < 3; ++k) forces.push_back(static_cast<float>(sum[3 + k]));
      maxPairForce_ = std::max(maxPairForce_, sum.segment<3>(3).norm());
    }
    samples_ += static_cast<long>(n);
    (*frame)["contacts"] = Base64(samples);
    (*frame)["forces"] = Base64(forces);
  }

  json settings_ = json::object(), actors_ = json::array(), times_ = json::array();
  json energy_ = json::object(), frames_ = json::array();
  std::vector<int> softNodes_;  // per actor: soft boundary nodes (0: rigid)
  long samples_ = 0;
  double maxPairForce_ = 0.0, maxTraction_ = 0.0;
};

// Reads the whole trajectory; throws BadInput. A last line without its newline that is not
// valid JSON (a killed run's) is skipped and noted.
void ReadTrajectory(const std::string& path, PageData* data, std::vector<std::string>* notes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BadInput{"view: cannot read \"" + path + "\""};
  bool header = true;
  int lineNo = 0;
  for (std::string line; std::getline(in, line);) {
    ++lineNo;
    const bool unterminated = in.eof();
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = path + ":" + std::to_string(lineNo) + ": ";
    json j;
    std::string why;
    if (!ParseJsonText(line, &j, &why)) {
      if (unterminated && !header) {
        notes->push_back(where + "the last line is truncated (no newline, not valid JSON): "
                                 "skipped");
        break;
      }
      throw BadInput{where + why};
    }
    if (header) {
      data->ReadHeader(j, where);
      header = false;
    } else {
      data->ReadFrame(j, where);
    }
  }
  if (header) throw BadInput{"view: \"" + path + "\" is empty"};
  if (data->Frames() == 0) throw BadInput{"view: \"" + path + "\" has no frames"};
}

// JSON inside <script>: '<' only occurs in strings, where \u003c keeps "</script>" and "<!--"
// from ending or escaping the element.
std::string ScriptSafe(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

// A script's text inside <script>: "</script" split so that it cannot end the element.
std::string ScriptText(std::string text) {
  for (size_t at = text.find("</script"); at != std::string::npos; at = text.find("</script", at))
    text.replace(at, 2, "<\\/");
  return text;
}

// The template with each marker replaced by its text; markers are looked for in the template
// only, never in the inserted texts.
std::string Fill(const std::string& page,
                 std::vector<std::pair<std::string, std::string>> markers) {
  std::vector<std::pair<size_t, size_t>> at;  // (position in the template, marker index)
  for (size_t m = 0; m < markers.size(); ++m) {
    const size_t pos = page.find(markers[m].first);
    if (pos != std::string::npos) at.emplace_back(pos, m);
  }
  std::sort(at.begin(), at.end());
  std::string out;
  size_t from = 0;
  for (const auto& [pos, m] : at) {
    out.append(page, from, pos - from);
    out += markers[m].second;
    from = pos + markers[m].first.size();
  }
  out.append(page, from, std::string::npos);
  return out;
}

}  // namespace

std::string ViewerPagePath(const std::string& trajectoryPath) {
  return std::filesystem::path(trajectoryPath).replace_extension(".html").string();
}

bool WriteViewerPage(const std::string& trajectoryPath, const std::string& pagePath,
                     ViewerPageInfo* info, Error* error) {
  PageData data;
  std::vector<std::string> notes;
  try {
    ReadTrajectory(trajectoryPath, &data, &notes);
  } catch (const BadInput& e) {
    return Fail(error, e.message);
  }
  const std::string title = std::filesystem::path(trajectoryPath).filename().string();
  const std::string page =
      Fill(std::string(viewer_assets::Template()),
           {{"/*@superdex-data@*/", ScriptSafe(data.Page(title).dump())},
            {"/*@viewer-js@*/", ScriptText(std::string(viewer_assets::Script()))},
            {"/*@three-js@*/", ScriptText(std::string(viewer_assets::Three()))}});
  std::error_code ec;
  const std::filesystem::path p(pagePath);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
  // Written to a temporary name and renamed when complete: never a partial page.
  const std::string part = pagePath + ".part";
  errno = 0;
  std::ofstream out(part, std::ios::binary);
  out << page;
  out.close();
  if (!out || std::rename(part.c_str(), pagePath.c_str()) != 0) {
    const std::string why = errno ? std::strerror(errno) : "write error";
    std::remove(part.c_str());
    return Fail(error, "view: cannot write \"" + pagePath + "\": " + why);
  }
  if (info) {
    info->notes = notes;
    info->path = pagePath;
    info->frames = data.Frames();
    info->actors = data.Actors();
    info->contactSamples = data.ContactSamples();
    info->bytes = static_cast<long>(page.size());
  }
  return true;
}

}  // namespace superdex
