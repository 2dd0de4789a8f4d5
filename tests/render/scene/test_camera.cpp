// Tests render/scene/camera.h: centre ray along the view direction, field of view at the edges.
#include "render/scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace thaw::render {
namespace {

TEST(Camera, CentreAndEdgeRays) {
  const Camera cam({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 90.0, 200, 100);
  const Ray c = cam.generate(100, 50);
  EXPECT_NEAR(c.direction.z, -1.0f, 1e-6f);
  // Top edge at 45 deg (vertical fov 90); right edge at atan(2) for a 2:1 image; +x to the right.
  const Ray top = cam.generate(100, 0);
  EXPECT_NEAR(std::atan2(top.direction.y, -top.direction.z), M_PI / 4, 1e-6);
  const Ray right = cam.generate(200, 50);
  EXPECT_NEAR(std::atan2(right.direction.x, -right.direction.z), std::atan(2.0), 1e-6);
}

}  // namespace
}  // namespace thaw::render
