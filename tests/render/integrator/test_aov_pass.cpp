// Tests render/integrator/aov_pass.h against analytic answers: the depth of a plane facing the
// camera (the same at every pixel: camera-space z, not ray length), a sphere's depth, normal and
// ids pixel by pixel from the ray-sphere intersection in double, its alpha summed over the image
// against the area of its image (a circle), alpha 1 under a non-black background, and the
// result independent of the thread count.
#include "render/integrator/aov_pass.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "render/scene/scene.h"
#include "tests/render/test_util.h"

namespace thaw::render {
namespace {

/// Camera at the origin looking down -z, vertical field of view 60 degrees, black background.
SceneDescription camera_scene(int w, int h) {
  SceneDescription d;
  d.image.width = w;
  d.image.height = h;
  d.image.background = {0.0, 0.0, 0.0};
  d.camera.position = {0.0, 0.0, 0.0};
  d.camera.look_at = {0.0, 0.0, -1.0};
  d.camera.up = {0.0, 1.0, 0.0};
  d.camera.vertical_fov_deg = 60.0;
  MaterialDescription m;
  m.name = "grey";
  d.materials.push_back(m);
  return d;
}

TEST(AovPass, PlaneFacingTheCameraHasOneDepth) {
  const double distance = 7.5;
  SceneDescription d = camera_scene(40, 30);
  ObjectDescription plane;
  plane.shape = ObjectDescription::Shape::plane;
  plane.point = {3.0, -2.0, -distance};
  plane.normal = {0.0, 0.0, 1.0};
  plane.material = "grey";
  plane.label = "wall";
  d.objects.push_back(plane);
  const Scene scene = build_scene(d);
  const AovImage aov = render_aovs(scene);
  ASSERT_EQ(aov.width, 40);
  ASSERT_EQ(aov.object_names.at(0), "wall");
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      const std::size_t i = std::size_t(y) * 40 + x;
      // t from one float division, times a float dot product: a few ulps, < 1e-6 relative.
      EXPECT_NEAR(aov.depth[i], distance, 1e-5 * distance) << x << "," << y;
      EXPECT_EQ(aov.normal[i].z, 1.0f);
      EXPECT_EQ(aov.object_id[i], 1u);
      EXPECT_EQ(aov.medium_id[i], 0u);  // opaque
      EXPECT_EQ(aov.alpha[i], 1.0f);    // the plane covers every pixel
    }
  // The corner ray is ~1.3 times longer than the depth: a depth along the ray would fail above.
  const Ray corner = scene.camera().generate(0.5f, 0.5f);
  EXPECT_GT(1.0 / -corner.direction.z, 1.2);
}

TEST(AovPass, SphereDepthNormalIdsAndAlphaMatchTheAnalyticSphere) {
  const int w = 160, h = 120;
  const double cz = -5.0, r = 1.0;  // centre (0.4, 0.2, -5): off-axis, so z and t differ
  const double cx = 0.4, cy = 0.2;
  SceneDescription d = camera_scene(w, h);
  d.media.push_back(test::medium("ice", 1.31));
  ObjectDescription ball;
  ball.shape = ObjectDescription::Shape::sphere;
  ball.center = {cx, cy, cz};
  ball.radius = r;
  ball.inside = "ice";
  ball.outside = "vacuum";
  ball.label = "ball";
  d.objects.push_back(ball);
  const Scene scene = build_scene(d);
  const AovImage aov = render_aovs(scene);
  std::uint32_t ice = 0;
  for (std::size_t k = 0; k < aov.medium_names.size(); ++k)
    if (aov.medium_names[k] == "ice") ice = static_cast<std::uint32_t>(k + 1);
  ASSERT_GT(ice, 0u);
  int hits = 0, misses = 0, fractional = 0;
  double alpha_sum = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      alpha_sum += aov.alpha[i];
      fractional += aov.alpha[i] > 0.0f && aov.alpha[i] < 1.0f;
      const Ray ray = scene.camera().generate(x + 0.5f, y + 0.5f);
      const double dx = ray.direction.x, dy = ray.direction.y, dz = ray.direction.z;
      // |o + t d - c|^2 = r^2 with o = 0, |d| = 1: t^2 - 2 t (d.c) + |c|^2 - r^2 = 0
      const double b = dx * cx + dy * cy + dz * cz;
      const double disc = b * b - (cx * cx + cy * cy + cz * cz - r * r);
      if (disc > 0.04 * r * r) {  // clearly inside the silhouette: a well-conditioned root
        ++hits;
        const double t = b - std::sqrt(disc);
        // the view axis is -z: depth = t (d . -z)
        EXPECT_NEAR(aov.depth[i], t * -dz, 1e-4 * t) << x << "," << y;
        const double n[3] = {(t * dx - cx) / r, (t * dy - cy) / r, (t * dz - cz) / r};
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(aov.normal[i][a], n[a], 1e-3);
        EXPECT_EQ(aov.object_id[i], 1u);
        EXPECT_EQ(aov.medium_id[i], ice);  // the camera ray enters the ice
      } else if (disc < -0.04 * r * r) {
        ++misses;
        EXPECT_TRUE(std::isinf(aov.depth[i]));
        EXPECT_EQ(aov.object_id[i], 0u);
        EXPECT_EQ(aov.medium_id[i], 0u);
        EXPECT_EQ(aov.alpha[i], 0.0f);
      }
    }
  EXPECT_GT(hits, 500);
  EXPECT_GT(misses, 5000);
  EXPECT_GT(fractional, 20);  // the silhouette is anti-aliased
  // The sphere's image is an ellipse: the cone of half-angle asin(r / |c|) around the centre
  // direction cut by the image plane z = -1. Its area (in focal units) is
  // pi tan(a)^2 / cos(theta)^3 with theta the angle between centre direction and view axis
  // (the area of a cone section by a plane at angle theta, small-cone exact form below).
  const double dist = std::sqrt(cx * cx + cy * cy + cz * cz);
  const double half_angle = std::asin(r / dist), cos_theta = -cz / dist;
  const double tan_a = std::tan(half_angle);
  // exact area of the section of a circular cone by a plane at distance 1 (conic section):
  // pi * tan^2(a) / cos^3(theta) / (1 - tan^2(theta) tan^2(a))^(3/2)
  const double tan_t = std::sqrt(1.0 - cos_theta * cos_theta) / cos_theta;
  const double area_focal = std::numbers::pi * tan_a * tan_a / std::pow(cos_theta, 3) /
                            std::pow(1.0 - tan_t * tan_t * tan_a * tan_a, 1.5);
  const double pixels_per_focal = (h / 2.0) / std::tan(std::numbers::pi / 6.0);
  const double area_px = area_focal * pixels_per_focal * pixels_per_focal;
  // 2 x 2 stratified coverage errs only in pixels the silhouette crosses, by at most 1/2 each
  // on average over a smooth edge; those number about the perimeter (2 pi R for R ~ 20 px).
  const double perimeter_px = 2.0 * std::numbers::pi * std::sqrt(area_px / std::numbers::pi);
  EXPECT_NEAR(alpha_sum, area_px, 0.5 * perimeter_px);
}

TEST(AovPass, OpaqueAlphaUnderABackgroundAndThreadIndependence) {
  SceneDescription d = camera_scene(33, 21);
  d.image.background = {0.1, 0.2, 0.3};
  ObjectDescription ball;
  ball.shape = ObjectDescription::Shape::sphere;
  ball.center = {0.0, 0.0, -4.0};
  ball.radius = 1.0;
  ball.material = "grey";
  d.objects.push_back(ball);
  const Scene scene = build_scene(d);
  const AovImage one = render_aovs(scene, 1), two = render_aovs(scene, 2);
  for (float a : one.alpha) EXPECT_EQ(a, 1.0f);
  EXPECT_EQ(one.object_id, two.object_id);
  for (std::size_t i = 0; i < one.depth.size(); ++i) {
    EXPECT_EQ(std::isinf(one.depth[i]), std::isinf(two.depth[i]));
    if (!std::isinf(one.depth[i])) {
      EXPECT_EQ(one.depth[i], two.depth[i]);
    }
    EXPECT_EQ(one.normal[i].x, two.normal[i].x);
  }
  // the centre pixel sees the front of the ball at depth 3
  EXPECT_NEAR(one.depth[std::size_t(10) * 33 + 16], 3.0, 3e-3);
}

}  // namespace
}  // namespace thaw::render
