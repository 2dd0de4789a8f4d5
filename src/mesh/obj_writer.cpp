#include "src/mesh/obj_writer.h"

#include "src/common/atomic_file.h"
#include "src/common/check.h"
#include "src/meshio/obj_writer.h"

namespace thaw::mesh {

std::string format_obj(const TriangleMesh& mesh, const std::string& comment) {
  const bool normals = !mesh.normals.empty();
  THAW_CHECK(!normals || mesh.normals.size() == mesh.vertices.size(), "one normal per vertex");
  // The file's own type (src/meshio): vertex normals are indexed like the vertices.
  meshio::TriangleMesh file;
  file.vertices = mesh.vertices;
  file.triangles.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) file.triangles.push_back({f[0], f[1], f[2]});
  if (normals) {
    file.normals = mesh.normals;
    file.normal_triangles = file.triangles;
  }
  return meshio::format_obj(file, comment);
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::string& comment) {
  write_file_atomic(path, format_obj(mesh, comment));
}

}  // namespace thaw::mesh
