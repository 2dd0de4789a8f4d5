#pragma once
// Watertight ray/triangle intersection (Woop, Benthin & Wald 2013, "Watertight Ray/Triangle
// Intersection", JCGT 2(1)): the ray is sheared so that it runs along +z, the three 2D edge
// functions are evaluated on the projected vertices, and exactly-zero edge functions are
// recomputed in double. Two triangles sharing an edge evaluate that edge function on the same
// float inputs with opposite sign, so a ray can never slip between them. Two-sided.
// A hit is accepted only if its t exceeds the rounding-error bound of t itself (Pharr, Jakob &
// Humphreys, PBR 3rd ed. sec. 3.9.6; pbrt-v4 Triangle::Intersect): t is computed from the
// vertices relative to the ray origin, so its error scales with the triangle's extent (a 200 m
// floor quad: ~1e-5), while a secondary ray's origin is offset only by the error of the hit
// point (~1e-7 there). Without this bound a shadow ray leaving a large triangle re-hits it at a
// rounding-noise t > 0: salt-and-pepper false shadows (issue 10 item 1).
// Knows nothing about meshes or the BVH.
#include <algorithm>
#include <cmath>
#include <utility>

#include "render/math/ray.h"

namespace thaw::render {

/// Per-ray constants of the watertight test, computed once per ray.
struct ShearedRay {
  Vec3 origin;
  int kx = 0, ky = 1, kz = 2;
  float sx = 0, sy = 0, sz = 1;

  ShearedRay() = default;
  explicit ShearedRay(const Ray& ray) : origin(ray.origin) {
    const Vec3& d = ray.direction;
    kz = max_dimension(abs(d));
    kx = kz + 1 == 3 ? 0 : kz + 1;
    ky = kx + 1 == 3 ? 0 : kx + 1;
    // Keep the winding of the projected triangle independent of the sign of d[kz].
    if (d[kz] < 0.0f) std::swap(kx, ky);
    sx = d[kx] / d[kz];
    sy = d[ky] / d[kz];
    sz = 1.0f / d[kz];
  }
};

/// Barycentric hit on a triangle: point = b0 p0 + b1 p1 + b2 p2, b0 = 1 - b1 - b2.
struct TriangleHit {
  float t, b0, b1, b2;
};

/// Bound on the rounding error of the computed t = (u az + v bz + w cz) / (u + v + w) from the
/// sheared vertex coordinates (x, y), the scaled z and the edge functions u, v, w (PBR 3rd ed.
/// eqs. 3.14-3.18: delta_z, delta_x, delta_y, delta_e, delta_t). The 4-wide test evaluates the
/// same expression in the same order lane by lane.
inline float triangle_t_error(float ax, float ay, float bx, float by, float cx, float cy, float az,
                              float bz, float cz, float u, float v, float w, float inv_det) {
  const float max_zt = std::max(std::max(std::fabs(az), std::fabs(bz)), std::fabs(cz));
  const float max_xt = std::max(std::max(std::fabs(ax), std::fabs(bx)), std::fabs(cx));
  const float max_yt = std::max(std::max(std::fabs(ay), std::fabs(by)), std::fabs(cy));
  const float delta_z = gamma_bound(3) * max_zt;
  const float delta_x = gamma_bound(5) * (max_xt + max_zt);
  const float delta_y = gamma_bound(5) * (max_yt + max_zt);
  const float delta_e =
      2.0f * (gamma_bound(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
  const float max_e = std::max(std::max(std::fabs(u), std::fabs(v)), std::fabs(w));
  return 3.0f * (gamma_bound(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) *
         std::fabs(inv_det);
}

/// Intersects the triangle (p0, p1, p2) for 0 < t < t_max. On a hit fills `hit` and returns true.
inline bool intersect_triangle(const ShearedRay& r, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                               float t_max, TriangleHit& hit) {
  const Vec3 a = p0 - r.origin, b = p1 - r.origin, c = p2 - r.origin;
  const float ax = a[r.kx] - r.sx * a[r.kz], ay = a[r.ky] - r.sy * a[r.kz];
  const float bx = b[r.kx] - r.sx * b[r.kz], by = b[r.ky] - r.sy * b[r.kz];
  const float cx = c[r.kx] - r.sx * c[r.kz], cy = c[r.ky] - r.sy * c[r.kz];
  float u = cx * by - cy * bx;
  float v = ax * cy - ay * cx;
  float w = bx * ay - by * ax;
  if (u == 0.0f || v == 0.0f || w == 0.0f) [[unlikely]] {
    // A float product of two floats is exact in double, so the sign here is exact (paper sec. 3).
    u = static_cast<float>(double(cx) * double(by) - double(cy) * double(bx));
    v = static_cast<float>(double(ax) * double(cy) - double(ay) * double(cx));
    w = static_cast<float>(double(bx) * double(ay) - double(by) * double(ax));
  }
  if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return false;
  const float det = u + v + w;
  if (det == 0.0f) return false;
  const float az = r.sz * a[r.kz], bz = r.sz * b[r.kz], cz = r.sz * c[r.kz];
  const float t_scaled = u * az + v * bz + w * cz;
  if (det < 0.0f) {
    if (t_scaled >= 0.0f || t_scaled < t_max * det) return false;
  } else {
    if (t_scaled <= 0.0f || t_scaled > t_max * det) return false;
  }
  const float inv_det = 1.0f / det;
  const float t = t_scaled * inv_det;
  if (!(t < t_max)) return false;
  if (!(t > triangle_t_error(ax, ay, bx, by, cx, cy, az, bz, cz, u, v, w, inv_det))) return false;
  hit = {t, u * inv_det, v * inv_det, w * inv_det};
  return true;
}

}  // namespace thaw::render
