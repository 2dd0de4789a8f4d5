// Tests render/geometry/sphere.h: roots from outside and inside, tangent rays, precision far away.
#include "render/geometry/sphere.h"

#include <gtest/gtest.h>

namespace thaw::render {
namespace {

TEST(Sphere, FromOutsideNearRoot) {
  float t;
  ASSERT_TRUE(intersect_sphere(Ray{{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1.0f, 1e30f, t));
  EXPECT_FLOAT_EQ(t, 4.0f);
}

TEST(Sphere, FromInsideFarRoot) {
  float t;
  ASSERT_TRUE(intersect_sphere(Ray{{0, 0, 0.5f}, {0, 0, -1}}, {0, 0, 0}, 1.0f, 1e30f, t));
  EXPECT_FLOAT_EQ(t, 1.5f);
}

TEST(Sphere, MissesBehindBesideAndBeyondTMax) {
  float t;
  EXPECT_FALSE(intersect_sphere(Ray{{0, 0, 5}, {0, 0, 1}}, {0, 0, 0}, 1.0f, 1e30f, t));
  EXPECT_FALSE(intersect_sphere(Ray{{1.001f, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1.0f, 1e30f, t));
  EXPECT_FALSE(intersect_sphere(Ray{{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1.0f, 3.9f, t));
}

TEST(Sphere, UnnormalisedDirection) {
  float t;
  ASSERT_TRUE(intersect_sphere(Ray{{0, 0, 5}, {0, 0, -2}}, {0, 0, 0}, 1.0f, 1e30f, t));
  EXPECT_FLOAT_EQ(t, 2.0f);
}

TEST(Sphere, SmallSphereFarAwayIsAccurate) {
  // The naive quadratic loses all digits here (b^2 ~ 1e12 vs c ~ 1e12); Haines et al.'s form keeps
  // the hit within float rounding of the distance: |t - 99999| <= 4 ulp(1e5) ~ 0.03.
  float t;
  ASSERT_TRUE(intersect_sphere(Ray{{0, 0, 1e5f}, {0, 0, -1}}, {0, 0, 0}, 1.0f, 1e30f, t));
  EXPECT_NEAR(t, 99999.0f, 0.03f);
}

}  // namespace
}  // namespace thaw::render
