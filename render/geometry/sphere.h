#pragma once
// Ray/sphere intersection. Solved in double with the cancellation-free quadratic of Haines et al.,
// "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems ch. 7), so rays leaving a
// sphere from an offset origin do not re-hit it. Knows nothing about materials.
#include <cmath>

#include "render/math/ray.h"

namespace thaw::render {

/// Nearest t in (0, t_max) where `ray` meets the sphere (center, radius); false if none.
inline bool intersect_sphere(const Ray& ray, const Vec3& center, float radius, float t_max,
                             float& t_hit) {
  const double fx = double(ray.origin.x) - center.x, fy = double(ray.origin.y) - center.y,
               fz = double(ray.origin.z) - center.z;
  const double dx = ray.direction.x, dy = ray.direction.y, dz = ray.direction.z;
  const double a = dx * dx + dy * dy + dz * dz;
  const double beta = -(fx * dx + fy * dy + fz * dz);
  // |f + (beta/a) d|^2 is the squared distance of the line from the centre (no cancellation).
  const double inv_a = 1.0 / a;  // one division instead of two: s and t1 below
  const double s = beta * inv_a;
  const double lx = fx + s * dx, ly = fy + s * dy, lz = fz + s * dz;
  const double r2 = double(radius) * radius;
  const double disc = r2 - (lx * lx + ly * ly + lz * lz);
  if (disc < 0.0) return false;
  const double c = fx * fx + fy * fy + fz * fz - r2;
  const double q = beta + std::copysign(std::sqrt(a * disc), beta);
  if (q == 0.0) return false;
  double t0 = c / q, t1 = q * inv_a;
  if (t0 > t1) std::swap(t0, t1);
  const double t = t0 > 0.0 ? t0 : t1;
  if (!(t > 0.0) || !(t < t_max)) return false;
  t_hit = static_cast<float>(t);
  return t_hit > 0.0f && t_hit < t_max;
}

}  // namespace thaw::render
