// The shadow cone's tests are conservative: a shape it calls clear meets none of the segments
// from the apex to the light's ball; shapes on the axis are never called clear.
#include "render/geometry/shadow_cone.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace thaw::render {
namespace {

/// Distance from point c to the segment [a, b].
float segment_distance(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a;
  const float t = std::clamp(dot(c - a, ab) / dot(ab, ab), 0.0f, 1.0f);
  return length(a + ab * t - c);
}

// Random balls around a cone from the origin to a light ball of radius 0.5 at distance 4: for
// every ball called clear, no segment from the apex to 2000 points of the light ball (its
// surface and inside) comes within the ball's radius. Each ball called touching is counted, so
// the test also shows that most near-axis balls are caught (not a test that cannot fail: a cone
// that called everything clear would fail the first assertion).
TEST(ShadowCone, ClearBallsMeetNoSegment) {
  const Vec3 apex{0.1f, 0.2f, -0.3f}, light{1.0f, 4.0f, 0.5f};
  const float radius = 0.5f;
  const ShadowCone cone(apex, light, radius, 0.0f);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Vec3> targets;
  while (targets.size() < 2000) {
    const Vec3 q{u(rng), u(rng), u(rng)};
    if (dot(q, q) <= 1.0f) targets.push_back(light + q * radius);
  }
  int clear = 0, touching = 0;
  for (int i = 0; i < 3000; ++i) {
    const float s = 0.5f * (u(rng) + 1.0f);
    const Vec3 c = apex + (light - apex) * (0.5f * (u(rng) + 1.0f) * 1.3f - 0.1f) +
                   Vec3{u(rng), u(rng), u(rng)} * s;
    const float rho = 0.3f * (0.5f * (u(rng) + 1.0f));
    if (cone.may_touch_sphere(c, rho)) {
      ++touching;
      continue;
    }
    ++clear;
    for (const Vec3& t : targets) ASSERT_GT(segment_distance(apex, t, c), rho) << i;
  }
  EXPECT_GT(clear, 300);
  EXPECT_GT(touching, 300);
  // On the axis, in front of the light, behind the apex, beyond the light.
  EXPECT_TRUE(cone.may_touch_sphere(apex + (light - apex) * 0.5f, 0.01f));
  EXPECT_TRUE(cone.may_touch_box(apex + (light - apex) * 0.5f - Vec3{0.01f, 0.01f, 0.01f},
                                 apex + (light - apex) * 0.5f + Vec3{0.01f, 0.01f, 0.01f}));
  EXPECT_FALSE(cone.may_touch_sphere(apex - (light - apex) * 0.5f, 0.1f));
  EXPECT_FALSE(cone.may_touch_sphere(apex + (light - apex) * 2.0f, 0.1f));
}

// The four-box test is the one-box test lane by lane, bit for bit (the same operations in the
// same order), on boxes in, near and off the cone, with a slack, and skips empty slots.
TEST(ShadowCone, FourBoxesAsOne) {
  const Vec3 apex{0.1f, 0.2f, -0.3f}, light{1.0f, 4.0f, 0.5f};
  const ShadowCone cone(apex, light, 0.5f, 1e-4f);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int touching = 0;
  for (int k = 0; k < 2000; ++k) {
    float planes[6][4];
    bool want[4];
    for (int i = 0; i < 4; ++i) {
      const Vec3 c = apex + (light - apex) * (0.7f * (u(rng) + 1.0f) - 0.2f) +
                     Vec3{u(rng), u(rng), u(rng)} * 0.6f;
      const Vec3 e = Vec3{u(rng) + 1.0f, u(rng) + 1.0f, u(rng) + 1.0f} * 0.2f;
      const Vec3 lo = c - e, hi = c + e;
      for (int a = 0; a < 3; ++a) {
        planes[2 * a][i] = lo[a];
        planes[2 * a + 1][i] = hi[a];
      }
      want[i] = cone.may_touch_box(lo, hi);
    }
    if (k % 7 == 0) {  // an empty slot, as in a BVH node with fewer than four children
      for (int a = 0; a < 3; ++a) {
        planes[2 * a][3] = std::numeric_limits<float>::infinity();
        planes[2 * a + 1][3] = -std::numeric_limits<float>::infinity();
      }
      want[3] = false;
    }
    const unsigned got = cone.may_touch_boxes4(planes);
    for (int i = 0; i < 4; ++i) {
      ASSERT_EQ(bool(got & (1u << i)), want[i]) << k << " " << i;
      touching += want[i];
    }
  }
  EXPECT_GT(touching, 1000);
  EXPECT_LT(touching, 7000);
}

// The eight-box tests (an 8-wide BVH node's children): the SSE halves and, where the CPU has it,
// the AVX2 pass give the scalar test's answer for every box, empty slots never touching.
TEST(ShadowCone, EightBoxesAsOne) {
  const Vec3 apex{-0.2f, 0.1f, 0.4f}, light{-1.0f, 3.0f, 1.5f};
  const ShadowCone cone(apex, light, 0.3f, 1e-4f);
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int touching = 0;
  for (int k = 0; k < 2000; ++k) {
    alignas(32) float planes[6][8];
    bool want[8];
    for (int i = 0; i < 8; ++i) {
      const Vec3 c = apex + (light - apex) * (0.7f * (u(rng) + 1.0f) - 0.2f) +
                     Vec3{u(rng), u(rng), u(rng)} * 0.6f;
      const Vec3 e = Vec3{u(rng) + 1.0f, u(rng) + 1.0f, u(rng) + 1.0f} * 0.2f;
      const Vec3 lo = c - e, hi = c + e;
      for (int a = 0; a < 3; ++a) {
        planes[2 * a][i] = lo[a];
        planes[2 * a + 1][i] = hi[a];
      }
      want[i] = cone.may_touch_box(lo, hi);
    }
    if (k % 5 == 0) {  // empty slots, as in a node with fewer than eight children
      for (int i = 8 - 1 - k % 4; i < 8; ++i) {
        for (int a = 0; a < 3; ++a) {
          planes[2 * a][i] = std::numeric_limits<float>::infinity();
          planes[2 * a + 1][i] = -std::numeric_limits<float>::infinity();
        }
        want[i] = false;
      }
    }
    const unsigned sse = cone.may_touch_boxes8(planes);
    for (int i = 0; i < 8; ++i) {
      ASSERT_EQ(bool(sse & (1u << i)), want[i]) << k << " " << i;
      touching += want[i];
    }
#if THAW_AVX2_DISPATCH
    if (cpu_supports_avx2()) {
      ASSERT_EQ(cone.may_touch_boxes8_avx2(planes), sse) << k;
    }
#endif
  }
  EXPECT_GT(touching, 2000);
  EXPECT_LT(touching, 14000);
}

}  // namespace
}  // namespace thaw::render
