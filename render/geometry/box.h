#pragma once
// Ray/axis-aligned box intersection (slab method, Kay & Kajiya 1986) reporting which face was hit,
// so the hit point can be snapped exactly onto that face. Knows nothing about materials.
#include <cmath>
#include <utility>

#include "render/math/ray.h"

namespace thaw::render {

/// Nearest t in (0, t_max) where `ray` meets the surface of the box [lo, hi]; `axis` is the axis
/// of the face hit and `high_side` whether it is the face at hi[axis].
inline bool intersect_box(const Ray& ray, const Vec3& lo, const Vec3& hi, float t_max, float& t_hit,
                          int& axis, bool& high_side) {
  float t_near = -std::numeric_limits<float>::infinity(),
        t_far = std::numeric_limits<float>::infinity();
  int near_axis = -1, far_axis = -1;
  bool near_high = false, far_high = false;
  for (int i = 0; i < 3; ++i) {
    const float d = ray.direction[i], o = ray.origin[i];
    if (d == 0.0f) {
      if (o < lo[i] || o > hi[i]) return false;
      continue;
    }
    float t0 = (lo[i] - o) / d, t1 = (hi[i] - o) / d;
    bool h0 = false, h1 = true;
    if (t0 > t1) {
      std::swap(t0, t1);
      std::swap(h0, h1);
    }
    if (t0 > t_near) {
      t_near = t0;
      near_axis = i;
      near_high = h0;
    }
    if (t1 < t_far) {
      t_far = t1;
      far_axis = i;
      far_high = h1;
    }
  }
  if (t_near > t_far) return false;
  if (t_near > 0.0f && near_axis >= 0) {
    if (!(t_near < t_max)) return false;
    t_hit = t_near;
    axis = near_axis;
    high_side = near_high;
    return true;
  }
  if (t_far > 0.0f && far_axis >= 0 && t_far < t_max) {
    t_hit = t_far;
    axis = far_axis;
    high_side = far_high;
    return true;
  }
  return false;
}

}  // namespace thaw::render
