#pragma once
// Four triangles tested against one ray at once (SSE): the watertight test of triangle.h
// (Woop, Benthin & Wald 2013) evaluated lane-wise with the same operations in the same order, so
// each lane's result is bit-identical to intersect_triangle(); a lane whose edge function is
// exactly zero is redone by the scalar test (its double-precision fallback). BVH leaves of
// triangles are stored this way (structure of arrays, unused lanes repeat lane 0), like Embree's
// Triangle4. Knows nothing about meshes or the BVH.
#include <cstdint>

#include "render/geometry/triangle.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace thaw::render {

struct alignas(16) Triangle4 {
  /// p[vertex][axis][lane]
  float p[3][3][4];
  /// primitive index of each lane (unused lanes repeat lane 0)
  std::uint32_t prim[4];

  Vec3 vertex(int v, int lane) const { return {p[v][0][lane], p[v][1][lane], p[v][2][lane]}; }
  void set(int lane, const Vec3& a, const Vec3& b, const Vec3& c, std::uint32_t primitive) {
    const Vec3* v[3] = {&a, &b, &c};
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) p[j][k][lane] = (*v[j])[k];
    prim[lane] = primitive;
  }
};

#if defined(__SSE2__)
/// triangle_t_error() of triangle.h lane by lane, same operations in the same order.
inline __m128 t_error4(__m128 ax, __m128 ay, __m128 bx, __m128 by, __m128 cx, __m128 cy, __m128 az,
                       __m128 bz, __m128 cz, __m128 u, __m128 v, __m128 w, __m128 inv_det) {
  const __m128 sign = _mm_set1_ps(-0.0f);
  auto abs4 = [&](__m128 x) { return _mm_andnot_ps(sign, x); };
  auto max3 = [&](__m128 a, __m128 b, __m128 c) {
    return _mm_max_ps(_mm_max_ps(abs4(a), abs4(b)), abs4(c));
  };
  const __m128 max_zt = max3(az, bz, cz), max_xt = max3(ax, bx, cx), max_yt = max3(ay, by, cy);
  const __m128 g2 = _mm_set1_ps(gamma_bound(2)), g3 = _mm_set1_ps(gamma_bound(3)),
               g5 = _mm_set1_ps(gamma_bound(5));
  const __m128 delta_z = _mm_mul_ps(g3, max_zt);
  const __m128 delta_x = _mm_mul_ps(g5, _mm_add_ps(max_xt, max_zt));
  const __m128 delta_y = _mm_mul_ps(g5, _mm_add_ps(max_yt, max_zt));
  const __m128 delta_e = _mm_mul_ps(
      _mm_set1_ps(2.0f), _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(g2, max_xt), max_yt),
                                               _mm_mul_ps(delta_y, max_xt)),
                                    _mm_mul_ps(delta_x, max_yt)));
  const __m128 max_e = max3(u, v, w);
  const __m128 sum =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(g3, max_e), max_zt), _mm_mul_ps(delta_e, max_zt)),
                 _mm_mul_ps(delta_z, max_e));
  return _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(3.0f), sum), abs4(inv_det));
}
#endif

/// Closest hit among the four triangles for 0 < t < t_max; on a hit fills `hit`, `lane` and
/// returns true. With `any_hit` it returns at the first hit found (for shadow rays).
inline bool intersect_triangle4(const ShearedRay& r, const Triangle4& tri, float t_max,
                                TriangleHit& hit, int& lane, bool any_hit = false) {
#if defined(__SSE2__)
  const int kx = r.kx, ky = r.ky, kz = r.kz;
  const __m128 ox = _mm_set1_ps(r.origin[kx]), oy = _mm_set1_ps(r.origin[ky]),
               oz = _mm_set1_ps(r.origin[kz]);
  const __m128 sx = _mm_set1_ps(r.sx), sy = _mm_set1_ps(r.sy), sz = _mm_set1_ps(r.sz);
  // Same expression order as intersect_triangle: a = p0 - o; ax = a[kx] - sx * a[kz]; ...
  const __m128 a_x = _mm_sub_ps(_mm_load_ps(tri.p[0][kx]), ox),
               a_y = _mm_sub_ps(_mm_load_ps(tri.p[0][ky]), oy),
               a_z = _mm_sub_ps(_mm_load_ps(tri.p[0][kz]), oz);
  const __m128 b_x = _mm_sub_ps(_mm_load_ps(tri.p[1][kx]), ox),
               b_y = _mm_sub_ps(_mm_load_ps(tri.p[1][ky]), oy),
               b_z = _mm_sub_ps(_mm_load_ps(tri.p[1][kz]), oz);
  const __m128 c_x = _mm_sub_ps(_mm_load_ps(tri.p[2][kx]), ox),
               c_y = _mm_sub_ps(_mm_load_ps(tri.p[2][ky]), oy),
               c_z = _mm_sub_ps(_mm_load_ps(tri.p[2][kz]), oz);
  const __m128 ax = _mm_sub_ps(a_x, _mm_mul_ps(sx, a_z)), ay = _mm_sub_ps(a_y, _mm_mul_ps(sy, a_z));
  const __m128 bx = _mm_sub_ps(b_x, _mm_mul_ps(sx, b_z)), by = _mm_sub_ps(b_y, _mm_mul_ps(sy, b_z));
  const __m128 cx = _mm_sub_ps(c_x, _mm_mul_ps(sx, c_z)), cy = _mm_sub_ps(c_y, _mm_mul_ps(sy, c_z));
  const __m128 u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
  const __m128 v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
  const __m128 w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
  const __m128 zero = _mm_setzero_ps();
  const int exact_zero = _mm_movemask_ps(
      _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)), _mm_cmpeq_ps(w, zero)));
  const __m128 any_neg =
      _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u, zero), _mm_cmplt_ps(v, zero)), _mm_cmplt_ps(w, zero));
  const __m128 any_pos =
      _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u, zero), _mm_cmpgt_ps(v, zero)), _mm_cmpgt_ps(w, zero));
  // Most leaves' triangles miss the ray: where no lane passes the edge test and none needs the
  // scalar redo, the answer is already "no hit" (the rest below would mask every lane out).
  const __m128 mixed = _mm_and_ps(any_neg, any_pos);
  if (exact_zero == 0 && _mm_movemask_ps(mixed) == 0xf) return false;
  const __m128 det = _mm_add_ps(_mm_add_ps(u, v), w);
  const __m128 az = _mm_mul_ps(sz, a_z), bz = _mm_mul_ps(sz, b_z), cz = _mm_mul_ps(sz, c_z);
  const __m128 t_scaled =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(u, az), _mm_mul_ps(v, bz)), _mm_mul_ps(w, cz));
  const __m128 limit = _mm_mul_ps(_mm_set1_ps(t_max), det);
  const __m128 ok_neg =
      _mm_and_ps(_mm_cmplt_ps(det, zero),
                 _mm_and_ps(_mm_cmplt_ps(t_scaled, zero), _mm_cmpge_ps(t_scaled, limit)));
  const __m128 ok_pos =
      _mm_and_ps(_mm_cmpgt_ps(det, zero),
                 _mm_and_ps(_mm_cmpgt_ps(t_scaled, zero), _mm_cmple_ps(t_scaled, limit)));
  __m128 ok = _mm_andnot_ps(mixed, _mm_or_ps(ok_neg, ok_pos));
  // The same before the division: no lane ahead within t_max (as t_scaled against det says).
  if (exact_zero == 0 && _mm_movemask_ps(ok) == 0) return false;
  const __m128 inv_det = _mm_div_ps(_mm_set1_ps(1.0f), det);
  const __m128 t = _mm_mul_ps(t_scaled, inv_det);
  ok = _mm_and_ps(ok, _mm_cmplt_ps(t, _mm_set1_ps(t_max)));
  int mask = _mm_movemask_ps(ok) & ~exact_zero;
  if (mask)
    mask &= _mm_movemask_ps(
        _mm_cmpgt_ps(t, t_error4(ax, ay, bx, by, cx, cy, az, bz, cz, u, v, w, inv_det)));
  alignas(16) float ts[4], us[4], vs[4], ws[4];
  _mm_store_ps(ts, t);
  bool found = false;
  float best = t_max;
  if (mask) {
    if (any_hit) {
      lane = __builtin_ctz(static_cast<unsigned>(mask));
      return true;
    }
    _mm_store_ps(us, _mm_mul_ps(u, inv_det));
    _mm_store_ps(vs, _mm_mul_ps(v, inv_det));
    _mm_store_ps(ws, _mm_mul_ps(w, inv_det));
    while (mask) {
      const int i = __builtin_ctz(static_cast<unsigned>(mask));
      mask &= mask - 1;
      if (ts[i] < best) {
        best = ts[i];
        hit = {ts[i], us[i], vs[i], ws[i]};
        lane = i;
        found = true;
      }
    }
  }
  for (int i = 0; i < 4; ++i) {
    if (!(exact_zero & (1 << i))) continue;
    TriangleHit h;
    if (intersect_triangle(r, tri.vertex(0, i), tri.vertex(1, i), tri.vertex(2, i), best, h)) {
      best = h.t;
      hit = h;
      lane = i;
      found = true;
      if (any_hit) return true;
    }
  }
  return found;
#else
  bool found = false;
  for (int i = 0; i < 4; ++i) {
    TriangleHit h;
    if (intersect_triangle(r, tri.vertex(0, i), tri.vertex(1, i), tri.vertex(2, i), t_max, h)) {
      t_max = h.t;
      hit = h;
      lane = i;
      found = true;
      if (any_hit) return true;
    }
  }
  return found;
#endif
}

}  // namespace thaw::render
