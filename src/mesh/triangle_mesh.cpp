#include "src/mesh/triangle_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "base/check.h"

namespace thaw::mesh {

meshio::TriangleMesh to_file_mesh(const TriangleMesh& mesh) {
  meshio::TriangleMesh file;
  to_file_mesh(mesh, file);
  return file;
}

void to_file_mesh(const TriangleMesh& mesh, meshio::TriangleMesh& file) {
  const bool normals = !mesh.normals.empty();
  THAW_CHECK(!normals || mesh.normals.size() == mesh.vertices.size(), "one normal per vertex");
  file.vertices = mesh.vertices;  // copy-assignment reuses the storage it has
  file.triangles.clear();
  for (const auto& f : mesh.faces) file.triangles.push_back({f[0], f[1], f[2]});
  file.normals.clear();
  file.normal_triangles.clear();
  if (normals) {
    file.normals = mesh.normals;
    file.normal_triangles = file.triangles;
  }
}

TriangleMesh from_file_mesh(const meshio::TriangleMesh& file) {
  THAW_CHECK(file.vertices.size() <= static_cast<std::size_t>(std::numeric_limits<int>::max()),
             "vertex indices fit in int");
  TriangleMesh mesh;
  mesh.vertices = file.vertices;
  mesh.faces.reserve(file.triangles.size());
  for (const auto& t : file.triangles)
    mesh.faces.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
  if (file.normals.size() == file.vertices.size() && file.normal_triangles == file.triangles)
    mesh.normals = file.normals;
  return mesh;
}

double enclosed_volume(const TriangleMesh& m) {
  double six_v = 0;
  for (const auto& f : m.faces) {
    const auto& a = m.vertices[f[0]];
    const auto& b = m.vertices[f[1]];
    const auto& c = m.vertices[f[2]];
    six_v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return six_v / 6.0;
}

void set_angle_weighted_normals(TriangleMesh& m) {
  using V = std::array<double, 3>;
  auto sub = [](const V& a, const V& b) { return V{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
  auto norm = [](const V& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); };
  m.normals.assign(m.vertices.size(), V{0, 0, 0});
  for (const auto& f : m.faces) {
    const V &a = m.vertices[f[0]], &b = m.vertices[f[1]], &c = m.vertices[f[2]];
    const V u = sub(b, a), v = sub(c, a);
    V n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = norm(n);
    if (!(len > 0)) continue;
    for (double& x : n) x /= len;
    for (int k = 0; k < 3; ++k) {
      const V e1 = sub(m.vertices[f[(k + 1) % 3]], m.vertices[f[k]]),
              e2 = sub(m.vertices[f[(k + 2) % 3]], m.vertices[f[k]]);
      const double l1 = norm(e1), l2 = norm(e2);
      if (!(l1 > 0 && l2 > 0)) continue;
      const double angle = std::acos(
          std::clamp((e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / (l1 * l2), -1.0, 1.0));
      for (int d = 0; d < 3; ++d) m.normals[static_cast<std::size_t>(f[k])][d] += angle * n[d];
    }
  }
  for (auto& n : m.normals) {
    const double len = norm(n);
    if (len > 0)
      for (double& x : n) x /= len;
    else
      n = {0, 1, 0};
  }
}

double surface_area(const TriangleMesh& m) {
  double sum = 0;
  for (const auto& f : m.faces) {
    const auto& a = m.vertices[f[0]];
    const auto& b = m.vertices[f[1]];
    const auto& c = m.vertices[f[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
                 z = u[0] * v[1] - u[1] * v[0];
    sum += 0.5 * std::sqrt(x * x + y * y + z * z);
  }
  return sum;
}

}  // namespace thaw::mesh
