#include "src/pipeline/handoff_camera.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "render/scene/camera.h"
#include "src/pipeline/handoff_blender.h"

namespace thaw::pipeline {
namespace {

render::CameraDescription tilted_camera() {
  render::CameraDescription c;
  c.position = {0.3, 0.2, 0.5};
  c.look_at = {0.0, 0.03, -0.02};
  c.up = {0.1, 1.0, 0.0};  // not orthogonal to the view: the renderer orthogonalises it
  c.vertical_fov_deg = 35.0;
  return c;
}

TEST(HandoffCamera, WorldToNdcPutsThePointOfEachRendererRayOnItsPixel) {
  const render::CameraDescription c = tilted_camera();
  const int w = 640, h = 480;
  const CameraMatrices m = camera_matrices(c, w, h);
  const render::Camera rc(render::Vec3(0.3f, 0.2f, 0.5f), render::Vec3(0.0f, 0.03f, -0.02f),
                          render::Vec3(0.1f, 1.0f, 0.0f), 35.0, w, h);
  for (const auto& [x, y] : std::vector<std::pair<float, float>>{
           {0, 0}, {640, 0}, {0, 480}, {640, 480}, {320, 240}, {10.5f, 400.25f}}) {
    const render::Ray ray = rc.generate(x, y);
    for (double t : {0.1, 1.0, 7.0}) {
      const std::array<double, 3> p{c.position[0] + t * ray.direction.x,
                                    c.position[1] + t * ray.direction.y,
                                    c.position[2] + t * ray.direction.z};
      const auto px = project_to_pixel(m, p);
      // The renderer's camera basis is in float: 1e-6 relative of the 640-pixel image.
      EXPECT_NEAR(px[0], x, 2e-3) << x << " " << y << " t " << t;
      EXPECT_NEAR(px[1], y, 2e-3) << x << " " << y << " t " << t;
    }
  }
  EXPECT_NEAR(m.horizontal_fov_deg, 2 * std::atan(std::tan(17.5 * M_PI / 180) * 4 / 3) * 180 / M_PI,
              1e-12);
}

TEST(HandoffCamera, CameraSpaceLooksAlongMinusZWithTheCameraAtTheOrigin) {
  const render::CameraDescription c = tilted_camera();
  const CameraMatrices m = camera_matrices(c, 100, 50);
  const auto apply = [&](const std::array<double, 3>& p) {
    std::array<double, 3> q{};
    for (int i = 0; i < 3; ++i)
      q[i] = m.world_to_camera[4 * i] * p[0] + m.world_to_camera[4 * i + 1] * p[1] +
             m.world_to_camera[4 * i + 2] * p[2] + m.world_to_camera[4 * i + 3];
    return q;
  };
  const auto o = apply(c.position);
  for (double v : o) EXPECT_NEAR(v, 0.0, 1e-15);
  const auto target = apply(c.look_at);
  const double d = std::hypot(c.look_at[0] - c.position[0], c.look_at[1] - c.position[1],
                              c.look_at[2] - c.position[2]);
  EXPECT_NEAR(target[0], 0.0, 1e-15);
  EXPECT_NEAR(target[1], 0.0, 1e-15);
  EXPECT_NEAR(target[2], -d, 1e-15);
  // world_to_ndc is the product, and the EXR form is its transpose.
  const Matrix4 t = transposed(m.world_to_ndc);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_EQ(t[4 * j + i], m.world_to_ndc[4 * i + j]);
  EXPECT_EQ(transposed(t), m.world_to_ndc);
}

TEST(HandoffCamera, JsonHoldsTheCornerPointsOfTheRenderersRays) {
  const render::CameraDescription c = tilted_camera();
  const auto j = nlohmann::json::parse(camera_json(c, 160, 120));
  EXPECT_EQ(j["format"], "thaw-camera/1");
  ASSERT_EQ(j["corner_points"].size(), 4u);
  const CameraMatrices m = camera_matrices(c, 160, 120);
  for (const auto& corner : j["corner_points"]) {
    const auto px = project_to_pixel(m, corner["world_m"].get<std::array<double, 3>>());
    EXPECT_NEAR(px[0], corner["pixel"][0].get<double>(), 1e-3);
    EXPECT_NEAR(px[1], corner["pixel"][1].get<double>(), 1e-3);
  }
  EXPECT_EQ(j["world_to_ndc"].size(), 4u);
}

TEST(HandoffBlender, LightPowerMatchesThawsIrradianceOnAWhiteMatteSurface) {
  // Cycles: I = P / (4 pi), reflected radiance albedo E / pi; thaw: albedo E with E = I / d^2.
  const double p = blender_light_power_w(5.2, true, 2.0);
  EXPECT_NEAR(p / (4 * M_PI) / M_PI, 5.2, 1e-12);
  // No falloff: matched at the reference distance.
  EXPECT_NEAR(blender_light_power_w(5.2, false, 2.0), 4 * p, 1e-9);
}

}  // namespace
}  // namespace thaw::pipeline
