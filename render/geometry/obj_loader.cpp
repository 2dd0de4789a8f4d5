#include "render/geometry/obj_loader.h"

#include <tiny_obj_loader.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "src/common/error.h"

namespace thaw::render {

namespace {

/// Checks the numbers of `v` and `vn` lines; throws naming the first bad line.
void check_numbers(const std::string& text, const std::string& source) {
  std::size_t line_no = 0, pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    ++line_no;
    const char* p = text.data() + pos;
    const char* e = text.data() + end;
    pos = end + 1;
    while (p < e && (*p == ' ' || *p == '\t')) ++p;
    const bool is_v = (e - p > 1 && p[0] == 'v' && (p[1] == ' ' || p[1] == '\t'));
    const bool is_vn = (e - p > 2 && p[0] == 'v' && p[1] == 'n' && (p[2] == ' ' || p[2] == '\t'));
    if (!is_v && !is_vn) continue;
    p += is_v ? 1 : 2;
    int count = 0;
    while (true) {
      while (p < e && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
      if (p >= e || *p == '#') break;
      double value = 0.0;
      const char* q = (*p == '+') ? p + 1 : p;
      const auto [ptr, ec] = std::from_chars(q, e, value);
      const bool ends_well = ptr == e || *ptr == ' ' || *ptr == '\t' || *ptr == '\r';
      if (ec != std::errc() || !ends_well || !std::isfinite(value))
        throw UserError(source, "line " + std::to_string(line_no),
                        std::string("malformed or non-finite number in '") + (is_v ? "v" : "vn") +
                            "' line");
      p = ptr;
      ++count;
    }
    if (count < 3)
      throw UserError(source, "line " + std::to_string(line_no),
                      std::string("'") + (is_v ? "v" : "vn") + "' line needs 3 numbers");
  }
}

}  // namespace

TriangleMesh parse_obj(const std::string& text, const std::string& source) {
  check_numbers(text, source);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  std::istringstream in(text);
  // No material reader: thaw scenes assign materials themselves; mtllib lines are ignored.
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, nullptr, true);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
    throw UserError(source, "", "malformed OBJ: " + (err.empty() ? std::string("parse failed") : err));
  }
  TriangleMesh mesh;
  const std::size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3;
  mesh.positions.resize(nv);
  for (std::size_t i = 0; i < nv; ++i)
    mesh.positions[i] = Vec3{attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]};
  bool all_normals = nn > 0;
  std::size_t face_count = 0;
  for (const auto& shape : shapes) {
    const auto& idx = shape.mesh.indices;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      if (shape.mesh.num_face_vertices[f] != 3)
        throw UserError(source, "", "face " + std::to_string(face_count + 1) + " could not be triangulated");
      std::array<std::uint32_t, 3> t{}, n{};
      for (int k = 0; k < 3; ++k) {
        const auto& vi = idx[3 * f + k];
        if (vi.vertex_index < 0 || static_cast<std::size_t>(vi.vertex_index) >= nv)
          throw UserError(source, "face " + std::to_string(face_count + 1),
                          "vertex index out of range (the file has " + std::to_string(nv) + " vertices)");
        t[k] = static_cast<std::uint32_t>(vi.vertex_index);
        if (vi.normal_index < 0) {
          all_normals = false;
        } else if (static_cast<std::size_t>(vi.normal_index) >= nn) {
          throw UserError(source, "face " + std::to_string(face_count + 1),
                          "normal index out of range (the file has " + std::to_string(nn) + " normals)");
        } else {
          n[k] = static_cast<std::uint32_t>(vi.normal_index);
        }
      }
      mesh.triangles.push_back(t);
      mesh.normal_indices.push_back(n);
      ++face_count;
    }
  }
  if (all_normals) {
    mesh.normals.resize(nn);
    for (std::size_t i = 0; i < nn; ++i) {
      const Vec3 n{attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]};
      const float len = length(n);
      if (!(len > 0.0f)) throw UserError(source, "normal " + std::to_string(i + 1), "zero-length normal");
      mesh.normals[i] = n / len;
    }
  } else {
    mesh.normal_indices.clear();
  }
  if (mesh.triangles.empty()) throw UserError(source, "", "OBJ file has no faces");
  if (auto problem = validate_mesh(mesh)) throw UserError(source, "", *problem);
  return mesh;
}

TriangleMesh load_obj(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw UserError(path.string(), "", "is a directory, expected an OBJ file");
  if (!std::filesystem::is_regular_file(path, ec)) throw UserError(path.string(), "", "OBJ file not found");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError(path.string(), "", "cannot be read");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_obj(buffer.str(), path.string());
}

}  // namespace thaw::render
