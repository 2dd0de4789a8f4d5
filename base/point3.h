#pragma once
// Vector arithmetic on the mesh files' points (std::array<double, 3>, as TriangleMesh holds them)
// for the code that works on those points without a vector type of its own: sim's OBJ shapes,
// the mesher's grid surfaces, inspect's mesh report. Header-only; knows nothing of the
// renderer's Vec3 (render/math), Eigen, CGAL or VTK.
#include <array>
#include <cmath>

namespace thaw::meshio {

using Point3 = std::array<double, 3>;

inline Point3 sub(const Point3& a, const Point3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline double dot(const Point3& a, const Point3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Point3& a) {
  return std::sqrt(dot(a, a));
}

}  // namespace thaw::meshio
