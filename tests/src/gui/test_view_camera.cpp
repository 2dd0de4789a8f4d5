// The 3D view's camera moves (src/gui/view_camera.h) against their geometric definitions: an
// orbit is a rotation about the focal point (distance kept, the angles exact), a pan a
// translation by view heights along the camera's right and up, a dolly a division of the
// distance, the framing the bounding sphere tangent to the field of view. Tolerances: each
// result is a few dozen floating-point operations on values of order 1, so 1e-12 is ~1e4 ulps.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "src/gui/view_camera.h"

namespace thaw::gui {
namespace {

constexpr double kTol = 1e-12;
using V = std::array<double, 3>;

double distance(const V& a, const V& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}
double dot(const V& a, const V& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
void expect_near(const V& a, const V& b) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], kTol) << "component " << k;
}

/// On the +z axis, 2 from the focal point (1, 2, 3), y up, 30 degrees.
ViewCamera on_axis() {
  return {{1, 2, 5}, {1, 2, 3}, {0, 1, 0}, 30};
}

TEST(ViewCamera, AzimuthRotatesAboutTheViewUpThroughTheFocalPoint) {
  const ViewCamera c = orbit(on_axis(), 90, 0);
  // +90 degrees about +y (right-handed) takes +z to +x
  expect_near(c.position, {3, 2, 3});
  expect_near(c.focal_point, {1, 2, 3});
  expect_near(c.view_up, {0, 1, 0});
}

TEST(ViewCamera, ElevationMovesTheCameraUpAndKeepsTheViewUpOrthogonal) {
  const ViewCamera c = orbit(on_axis(), 0, 30);
  const double pi = std::numbers::pi;
  expect_near(c.position, {1, 2 + 2 * std::sin(pi / 6), 3 + 2 * std::cos(pi / 6)});
  const V dop{c.focal_point[0] - c.position[0], c.focal_point[1] - c.position[1],
              c.focal_point[2] - c.position[2]};
  EXPECT_NEAR(dot(dop, c.view_up), 0.0, kTol);
  EXPECT_NEAR(std::sqrt(dot(c.view_up, c.view_up)), 1.0, kTol);
  EXPECT_GT(c.view_up[1], 0.0);  // still upright
}

TEST(ViewCamera, AnOrbitKeepsTheDistanceToTheFocalPoint) {
  ViewCamera c = on_axis();
  for (int k = 0; k < 50; ++k) c = orbit(c, 7.3, -4.1 + 0.2 * k);
  EXPECT_NEAR(distance(c.position, c.focal_point), 2.0, kTol);
  expect_near(c.focal_point, {1, 2, 3});
}

TEST(ViewCamera, APanMovesPositionAndFocalPointByViewHeights) {
  const ViewCamera c = pan(on_axis(), 0.5, -0.25);
  // The view height at distance 2 with 30 degrees: 2 * 2 * tan(15 degrees); right is +x.
  const double h = 4 * std::tan(std::numbers::pi / 12);
  expect_near(c.position, {1 + 0.5 * h, 2 - 0.25 * h, 5});
  expect_near(c.focal_point, {1 + 0.5 * h, 2 - 0.25 * h, 3});
  expect_near(c.view_up, {0, 1, 0});
}

TEST(ViewCamera, ADollyDividesTheDistance) {
  const ViewCamera closer = dolly(on_axis(), 4.0);
  expect_near(closer.position, {1, 2, 3.5});
  expect_near(closer.focal_point, {1, 2, 3});
  const ViewCamera farther = dolly(on_axis(), 0.5);
  expect_near(farther.position, {1, 2, 7});
}

TEST(ViewCamera, FramingMakesTheBoundingSphereTangentToTheFieldOfView) {
  const std::array<double, 6> box{-1, 1, 0, 2, 4, 6};  // a cube of side 2 about (0, 1, 5)
  const double radius = std::sqrt(3.0);
  ViewCamera c = orbit(on_axis(), 40, 20);  // an oblique direction, kept
  const ViewCamera wide = frame_bounds(c, box, 1.5);
  expect_near(wide.focal_point, {0, 1, 5});
  const double half = 0.5 * 30 * std::numbers::pi / 180;
  EXPECT_NEAR(distance(wide.position, wide.focal_point) * std::sin(half), radius, kTol);
  // the direction from the focal point is the camera's before
  const double d0 = distance(c.position, c.focal_point);
  const double d1 = distance(wide.position, wide.focal_point);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR((wide.position[k] - wide.focal_point[k]) / d1,
                (c.position[k] - c.focal_point[k]) / d0, kTol);
  // A view taller than wide: the horizontal angle, narrower, decides.
  const ViewCamera tall = frame_bounds(c, box, 0.5);
  const double half_h = std::atan(std::tan(half) * 0.5);
  EXPECT_NEAR(distance(tall.position, tall.focal_point) * std::sin(half_h), radius, kTol);
}

}  // namespace
}  // namespace thaw::gui
