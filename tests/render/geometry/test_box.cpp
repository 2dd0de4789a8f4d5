// Tests render/geometry/box.h: faces hit from outside and inside, parallel rays, edges.
#include "render/geometry/box.h"

#include <gtest/gtest.h>

namespace thaw::render {
namespace {

const Vec3 lo{-1, -1, -1}, hi{1, 1, 1};

TEST(Box, HitsNearFaceFromOutside) {
  float t;
  int axis;
  bool high;
  ASSERT_TRUE(intersect_box(Ray{{0, 0, 5}, {0, 0, -1}}, lo, hi, 1e30f, t, axis, high));
  EXPECT_FLOAT_EQ(t, 4.0f);
  EXPECT_EQ(axis, 2);
  EXPECT_TRUE(high);
}

TEST(Box, HitsFarFaceFromInside) {
  float t;
  int axis;
  bool high;
  ASSERT_TRUE(intersect_box(Ray{{0, 0, 0}, {-1, 0, 0}}, lo, hi, 1e30f, t, axis, high));
  EXPECT_FLOAT_EQ(t, 1.0f);
  EXPECT_EQ(axis, 0);
  EXPECT_FALSE(high);
}

TEST(Box, ParallelRayOutsideSlabMisses) {
  float t;
  int axis;
  bool high;
  EXPECT_FALSE(intersect_box(Ray{{0, 2, 5}, {0, 0, -1}}, lo, hi, 1e30f, t, axis, high));
  EXPECT_TRUE(intersect_box(Ray{{0, 0.999f, 5}, {0, 0, -1}}, lo, hi, 1e30f, t, axis, high));
}

TEST(Box, EdgeAndCornerAreHit) {
  float t;
  int axis;
  bool high;
  EXPECT_TRUE(
      intersect_box(Ray{{1, 1, 5}, {0, 0, -1}}, lo, hi, 1e30f, t, axis, high));  // along an edge
  EXPECT_TRUE(
      intersect_box(Ray{{3, 3, 3}, {-1, -1, -1}}, lo, hi, 1e30f, t, axis, high));  // at a corner
  EXPECT_NEAR(t, 2.0f, 1e-6f);
}

TEST(Box, BehindAndBeyondTMaxMiss) {
  float t;
  int axis;
  bool high;
  EXPECT_FALSE(intersect_box(Ray{{0, 0, 5}, {0, 0, 1}}, lo, hi, 1e30f, t, axis, high));
  EXPECT_FALSE(intersect_box(Ray{{0, 0, 5}, {0, 0, -1}}, lo, hi, 3.5f, t, axis, high));
}

}  // namespace
}  // namespace thaw::render
