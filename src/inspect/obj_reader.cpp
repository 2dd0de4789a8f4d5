#include "src/inspect/obj_reader.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string_view>
#include <unordered_set>

#include "src/common/atomic_file.h"
#include "src/common/error.h"

namespace thaw::inspect {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/// Splits `line` into whitespace-separated tokens.
void tokenize(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
}

// Statements that are valid OBJ but carry nothing a surface check needs.
const std::unordered_set<std::string_view>& ignored_statements() {
  static const std::unordered_set<std::string_view> s = {
      "vt", "vn", "vp", "o", "g", "s", "mg", "usemtl", "mtllib", "l", "p", "usemap", "maplib",
      "lod", "shadow_obj", "trace_obj", "bevel", "c_interp", "d_interp", "cstype", "deg", "bmat",
      "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con",
      "ctech", "stech"};
  return s;
}

class Parser {
 public:
  explicit Parser(std::string source) : m_source(std::move(source)) {}

  TriangleMesh parse(const std::string& text) {
    std::vector<std::string_view> tokens;
    std::vector<std::int64_t> corners;
    std::size_t pos = 0;
    long line_no = 0;
    while (pos < text.size()) {
      std::size_t end = text.find('\n', pos);
      if (end == std::string::npos) end = text.size();
      std::string_view line(text.data() + pos, end - pos);
      pos = end + 1;
      ++line_no;
      m_line = line_no;
      const std::size_t hash = line.find('#');
      if (hash != std::string_view::npos) line = line.substr(0, hash);
      tokenize(line, tokens);
      if (tokens.empty()) continue;
      const std::string_view keyword = tokens[0];
      if (keyword == "v") {
        parse_vertex(tokens);
      } else if (keyword == "f") {
        parse_face(tokens, corners);
      } else if (keyword == "vt") {
        ++m_texcoords;
      } else if (keyword == "vn") {
        ++m_normals;
      } else if (!ignored_statements().contains(keyword)) {
        fail("unknown OBJ statement '" + std::string(keyword) + "'");
      }
    }
    if (m_max_vertex_ref > static_cast<std::int64_t>(m_mesh.vertices.size())) {
      m_line = m_max_vertex_line;
      fail("face refers to vertex " + std::to_string(m_max_vertex_ref) + " but the file has only " +
           std::to_string(m_mesh.vertices.size()) + " vertices");
    }
    if (m_max_texcoord_ref > m_texcoords) {
      m_line = m_max_texcoord_line;
      fail("face refers to texture coordinate " + std::to_string(m_max_texcoord_ref) +
           " but the file has only " + std::to_string(m_texcoords));
    }
    if (m_max_normal_ref > m_normals) {
      m_line = m_max_normal_line;
      fail("face refers to normal " + std::to_string(m_max_normal_ref) + " but the file has only " +
           std::to_string(m_normals));
    }
    if (m_mesh.triangles.empty())
      throw UserError(m_source, "",
                      "empty mesh: no faces (" + std::to_string(m_mesh.vertices.size()) +
                          " vertices)");
    return std::move(m_mesh);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw UserError(m_source, "line " + std::to_string(m_line), problem);
  }

  double parse_number(std::string_view token) const {
    double value = 0;
    const char* first = token.data();
    const char* last = token.data() + token.size();
    if (first != last && *first == '+') ++first;  // from_chars rejects a leading '+'
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || ptr != last)
      fail("malformed number '" + std::string(token) + "'");
    if (!std::isfinite(value)) fail("non-finite coordinate '" + std::string(token) + "'");
    return value;
  }

  void parse_vertex(const std::vector<std::string_view>& tokens) {
    // "v x y z", optionally with a weight w or an (r g b) colour as common extensions.
    if (tokens.size() != 4 && tokens.size() != 5 && tokens.size() != 7)
      fail("vertex needs 3 coordinates, got " + std::to_string(tokens.size() - 1) + " numbers");
    std::array<double, 3> p{};
    for (int k = 0; k < 3; ++k) p[k] = parse_number(tokens[k + 1]);
    for (std::size_t k = 4; k < tokens.size(); ++k) parse_number(tokens[k]);
    m_mesh.vertices.push_back(p);
  }

  /// Parses one index of a face corner; resolves negative (relative) indices against `count`
  /// elements read so far; returns the 1-based index and remembers the largest forward reference.
  std::int64_t parse_index(std::string_view token, std::int64_t count, const char* what,
                           std::int64_t& max_ref, long& max_line) const {
    std::int64_t index = 0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), index);
    if (ec != std::errc() || ptr != token.data() + token.size())
      fail(std::string("malformed ") + what + " index '" + std::string(token) + "'");
    if (index == 0) fail(std::string(what) + " index 0 (OBJ indices start at 1)");
    if (index < 0) {
      const std::int64_t resolved = count + 1 + index;
      if (resolved < 1)
        fail(std::string("relative ") + what + " index " + std::to_string(index) +
             " points before the first " + what + " (only " + std::to_string(count) + " so far)");
      return resolved;
    }
    if (index > max_ref) {
      max_ref = index;
      max_line = m_line;
    }
    return index;
  }

  void parse_face(const std::vector<std::string_view>& tokens, std::vector<std::int64_t>& corners) {
    if (tokens.size() < 4)
      fail("face needs at least 3 corners, got " + std::to_string(tokens.size() - 1));
    corners.clear();
    const auto nv = static_cast<std::int64_t>(m_mesh.vertices.size());
    for (std::size_t k = 1; k < tokens.size(); ++k) {
      const std::string_view corner = tokens[k];
      const std::size_t s1 = corner.find('/');
      const std::string_view vpart = corner.substr(0, s1);
      corners.push_back(parse_index(vpart, nv, "vertex", m_max_vertex_ref, m_max_vertex_line) - 1);
      if (s1 == std::string_view::npos) continue;
      const std::string_view rest = corner.substr(s1 + 1);
      const std::size_t s2 = rest.find('/');
      const std::string_view tpart = rest.substr(0, s2);
      if (!tpart.empty())
        parse_index(tpart, m_texcoords, "texture coordinate", m_max_texcoord_ref,
                    m_max_texcoord_line);
      if (s2 != std::string_view::npos) {
        const std::string_view npart = rest.substr(s2 + 1);
        if (npart.empty() || npart.find('/') != std::string_view::npos)
          fail("malformed face corner '" + std::string(corner) + "'");
        parse_index(npart, m_normals, "normal", m_max_normal_ref, m_max_normal_line);
      } else if (tpart.empty()) {
        fail("malformed face corner '" + std::string(corner) + "'");
      }
    }
    // A polygon becomes a fan around its first corner (exact for the convex polygons OBJ
    // exporters write; thaw's own meshes are triangles only).
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      m_mesh.triangles.push_back({corners[0], corners[k], corners[k + 1]});
  }

  std::string m_source;
  long m_line = 0;
  TriangleMesh m_mesh;
  std::int64_t m_texcoords = 0, m_normals = 0;
  std::int64_t m_max_vertex_ref = 0, m_max_texcoord_ref = 0, m_max_normal_ref = 0;
  long m_max_vertex_line = 0, m_max_texcoord_line = 0, m_max_normal_line = 0;
};

}  // namespace

TriangleMesh parse_obj(const std::string& text, const std::string& source_name) {
  return Parser(source_name).parse(text);
}

TriangleMesh read_obj(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw UserError(path.string(), "", "no such file");
  if (std::filesystem::is_directory(path, ec))
    throw UserError(path.string(), "", "is a directory, expected an OBJ file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError(path.string(), "", "cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw UserError(path.string(), "", "read error");
  return parse_obj(buffer.str(), path.string());
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh) {
  std::string text;
  text.reserve(mesh.vertices.size() * 64 + mesh.triangles.size() * 24);
  char buf[128];
  for (const auto& v : mesh.vertices) {
    const int n = std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g\n", v[0], v[1], v[2]);
    text.append(buf, static_cast<std::size_t>(n));
  }
  for (const auto& t : mesh.triangles) {
    const int n = std::snprintf(buf, sizeof buf, "f %lld %lld %lld\n",
                                static_cast<long long>(t[0] + 1), static_cast<long long>(t[1] + 1),
                                static_cast<long long>(t[2] + 1));
    text.append(buf, static_cast<std::size_t>(n));
  }
  write_file_atomic(path, text);
}

}  // namespace thaw::inspect
