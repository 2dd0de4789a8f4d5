#pragma once
// A ray: origin, direction (not necessarily unit) and the open parametric range (0, t_max) that is
// still of interest. Also the error-bounded origin offset that keeps secondary rays from hitting
// the surface they leave (pbrt-v4 OffsetRayOrigin; Waechter & Binder, Ray Tracing Gems ch. 6).
// Knows nothing about shapes or scenes.
#include <limits>

#include "render/math/vec3.h"

namespace thaw::render {

struct Ray {
  Vec3 origin;
  Vec3 direction;
  /// far end of the interval of interest (same units as the scene, in multiples of |direction|)
  float t_max = std::numeric_limits<float>::infinity();

  Vec3 at(float t) const { return origin + direction * t; }
};

/// Moves the hit point `p`, known to within +-`p_error` per coordinate, along the geometric normal
/// `n` by the error bound projected on it, to the side of `w` (the new ray's direction), and
/// rounds away from the surface, so the new ray cannot re-hit the surface it leaves at t > 0.
inline Vec3 offset_ray_origin(const Vec3& p, const Vec3& p_error, const Vec3& n, const Vec3& w) {
  const float d = dot(abs(n), p_error);
  Vec3 offset = n * d;
  if (dot(w, n) < 0.0f) offset = -offset;
  Vec3 po = p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0.0f)
      po[i] = next_float_up(po[i]);
    else if (offset[i] < 0.0f)
      po[i] = next_float_down(po[i]);
  }
  return po;
}

}  // namespace thaw::render
