#include "render/geometry/obj_loader.h"

#include "base/obj_reader.h"

namespace thaw::render {

TriangleMesh parse_obj(const std::string& text, const std::string& source) {
  return from_file_mesh(meshio::parse_obj(text, source), source);
}

TriangleMesh load_obj(const std::filesystem::path& path) {
  return from_file_mesh(meshio::read_obj(path), path.string());
}

}  // namespace thaw::render
