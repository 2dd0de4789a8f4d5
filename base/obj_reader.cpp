#include "base/obj_reader.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>
#include <unordered_set>

#include "base/error.h"
#include "base/text_file.h"

namespace thaw::meshio {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

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

// Statements that are valid OBJ but carry nothing a surface needs.
const std::unordered_set<std::string_view>& ignored_statements() {
  static const std::unordered_set<std::string_view> s = {
      "vp",    "o",        "g",        "s",      "mg",   "usemtl",     "mtllib",
      "l",     "p",        "usemap",   "maplib", "lod",  "shadow_obj", "trace_obj",
      "bevel", "c_interp", "d_interp", "cstype", "deg",  "bmat",       "step",
      "curv",  "curv2",    "surf",     "parm",   "trim", "hole",       "scrv",
      "sp",    "end",      "con",      "ctech",  "stech"};
  return s;
}

/// One kind of element faces refer to (vertex, texture coordinate, normal): how many were read
/// and the largest forward reference, checked at the end (OBJ allows forward references).
struct IndexSpace {
  const char* what;
  const char* unit;  // what follows the count in messages
  std::int64_t count = 0;
  std::int64_t max_ref = 0;
  long max_line = 0;
};

class Parser {
 public:
  explicit Parser(std::string source) : m_source(std::move(source)) {}

  TriangleMesh parse(const std::string& text) {
    std::vector<std::string_view> tokens;
    std::size_t pos = 0;
    while (pos < text.size()) {
      std::size_t end = text.find('\n', pos);
      const bool has_line_end = end != std::string::npos;
      if (!has_line_end) end = text.size();
      std::string_view line(text.data() + pos, end - pos);
      pos = end + 1;
      ++m_line;
      const std::size_t hash = line.find('#');
      if (hash != std::string_view::npos) line = line.substr(0, hash);
      tokenize(line, tokens);
      if (tokens.empty()) continue;
      // Every writer ends its lines; a last statement without one was most likely cut off
      // ("f 1 2 3" of "f 1 2 34", "v 0.5" of "v 0.5 1 2") and cannot be trusted.
      if (!has_line_end) fail("last line has no line end: the file looks truncated");
      parse_statement(tokens);
    }
    check_references(m_vertices);
    check_references(m_texcoords);
    check_references(m_normals);
    if (m_mesh.triangles.empty())
      throw UserError(
          m_source, "",
          "empty mesh: no faces (" + std::to_string(m_mesh.vertices.size()) + " vertices)");
    if (!m_all_corners_have_normals) m_mesh.normal_triangles.clear();
    if (m_mesh.normal_triangles.empty()) m_mesh.normals.clear();
    return std::move(m_mesh);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw UserError(m_source, "line " + std::to_string(m_line), problem);
  }

  void parse_statement(const std::vector<std::string_view>& tokens) {
    const std::string_view keyword = tokens[0];
    if (keyword == "v") {
      // "v x y z", optionally with a weight w or an (r g b) colour as common extensions.
      if (tokens.size() != 4 && tokens.size() != 5 && tokens.size() != 7)
        fail("vertex needs 3 coordinates, got " + std::to_string(tokens.size() - 1) + " numbers");
      m_mesh.vertices.push_back(point(tokens));
      for (std::size_t k = 4; k < tokens.size(); ++k) number(tokens[k]);
      ++m_vertices.count;
    } else if (keyword == "vn") {
      if (tokens.size() != 4)
        fail("normal needs 3 numbers, got " + std::to_string(tokens.size() - 1));
      m_mesh.normals.push_back(point(tokens));
      ++m_normals.count;
    } else if (keyword == "vt") {
      if (tokens.size() < 2 || tokens.size() > 4)
        fail("texture coordinate needs 1 to 3 numbers, got " + std::to_string(tokens.size() - 1));
      for (std::size_t k = 1; k < tokens.size(); ++k) number(tokens[k]);
      ++m_texcoords.count;
    } else if (keyword == "f") {
      parse_face(tokens);
    } else if (!ignored_statements().contains(keyword)) {
      fail("unknown OBJ statement '" + std::string(keyword) + "'");
    }
  }

  double number(std::string_view token) const {
    double value = 0;
    const char* first = token.data();
    const char* last = token.data() + token.size();
    if (first != last && *first == '+') ++first;  // from_chars rejects a leading '+'
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec != std::errc() || ptr != last) fail("malformed number '" + std::string(token) + "'");
    if (!std::isfinite(value)) fail("non-finite coordinate '" + std::string(token) + "'");
    return value;
  }

  std::array<double, 3> point(const std::vector<std::string_view>& tokens) const {
    return {number(tokens[1]), number(tokens[2]), number(tokens[3])};
  }

  void check_references(const IndexSpace& s) {
    if (s.max_ref <= s.count) return;
    m_line = s.max_line;
    fail("face refers to " + std::string(s.what) + " " + std::to_string(s.max_ref) +
         " but the file has only " + std::to_string(s.count) + s.unit);
  }

  /// Parses one index of a face corner: an integer (no sign other than '-', no fraction, no
  /// exponent, within 64 bits). Negative (relative) indices resolve against the elements read so
  /// far. Returns the 0-based index; remembers the largest forward reference.
  std::int64_t index(std::string_view token, IndexSpace& s) const {
    std::int64_t value = 0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec == std::errc::result_out_of_range)
      fail(std::string(s.what) + " index '" + std::string(token) + "' is out of range");
    if (ec != std::errc() || ptr != token.data() + token.size())
      fail(std::string("malformed ") + s.what + " index '" + std::string(token) + "'");
    if (value == 0) fail(std::string(s.what) + " index 0 (OBJ indices start at 1)");
    if (value < 0) {
      const std::int64_t resolved = s.count + 1 + value;
      if (resolved < 1)
        fail(std::string("relative ") + s.what + " index " + std::to_string(value) +
             " points before the first " + s.what + " (only " + std::to_string(s.count) +
             " so far)");
      return resolved - 1;
    }
    if (value > s.max_ref) {
      s.max_ref = value;
      s.max_line = m_line;
    }
    return value - 1;
  }

  void parse_face(const std::vector<std::string_view>& tokens) {
    if (tokens.size() < 4)
      fail("face needs at least 3 corners, got " + std::to_string(tokens.size() - 1));
    m_corners.clear();
    m_corner_normals.clear();
    for (std::size_t k = 1; k < tokens.size(); ++k) {
      // v, v/t, v//n or v/t/n
      const std::string_view corner = tokens[k];
      const std::size_t s1 = corner.find('/');
      m_corners.push_back(index(corner.substr(0, s1), m_vertices));
      if (s1 == std::string_view::npos) {
        m_all_corners_have_normals = false;
        continue;
      }
      const std::string_view rest = corner.substr(s1 + 1);
      const std::size_t s2 = rest.find('/');
      const std::string_view tpart = rest.substr(0, s2);
      if (!tpart.empty()) index(tpart, m_texcoords);
      if (s2 == std::string_view::npos) {
        if (tpart.empty()) fail("malformed face corner '" + std::string(corner) + "'");
        m_all_corners_have_normals = false;
        continue;
      }
      const std::string_view npart = rest.substr(s2 + 1);
      if (npart.empty() || npart.find('/') != std::string_view::npos)
        fail("malformed face corner '" + std::string(corner) + "'");
      m_corner_normals.push_back(index(npart, m_normals));
    }
    const bool normals = m_corner_normals.size() == m_corners.size();
    // A polygon becomes a fan around its first corner (exact for the convex polygons OBJ
    // exporters write; thaw's own meshes are triangles only).
    for (std::size_t k = 1; k + 1 < m_corners.size(); ++k) {
      m_mesh.triangles.push_back({m_corners[0], m_corners[k], m_corners[k + 1]});
      if (normals && m_all_corners_have_normals)
        m_mesh.normal_triangles.push_back(
            {m_corner_normals[0], m_corner_normals[k], m_corner_normals[k + 1]});
    }
  }

  std::string m_source;
  long m_line = 0;
  TriangleMesh m_mesh;
  IndexSpace m_vertices{"vertex", " vertices"}, m_texcoords{"texture coordinate", ""},
      m_normals{"normal", ""};
  bool m_all_corners_have_normals = true;
  std::vector<std::int64_t> m_corners, m_corner_normals;
};

}  // namespace

TriangleMesh parse_obj(const std::string& text, const std::string& source_name) {
  return Parser(source_name).parse(text);
}

TriangleMesh read_obj(const std::filesystem::path& path) {
  return parse_obj(read_text_file(path, "an OBJ file"), path.string());
}

}  // namespace thaw::meshio
