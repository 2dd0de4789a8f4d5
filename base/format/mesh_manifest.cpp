#include "base/format/mesh_manifest.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/error.h"
#include "base/format/json_error.h"
#include "base/text_file.h"

namespace thaw::meshio {
namespace {

using Json = nlohmann::json;

/// Typed, checked access to one JSON object; errors name the file and the key's path.
class Object {
 public:
  Object(const Json& j, std::string source, std::string where)
      : m_j(j), m_source(std::move(source)), m_where(std::move(where)) {
    if (!m_j.is_object()) fail("", "expected a JSON object");
  }
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    std::string at = m_where;
    if (!key.empty()) at += (at.empty() ? "" : ".") + key;
    throw UserError(m_source, at, problem);
  }
  bool has(const std::string& key) const { return m_j.contains(key); }
  const Json& at(const std::string& key) const {
    if (!m_j.contains(key)) fail(key, "missing");
    return m_j[key];
  }
  std::string string(const std::string& key) const {
    const Json& v = at(key);
    if (!v.is_string()) fail(key, "expected a string, got " + std::string(v.type_name()));
    return v.get<std::string>();
  }
  double non_negative(const std::string& key) const {
    const Json& v = at(key);
    if (!v.is_number()) fail(key, "expected a number, got " + std::string(v.type_name()));
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < 0) fail(key, "must be finite and >= 0, got " + v.dump());
    return x;
  }
  long count(const std::string& key) const {
    const Json& v = at(key);
    if (!v.is_number_integer() || v.get<std::int64_t>() < 0 ||
        v.get<std::int64_t>() > std::numeric_limits<long>::max())
      fail(key, "expected an integer >= 0, got " + v.dump());
    return v.get<long>();
  }
  std::optional<std::string> surface_file(const std::string& key) const {
    const Json& v = at(key);
    if (v.is_null()) return std::nullopt;
    if (!v.is_string() || v.get<std::string>().empty())
      fail(key, "expected a file name or null (vanished surface)");
    const std::string name = v.get<std::string>();
    // A plain name in the manifest's folder: a manifest must not point anywhere else.
    if (name.find('/') != std::string::npos || name.find('\\') != std::string::npos ||
        name == "." || name == "..")
      fail(key, "'" + name + "' is not a plain file name in the mesh folder");
    return name;
  }
  const Json& json() const { return m_j; }

 private:
  const Json& m_j;
  std::string m_source, m_where;
};

ManifestStep read_step(const Json& j, const std::string& source, std::size_t k) {
  const Object o(j, source, "steps[" + std::to_string(k) + "]");
  ManifestStep s;
  s.step = o.count("step");
  s.time_s = o.non_negative("time_s");
  s.inner_radius_m = o.non_negative("inner_radius_m");
  s.outer_radius_m = o.non_negative("outer_radius_m");
  s.inner = o.surface_file("inner");
  s.outer = o.surface_file("outer");
  if (o.has("inner_triangles")) s.inner_triangles = o.count("inner_triangles");
  if (o.has("outer_triangles")) s.outer_triangles = o.count("outer_triangles");
  for (auto [key, out] : {std::pair{"inner_exact_volume_m3", &s.inner_exact_volume_m3},
                          std::pair{"outer_exact_volume_m3", &s.outer_exact_volume_m3}})
    if (o.has(key) && !o.at(key).is_null()) *out = o.non_negative(key);
  return s;
}

}  // namespace

MeshManifestFile parse_mesh_manifest(const std::string& text, const std::string& source) {
  Json j;
  try {
    j = Json::parse(text);
  } catch (const Json::exception& e) {
    throw UserError(source, "", "malformed JSON: " + json_problem(e));
  }
  const Object root(j, source, "");
  MeshManifestFile m;
  if (root.string("format") != kMeshManifestFormat)
    root.fail("format", "expected \"" + std::string(kMeshManifestFormat) + "\", got " +
                            root.at("format").dump());
  if (root.has("geometry")) {
    const Object g(root.at("geometry"), source, "geometry");
    m.geometry = g.string("geometry");
    if (m.geometry != "sphere" && m.geometry != "cylinder" && m.geometry != "planar" &&
        m.geometry != "grid")
      g.fail("geometry", "expected sphere, cylinder, planar or grid, got \"" + m.geometry + "\"");
    if (g.has("length_m")) m.length_m = g.non_negative("length_m");
    if (g.has("lateral_size_m")) m.lateral_size_m = g.non_negative("lateral_size_m");
    if (g.has("planar_symmetric")) {
      if (!g.at("planar_symmetric").is_boolean())
        g.fail("planar_symmetric", "expected true or false");
      m.planar_symmetric = g.at("planar_symmetric").get<bool>();
    }
  }
  const Json& steps = root.at("steps");
  if (!steps.is_array()) root.fail("steps", "expected an array");
  for (std::size_t k = 0; k < steps.size(); ++k) {
    ManifestStep s = read_step(steps[k], source, k);
    if (!m.steps.empty() && s.step <= m.steps.back().step)
      throw UserError(source, "steps[" + std::to_string(k) + "].step",
                      "steps must be increasing (" + std::to_string(s.step) + " after " +
                          std::to_string(m.steps.back().step) + ")");
    m.steps.push_back(std::move(s));
  }
  return m;
}

MeshManifestFile read_mesh_manifest(const std::filesystem::path& path) {
  return parse_mesh_manifest(read_text_file(path, "a mesh manifest"), path.string());
}

}  // namespace thaw::meshio
