#include "src/mesh/obj_writer.h"

#include "base/atomic_file.h"
#include "base/obj_writer.h"

namespace thaw::mesh {

std::string format_obj(const TriangleMesh& mesh, const std::string& comment) {
  return meshio::format_obj(to_file_mesh(mesh), comment);
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::string& comment) {
  write_file_atomic(path, format_obj(mesh, comment));
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::string& comment, ObjBuffers& buffers) {
  to_file_mesh(mesh, buffers.file);
  meshio::format_obj(buffers.file, comment, buffers.text);
  write_file_atomic(path, buffers.text);
}

}  // namespace thaw::mesh
