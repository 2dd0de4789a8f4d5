#include "src/mesh/triangle_mesh.h"

#include <cmath>

namespace thaw::mesh {

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

double surface_area(const TriangleMesh& m) {
  double sum = 0;
  for (const auto& f : m.faces) {
    const auto& a = m.vertices[f[0]];
    const auto& b = m.vertices[f[1]];
    const auto& c = m.vertices[f[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    sum += 0.5 * std::sqrt(x * x + y * y + z * z);
  }
  return sum;
}

}  // namespace thaw::mesh
