#pragma once
// Ray/infinite-plane intersection. Planes are not closed, so they are opaque only; they live
// outside the BVH (their bounds are infinite). Knows nothing about materials.
#include "render/math/ray.h"

namespace thaw::render {

/// t in (0, t_max) where `ray` meets the plane through `point` with unit `normal`.
inline bool intersect_plane(const Ray& ray, const Vec3& point, const Vec3& normal, float t_max,
                            float& t_hit) {
  const float denom = dot(ray.direction, normal);
  if (denom == 0.0f) return false;
  const float t = dot(point - ray.origin, normal) / denom;
  if (!(t > 0.0f) || !(t < t_max)) return false;
  t_hit = t;
  return true;
}

}  // namespace thaw::render
