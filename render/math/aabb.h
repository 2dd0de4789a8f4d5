#pragma once
// Axis-aligned bounding box (float). Used by the BVH build and by shapes to report bounds.
#include <limits>

#include "render/math/vec3.h"

namespace thaw::render {

struct Aabb {
  Vec3 lo{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
          std::numeric_limits<float>::infinity()};
  Vec3 hi{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
          -std::numeric_limits<float>::infinity()};

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const Vec3& p) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  void extend(const Aabb& b) {
    lo = min(lo, b.lo);
    hi = max(hi, b.hi);
  }
  Vec3 extent() const { return hi - lo; }
  Vec3 center() const { return (lo + hi) * 0.5f; }
  /// Surface area [scene units^2]; 0 for an empty box.
  float area() const {
    if (empty()) return 0.0f;
    const Vec3 e = extent();
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
};

}  // namespace thaw::render
