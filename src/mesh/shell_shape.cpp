#include "src/mesh/shell_shape.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace thaw::mesh {

namespace {
double norm(const Vec3& v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}
}  // namespace

ShellShape ShellShape::from_geometry(const sim::ShellGeometry& g, double radius_m) {
  ShellShape s;
  s.geometry = g.geometry;
  s.radius_m = radius_m;
  switch (g.geometry) {
    case sim::Geometry::sphere:
      s.core_half_size_m = 0;
      break;
    case sim::Geometry::cylinder:
      s.core_half_size_m = 0.5 * g.length_m;
      break;
    case sim::Geometry::planar:
      s.core_half_size_m = 0.5 * g.lateral_size_m;
      break;
  }
  return s;
}

Vec3 ShellShape::closest_core_point(const Vec3& p) const {
  const double h = core_half_size_m;
  switch (geometry) {
    case sim::Geometry::sphere:
      return {0, 0, 0};
    case sim::Geometry::cylinder:
      return {0, 0, std::clamp(p[2], -h, h)};
    case sim::Geometry::planar:
      return {0, std::clamp(p[1], -h, h), std::clamp(p[2], -h, h)};
  }
  return {0, 0, 0};
}

double ShellShape::signed_distance(const Vec3& p) const {
  const Vec3 c = closest_core_point(p);
  return norm({p[0] - c[0], p[1] - c[1], p[2] - c[2]}) - radius_m;
}

Vec3 ShellShape::outward_normal(const Vec3& p) const {
  const Vec3 c = closest_core_point(p);
  const Vec3 d{p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  const double n = norm(d);
  if (!(n > 0)) return {1, 0, 0};
  return {d[0] / n, d[1] / n, d[2] / n};
}

double ShellShape::core_support(const Vec3& n) const {
  const double h = core_half_size_m;
  switch (geometry) {
    case sim::Geometry::sphere:
      return 0;
    case sim::Geometry::cylinder:
      return h * std::abs(n[2]);
    case sim::Geometry::planar:
      return h * (std::abs(n[1]) + std::abs(n[2]));
  }
  return 0;
}

// Steiner formula V(K + rB) = V(K) + A(K) r + M(K) r^2 + 4/3 pi r^3 for the flat/linear cores:
// a segment of length L has A = 0, M = pi L; a square of side S has A = 2 S^2, M = (pi/2) 4S.
double ShellShape::volume() const {
  const double r = radius_m, pi = std::numbers::pi, a = 2 * core_half_size_m;
  const double ball = 4.0 / 3.0 * pi * r * r * r;
  switch (geometry) {
    case sim::Geometry::sphere:
      return ball;
    case sim::Geometry::cylinder:
      return pi * r * r * a + ball;
    case sim::Geometry::planar:
      return 2 * a * a * r + 2 * pi * a * r * r + ball;
  }
  return 0;
}

double ShellShape::area() const {
  const double r = radius_m, pi = std::numbers::pi, a = 2 * core_half_size_m;
  const double ball = 4 * pi * r * r;
  switch (geometry) {
    case sim::Geometry::sphere:
      return ball;
    case sim::Geometry::cylinder:
      return 2 * pi * r * a + ball;
    case sim::Geometry::planar:
      return 2 * a * a + 4 * pi * a * r + ball;
  }
  return 0;
}

double ShellShape::bounding_radius() const {
  const double h = core_half_size_m;
  switch (geometry) {
    case sim::Geometry::sphere:
      return radius_m;
    case sim::Geometry::cylinder:
      return h + radius_m;
    case sim::Geometry::planar:
      return std::sqrt(2.0) * h + radius_m;
  }
  return radius_m;
}

double ShellShape::accuracy_length() const {
  return geometry == sim::Geometry::planar ? std::max(core_half_size_m, radius_m) : radius_m;
}

}  // namespace thaw::mesh
