#include "src/mesh/obj_writer.h"

#include <cstdio>

#include "src/common/atomic_file.h"
#include "src/common/check.h"

namespace thaw::mesh {

std::string format_obj(const TriangleMesh& mesh, const std::string& comment) {
  const bool normals = !mesh.normals.empty();
  THAW_CHECK(!normals || mesh.normals.size() == mesh.vertices.size(), "one normal per vertex");
  std::string out;
  out.reserve(mesh.vertices.size() * (normals ? 110 : 70) + mesh.faces.size() * 40 + 256);
  if (!comment.empty()) out += "# " + comment + "\n";
  char buf[160];
  for (const auto& v : mesh.vertices) {
    const int n = std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g\n", v[0], v[1], v[2]);
    out.append(buf, static_cast<std::size_t>(n));
  }
  for (const auto& v : mesh.normals) {
    const int n = std::snprintf(buf, sizeof buf, "vn %.9g %.9g %.9g\n", v[0], v[1], v[2]);
    out.append(buf, static_cast<std::size_t>(n));
  }
  for (const auto& f : mesh.faces) {
    const int a = f[0] + 1, b = f[1] + 1, c = f[2] + 1;
    const int n = normals ? std::snprintf(buf, sizeof buf, "f %d//%d %d//%d %d//%d\n", a, a, b, b, c, c)
                          : std::snprintf(buf, sizeof buf, "f %d %d %d\n", a, b, c);
    out.append(buf, static_cast<std::size_t>(n));
  }
  return out;
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh, const std::string& comment) {
  write_file_atomic(path, format_obj(mesh, comment));
}

}  // namespace thaw::mesh
