// Tests render/geometry/plane.h.
#include "render/geometry/plane.h"

#include <gtest/gtest.h>

namespace thaw::render {
namespace {

TEST(Plane, HitsFromEitherSide) {
  float t;
  ASSERT_TRUE(intersect_plane(Ray{{0, 2, 0}, {0, -1, 0}}, {0, -1, 0}, {0, 1, 0}, 1e30f, t));
  EXPECT_FLOAT_EQ(t, 3.0f);
  ASSERT_TRUE(intersect_plane(Ray{{5, -3, 7}, {0, 1, 0}}, {0, -1, 0}, {0, 1, 0}, 1e30f, t));
  EXPECT_FLOAT_EQ(t, 2.0f);
}

TEST(Plane, ParallelBehindAndBeyondMiss) {
  float t;
  EXPECT_FALSE(intersect_plane(Ray{{0, 2, 0}, {1, 0, 0}}, {0, -1, 0}, {0, 1, 0}, 1e30f, t));
  EXPECT_FALSE(intersect_plane(Ray{{0, 2, 0}, {0, 1, 0}}, {0, -1, 0}, {0, 1, 0}, 1e30f, t));
  EXPECT_FALSE(intersect_plane(Ray{{0, 2, 0}, {0, -1, 0}}, {0, -1, 0}, {0, 1, 0}, 2.5f, t));
}

TEST(Plane, GrazingRayFarAway) {
  float t;
  const Vec3 d = normalize(Vec3{1, -1e-3f, 0});
  ASSERT_TRUE(intersect_plane(Ray{{0, 0, 0}, d}, {0, -1, 0}, {0, 1, 0}, 1e30f, t));
  // y = t d.y carries the relative rounding of t and d (a few ulp): |y + 1| <= 1e-5.
  EXPECT_NEAR(Ray({{0, 0, 0}, d}).at(t).y, -1.0f, 1e-5f);
}

}  // namespace
}  // namespace thaw::render
