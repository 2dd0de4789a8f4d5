// render's core alone (thaw_render_core: no TOML, no JSON; this binary links nothing else): a
// scene described in code is checked by the scene rules, built and rendered without the file
// layer (render/format/scene_parser.h, render/format/medium_parser.h). A core that reached for a
// file format would not link.
#include <gtest/gtest.h>

#include <cmath>

#include "base/error.h"
#include "render/integrator/whitted.h"
#include "render/scene/scene.h"
#include "render/scene/scene_rules.h"

namespace thaw::render {
namespace {

SceneDescription ball_scene() {
  SceneDescription d;
  d.image.width = d.image.height = 16;
  d.image.background = {0.2, 0.3, 0.4};
  d.camera.position = {0, 0, 5};
  d.camera.look_at = {0, 0, 0};
  d.camera.vertical_fov_deg = 40;
  LightDescription light;
  light.position = {0, 0, 5};
  d.lights.push_back(light);
  MaterialDescription grey;
  grey.name = "grey";
  d.materials.push_back(grey);
  ObjectDescription ball;
  ball.radius = 1.0;
  ball.material = "grey";
  d.objects.push_back(ball);
  return d;
}

TEST(RenderCore, RendersASceneBuiltInCode) {
  const Scene scene = build_scene(ball_scene());
  const RenderResult r = render(scene);
  // A corner ray passes 20+ degrees off axis, the ball subtends asin(1/5) = 11.5: background.
  const Rgb corner = r.image.at(0, 0);
  EXPECT_FLOAT_EQ(corner.r, 0.2f);
  EXPECT_FLOAT_EQ(corner.b, 0.4f);
  // The centre sees the lit ball, not the background.
  const Rgb centre = r.image.at(8, 8);
  EXPECT_TRUE(std::isfinite(centre.r));
  EXPECT_NE(centre.b, 0.4f);
}

TEST(RenderCore, RulesNameTheKeyWithoutTheParser) {
  SceneDescription d = ball_scene();
  d.camera.vertical_fov_deg = 180;
  const auto problem = find_scene_problem(d);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->key, "camera.vertical_fov_deg");
  EXPECT_THROW(build_scene(d), UserError);
}

}  // namespace
}  // namespace thaw::render
