#include "src/meshio/obj_writer.h"

#include <cstdio>

#include "src/common/atomic_file.h"
#include "src/common/check.h"

namespace thaw::meshio {

std::string format_obj(const TriangleMesh& mesh, const std::string& comment) {
  const bool normals = !mesh.normal_triangles.empty();
  THAW_CHECK(!normals || mesh.normal_triangles.size() == mesh.triangles.size(),
             "one normal triple per triangle");
  std::string out;
  out.reserve(mesh.vertices.size() * 70 + mesh.normals.size() * 40 + mesh.triangles.size() * 40 +
              256);
  if (!comment.empty()) out += "# " + comment + "\n";
  char buf[192];
  for (const auto& v : mesh.vertices) {
    const int n = std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g\n", v[0], v[1], v[2]);
    out.append(buf, static_cast<std::size_t>(n));
  }
  for (const auto& v : mesh.normals) {
    const int n = std::snprintf(buf, sizeof buf, "vn %.9g %.9g %.9g\n", v[0], v[1], v[2]);
    out.append(buf, static_cast<std::size_t>(n));
  }
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    const long long a = t[0] + 1, b = t[1] + 1, c = t[2] + 1;
    int n = 0;
    if (normals) {
      const auto& m = mesh.normal_triangles[f];
      n = std::snprintf(buf, sizeof buf, "f %lld//%lld %lld//%lld %lld//%lld\n", a,
                        static_cast<long long>(m[0] + 1), b, static_cast<long long>(m[1] + 1), c,
                        static_cast<long long>(m[2] + 1));
    } else {
      n = std::snprintf(buf, sizeof buf, "f %lld %lld %lld\n", a, b, c);
    }
    out.append(buf, static_cast<std::size_t>(n));
  }
  return out;
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::string& comment) {
  write_file_atomic(path, format_obj(mesh, comment));
}

}  // namespace thaw::meshio
