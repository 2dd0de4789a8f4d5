#pragma once
// Test helper: rays leaving points of a large floor triangle (the two-triangle 200 x 200 floor of
// data/scenes/meshes/floor_200.obj at y = -1) from the error-offset origin the integrator uses,
// towards light positions all around. Used by the triangle and Triangle4 tests.
#include "render/geometry/triangle.h"

namespace thaw::render::test {

/// Calls fn(ray, p0, p1, p2) for a grid of hit points over the triangle and 24 light positions;
/// each ray's t range ends at the light (t = 1, unnormalised direction).
template <class Fn>
void for_each_ray_leaving_large_triangle(Fn&& fn) {
  const Vec3 a{-100, -1, -100}, b{-100, -1, 100}, c{100, -1, 100};
  const Vec3 ng = normalize(cross(b - a, c - a));
  for (int i = 0; i < 24; ++i) {
    for (int j = 0; j < 24; ++j) {
      // Barycentrics strictly inside: b1 + b2 < 1.
      const float b1 = (float(i) + 0.37f) / 24.0f, b2 = (1.0f - b1) * (float(j) + 0.61f) / 24.0f;
      const float b0 = 1.0f - b1 - b2;
      // As Scene::interaction: barycentric reconstruction and its error bound (pbrt-v4).
      const Vec3 p = a * b0 + b * b1 + c * b2;
      const Vec3 p_error = (abs(a * b0) + abs(b * b1) + abs(c * b2)) * gamma_bound(7);
      for (int k = 0; k < 24; ++k) {
        const float phi = 0.2618f * float(k), height = 0.5f + 1.5f * float(k % 5);
        const Vec3 light{-4.0f + 7.0f * std::cos(phi), height, 4.0f + 7.0f * std::sin(phi)};
        const Vec3 origin = offset_ray_origin(p, p_error, ng, light - p);
        fn(Ray{origin, light - origin, 1.0f - 1e-4f}, a, b, c);
      }
    }
  }
}

}  // namespace thaw::render::test
