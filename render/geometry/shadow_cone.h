#pragma once
// The region swept by the shadow rays from one origin to a spherical light: every segment from
// the apex o to a point of the ball (centre c, radius R) lies in their convex hull, which lies in
// the cone of apex o, axis towards c and half-angle asin(R / |c - o|), cut at |c - o| + R along
// the axis. Conservative tests of spheres and boxes against that cone ("may touch": false only
// when nothing of the shape can meet any of the segments), so that a shading point whose cone
// touches nothing needs no shadow ray at all (Scene::light_unoccluded). A slack, added to every
// tested radius, absorbs the float rounding of the tests. Knows nothing about scenes or lights.
#include <algorithm>
#include <cmath>

#include "render/accel/simd_level.h"
#include "render/math/vec3.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace thaw::render {

class ShadowCone {
 public:
  /// `apex` outside the ball (|center - apex| > radius), `slack` >= 0 [scene units].
  ShadowCone(const Vec3& apex, const Vec3& center, float radius, float slack)
      : m_apex(apex), m_slack(slack) {
    const Vec3 v = center - apex;
    m_distance = length(v);
    m_axis = v / m_distance;
    m_sin = std::min(radius / m_distance, 1.0f);
    m_cos = std::sqrt(1.0f - m_sin * m_sin);
    m_far = m_distance + radius;
  }

  /// Whether the ball (c, rho) may meet the cone: within rho of the apex, or within the axial
  /// range [-rho, far + rho] and at an angle from the axis below theta + asin(rho / |c - o|)
  /// (the cone grown by the ball's angular radius).
  bool may_touch_sphere(const Vec3& c, float rho) const {
    rho += m_slack;
    const Vec3 v = c - m_apex;
    const float len2 = dot(v, v);
    if (len2 <= rho * rho) return true;
    const float x = dot(v, m_axis);
    if (x < -rho || x > m_far + rho) return false;
    const float len = std::sqrt(len2);
    const float sin_phi = rho / len, cos_phi = std::sqrt(1.0f - sin_phi * sin_phi);
    // cos(theta + phi); theta, phi <= pi / 2, so theta + phi <= pi and cos is decreasing there.
    const float cos_sum = m_cos * cos_phi - m_sin * sin_phi;
    return x >= cos_sum * len;
  }

  /// Whether the box [lo, hi] may meet the cone: its circumscribed ball does.
  bool may_touch_box(const Vec3& lo, const Vec3& hi) const {
    return may_touch_sphere((lo + hi) * 0.5f, 0.5f * length(hi - lo));
  }

  /// may_touch_box() of four boxes at once (SSE, the same operations in the same order, so
  /// the same results): boxes as planes[0..5] = lo_x, hi_x, lo_y, hi_y, lo_z, hi_z of lanes 0-3.
  /// Bit i of the result is set if box i may meet the cone; empty boxes (lo > hi) never do.
  unsigned may_touch_boxes4(const float (&planes)[6][4]) const { return touch4(planes, 0); }

  /// The same for eight boxes (an 8-wide BVH node's children), as two SSE halves.
  unsigned may_touch_boxes8(const float (&planes)[6][8]) const {
    return touch4(planes, 0) | touch4(planes, 4) << 4;
  }

#if THAW_AVX2_DISPATCH
  /// may_touch_boxes8() in one AVX2 pass: the same operations lane for lane, the same bits.
  THAW_TARGET_AVX2 unsigned may_touch_boxes8_avx2(const float (&planes)[6][8]) const {
    const __m256 half = _mm256_set1_ps(0.5f);
    __m256 lo[3], hi[3], v[3], e[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = _mm256_loadu_ps(planes[2 * a]);
      hi[a] = _mm256_loadu_ps(planes[2 * a + 1]);
      v[a] = _mm256_sub_ps(_mm256_mul_ps(_mm256_add_ps(lo[a], hi[a]), half),
                           _mm256_set1_ps(m_apex[a]));
      e[a] = _mm256_sub_ps(hi[a], lo[a]);
    }
    const __m256 ee =
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(e[0], e[0]), _mm256_mul_ps(e[1], e[1])),
                      _mm256_mul_ps(e[2], e[2]));
    const __m256 rho =
        _mm256_add_ps(_mm256_mul_ps(half, _mm256_sqrt_ps(ee)), _mm256_set1_ps(m_slack));
    const __m256 len2 =
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(v[0], v[0]), _mm256_mul_ps(v[1], v[1])),
                      _mm256_mul_ps(v[2], v[2]));
    const __m256 x = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(v[0], _mm256_set1_ps(m_axis.x)),
                                                 _mm256_mul_ps(v[1], _mm256_set1_ps(m_axis.y))),
                                   _mm256_mul_ps(v[2], _mm256_set1_ps(m_axis.z)));
    const __m256 len = _mm256_sqrt_ps(len2);
    const __m256 sin_phi = _mm256_div_ps(rho, len);
    const __m256 cos_phi =
        _mm256_sqrt_ps(_mm256_sub_ps(_mm256_set1_ps(1.0f), _mm256_mul_ps(sin_phi, sin_phi)));
    const __m256 cos_sum = _mm256_sub_ps(_mm256_mul_ps(_mm256_set1_ps(m_cos), cos_phi),
                                         _mm256_mul_ps(_mm256_set1_ps(m_sin), sin_phi));
    const __m256 near = _mm256_cmp_ps(len2, _mm256_mul_ps(rho, rho), _CMP_LE_OQ);
    const __m256 in_range =
        _mm256_and_ps(_mm256_cmp_ps(x, _mm256_sub_ps(_mm256_setzero_ps(), rho), _CMP_GE_OQ),
                      _mm256_cmp_ps(x, _mm256_add_ps(_mm256_set1_ps(m_far), rho), _CMP_LE_OQ));
    const __m256 in_cone =
        _mm256_and_ps(in_range, _mm256_cmp_ps(x, _mm256_mul_ps(cos_sum, len), _CMP_GE_OQ));
    const __m256 used = _mm256_cmp_ps(lo[0], hi[0], _CMP_LE_OQ);
    return static_cast<unsigned>(
        _mm256_movemask_ps(_mm256_and_ps(used, _mm256_or_ps(near, in_cone))));
  }
#endif

  const Vec3& apex() const {
    return m_apex;
  }
  const Vec3& axis() const {
    return m_axis;
  }

 private:
  /// may_touch_box() of the four boxes in lanes [offset, offset + 4) of planes[6][W].
  template <int W>
  unsigned touch4(const float (&planes)[6][W], int offset) const {
#if defined(__SSE2__)
    const __m128 half = _mm_set1_ps(0.5f);
    __m128 lo[3], hi[3], v[3], e[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = _mm_loadu_ps(planes[2 * a] + offset);
      hi[a] = _mm_loadu_ps(planes[2 * a + 1] + offset);
      v[a] = _mm_sub_ps(_mm_mul_ps(_mm_add_ps(lo[a], hi[a]), half), _mm_set1_ps(m_apex[a]));
      e[a] = _mm_sub_ps(hi[a], lo[a]);
    }
    const auto dot3 = [](const __m128* x, const __m128* y) {
      return _mm_add_ps(_mm_add_ps(_mm_mul_ps(x[0], y[0]), _mm_mul_ps(x[1], y[1])),
                        _mm_mul_ps(x[2], y[2]));
    };
    const __m128 rho = _mm_add_ps(_mm_mul_ps(half, _mm_sqrt_ps(dot3(e, e))), _mm_set1_ps(m_slack));
    const __m128 len2 = dot3(v, v);
    const __m128 axis[3] = {_mm_set1_ps(m_axis.x), _mm_set1_ps(m_axis.y), _mm_set1_ps(m_axis.z)};
    const __m128 x = dot3(v, axis);
    const __m128 len = _mm_sqrt_ps(len2);
    const __m128 sin_phi = _mm_div_ps(rho, len);
    const __m128 cos_phi = _mm_sqrt_ps(_mm_sub_ps(_mm_set1_ps(1.0f), _mm_mul_ps(sin_phi, sin_phi)));
    const __m128 cos_sum = _mm_sub_ps(_mm_mul_ps(_mm_set1_ps(m_cos), cos_phi),
                                      _mm_mul_ps(_mm_set1_ps(m_sin), sin_phi));
    const __m128 near = _mm_cmple_ps(len2, _mm_mul_ps(rho, rho));
    const __m128 in_range = _mm_and_ps(_mm_cmpge_ps(x, _mm_sub_ps(_mm_setzero_ps(), rho)),
                                       _mm_cmple_ps(x, _mm_add_ps(_mm_set1_ps(m_far), rho)));
    const __m128 in_cone = _mm_and_ps(in_range, _mm_cmpge_ps(x, _mm_mul_ps(cos_sum, len)));
    const __m128 used = _mm_cmple_ps(lo[0], hi[0]);
    return static_cast<unsigned>(_mm_movemask_ps(_mm_and_ps(used, _mm_or_ps(near, in_cone))));
#else
    unsigned mask = 0;
    for (int i = 0; i < 4; ++i) {
      const Vec3 lo{planes[0][offset + i], planes[2][offset + i], planes[4][offset + i]};
      const Vec3 hi{planes[1][offset + i], planes[3][offset + i], planes[5][offset + i]};
      if (!(lo.x > hi.x) && may_touch_box(lo, hi)) mask |= 1u << i;
    }
    return mask;
#endif
  }

  Vec3 m_apex, m_axis;
  float m_distance = 0, m_sin = 0, m_cos = 1, m_far = 0, m_slack = 0;
};

}  // namespace thaw::render
