// Tests render/math/vec3.h and ray.h: the bit-stepping next_float_up/down agree with
// std::nextafter (zeros, denormals, extremes, random values); offset origins leave the surface.
#include "render/math/vec3.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/math/ray.h"

namespace thaw::render {
namespace {

TEST(Vec3, NextFloatMatchesNextafter) {
  const float inf = std::numeric_limits<float>::infinity();
  for (float v : {0.0f, -0.0f, 1e-45f, -1e-45f, 1.0f, -1.0f, 3.4e38f, -3.4e38f}) {
    EXPECT_EQ(next_float_up(v), std::nextafter(v, inf)) << v;
    EXPECT_EQ(next_float_down(v), std::nextafter(v, -inf)) << v;
  }
  EXPECT_EQ(next_float_up(inf), inf);
  EXPECT_EQ(next_float_down(-inf), -inf);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1e3f, 1e3f);
  for (int i = 0; i < 100000; ++i) {
    const float v = u(rng);
    ASSERT_EQ(next_float_up(v), std::nextafter(v, inf));
    ASSERT_EQ(next_float_down(v), std::nextafter(v, -inf));
  }
}

TEST(Ray, OffsetOriginMovesToTheSideOfTheNewDirection) {
  const Vec3 p{1.0f, 0.0f, 2.0f}, err{1e-6f, 1e-6f, 1e-6f}, n{0, 1, 0};
  EXPECT_GT(offset_ray_origin(p, err, n, {0, 1, 0}).y, 1e-6f * 0.99f);
  EXPECT_LT(offset_ray_origin(p, err, n, {0.3f, -1, 0}).y, -1e-6f * 0.99f);
  EXPECT_EQ(Ray({{0, 0, 0}, {1, 2, 3}}).at(2.0f), (Vec3{2, 4, 6}));
}

}  // namespace
}  // namespace thaw::render
