#pragma once
// Ray/sphere intersection. Solved in double with the cancellation-free quadratic of Haines et al.,
// "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems ch. 7), so rays leaving a
// sphere from an offset origin do not re-hit it. Knows nothing about materials.
#include <cmath>

#include "render/math/ray.h"

namespace thaw::render {

/// Nearest t in (0, t_max) where `ray` meets the sphere (center, radius); false if none.
/// The roots are t0 = c / q and t1 = q / a (q = beta + sign(beta) sqrt(a disc), c = |f|^2 - r^2,
/// f = origin - center, beta = -f.d): only the root that can be the answer is divided out, and a
/// ray starting outside (c > 0) and heading away from the centre (beta < 0) has both roots
/// negative, so it is rejected before any division or square root (secondary and shadow rays
/// leaving the spheres they do not face). Every answer is bit for bit that of taking the smaller
/// positive of both roots (tests/render/geometry/test_sphere.cpp checks it on random rays).
inline bool intersect_sphere(const Ray& ray, const Vec3& center, float radius, float t_max,
                             float& t_hit) {
  const double fx = double(ray.origin.x) - center.x, fy = double(ray.origin.y) - center.y,
               fz = double(ray.origin.z) - center.z;
  const double dx = ray.direction.x, dy = ray.direction.y, dz = ray.direction.z;
  const double beta = -(fx * dx + fy * dy + fz * dz);
  const double r2 = double(radius) * radius;
  const double c = fx * fx + fy * fy + fz * fz - r2;
  if (c > 0.0 && beta < 0.0) return false;  // outside, moving away: t0, t1 < 0
  const double a = dx * dx + dy * dy + dz * dz;
  // |f + (beta/a) d|^2 is the squared distance of the line from the centre (no cancellation).
  const double inv_a = 1.0 / a;  // one division instead of two: s and t1 below
  const double s = beta * inv_a;
  const double lx = fx + s * dx, ly = fy + s * dy, lz = fz + s * dz;
  const double disc = r2 - (lx * lx + ly * ly + lz * lz);
  if (disc < 0.0) return false;
  const double q = beta + std::copysign(std::sqrt(a * disc), beta);
  if (q == 0.0) return false;
  double t;
  if (c > 0.0) {
    // Outside: q < 0 puts both roots behind the origin; else both lie ahead, take the nearer.
    if (q < 0.0) return false;
    double t0 = c / q, t1 = q * inv_a;
    if (t0 > t1) std::swap(t0, t1);
    t = t0 > 0.0 ? t0 : t1;
  } else {
    // Inside or on the sphere: the roots straddle the origin (c/a = t0 t1 <= 0); the one with
    // the sign of q lies ahead: t1 = q/a if q > 0, else t0 = c/q.
    t = q > 0.0 ? q * inv_a : c / q;
  }
  if (!(t > 0.0) || !(t < t_max)) return false;
  t_hit = static_cast<float>(t);
  return t_hit > 0.0f && t_hit < t_max;
}

}  // namespace thaw::render
