#include "src/mesh/obj_writer.h"

#include "src/common/atomic_file.h"
#include "src/meshio/obj_writer.h"

namespace thaw::mesh {

std::string format_obj(const TriangleMesh& mesh, const std::string& comment) {
  return meshio::format_obj(to_file_mesh(mesh), comment);
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::string& comment) {
  write_file_atomic(path, format_obj(mesh, comment));
}

}  // namespace thaw::mesh
