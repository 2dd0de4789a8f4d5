#include "render/geometry/obj_loader.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include "src/common/error.h"
#include "src/meshio/obj_reader.h"

namespace thaw::render {

namespace {

/// The renderer's mesh (float positions, 32-bit indices, unit normals) from the file's.
TriangleMesh from_file_mesh(const meshio::TriangleMesh& file, const std::string& source) {
  constexpr auto max_index = static_cast<std::size_t>(std::numeric_limits<std::uint32_t>::max());
  if (file.vertices.size() > max_index || file.normals.size() > max_index)
    throw UserError(source, "", "more than 2^32 - 1 vertices or normals (the renderer's limit)");
  TriangleMesh mesh;
  mesh.positions.reserve(file.vertices.size());
  for (const auto& v : file.vertices)
    mesh.positions.push_back(
        Vec3(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])));
  mesh.triangles.reserve(file.triangles.size());
  for (const auto& t : file.triangles)
    mesh.triangles.push_back({static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]),
                              static_cast<std::uint32_t>(t[2])});
  for (std::size_t i = 0; i < file.normals.size(); ++i) {
    const auto& n = file.normals[i];
    const Vec3 v(static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2]));
    const float len = length(v);
    if (!(len > 0.0f))
      throw UserError(source, "normal " + std::to_string(i + 1), "zero-length normal");
    mesh.normals.push_back(v / len);
  }
  for (const auto& t : file.normal_triangles)
    mesh.normal_indices.push_back({static_cast<std::uint32_t>(t[0]),
                                   static_cast<std::uint32_t>(t[1]),
                                   static_cast<std::uint32_t>(t[2])});
  // Coordinates finite in double can overflow float (1e39): the renderer's own check.
  if (auto problem = validate_mesh(mesh)) throw UserError(source, "", *problem);
  return mesh;
}

}  // namespace

TriangleMesh parse_obj(const std::string& text, const std::string& source) {
  return from_file_mesh(meshio::parse_obj(text, source), source);
}

TriangleMesh load_obj(const std::filesystem::path& path) {
  return from_file_mesh(meshio::read_obj(path), path.string());
}

}  // namespace thaw::render
