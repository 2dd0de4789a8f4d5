// Tests the rough surfaces of the Whitted integrators (render/integrator/whitted_shading.h with
// render/material/microfacet.h) on whole renders: nested rough ice | water shells and a rough
// white metal ball in a uniform surround are invisible (the white furnace, RGB and spectral, at
// roughness 0.05, 0.3 and 0.7, within 1 % of the surround with the image's mean at least five
// standard errors inside that bound), a rough index-matched interface leaves the image as it is,
// and a rough interface does blur what is seen through it (the furnace does not pass trivially).
#include <gtest/gtest.h>

#include <cmath>

#include "render/integrator/whitted.h"
#include "render/scene/scene.h"
#include "tests/render/test_util.h"

namespace thaw::render {
namespace {

constexpr double kSurround = 0.5;

/// Two concentric spheres (ice shell around water) of roughness `roughness` in a uniform surround.
SceneDescription rough_furnace(double roughness, bool spectral) {
  SceneDescription d;
  d.image.width = d.image.height = 32;
  d.image.samples_per_pixel = 48;
  d.image.adaptive = false;
  d.image.background = {kSurround, kSurround, kSurround};
  d.image.max_depth = 64;
  d.image.min_weight = 1e-5;
  d.image.spectral = spectral ? ImageSettings::Spectral::on : ImageSettings::Spectral::off;
  d.caustics.enabled = false;
  d.camera.position = {0.0, 0.3, 2.6};
  d.camera.look_at = {0.0, 0.0, 0.0};
  d.camera.vertical_fov_deg = 45.0;
  d.media = {test::medium("air", 1.0), test::medium("ice", 1.31), test::medium("water", 1.33)};
  ObjectDescription o;
  o.shape = ObjectDescription::Shape::sphere;
  o.radius = 1.0;
  o.inside = "ice";
  o.outside = "air";
  o.roughness = roughness;
  d.objects.push_back(o);
  o.radius = 0.7;
  o.inside = "water";
  o.outside = "ice";
  d.objects.push_back(o);
  return d;
}

struct Stats {
  double mean, error;
};
/// Mean over the pixels covered by the ball (those that differ from the surround at all) and its
/// standard error (pixels are independent estimates: their own sampler points).
Stats ball_pixels(const Image& img) {
  double s = 0, s2 = 0;
  int n = 0;
  for (const Rgb& c : img.pixels()) {
    const double v = (double(c.r) + c.g + c.b) / 3.0;
    if (v == kSurround) continue;
    s += v;
    s2 += v * v;
    ++n;
  }
  const double mean = s / n;
  return {mean, std::sqrt(std::max(0.0, s2 / n - mean * mean) / (n - 1.0))};
}

class RoughFurnace : public ::testing::TestWithParam<double> {};

TEST_P(RoughFurnace, RoughNestedShellsAreInvisibleRgb) {
  const RenderResult r = render(build_scene(rough_furnace(GetParam(), false)));
  const Stats st = ball_pixels(r.image);
  ASSERT_LT(5.0 * st.error, 0.01 * kSurround);
  EXPECT_NEAR(st.mean, kSurround, 0.01 * kSurround);
  EXPECT_EQ(r.stats.medium_mismatches, 0u);
}

TEST_P(RoughFurnace, RoughNestedShellsAreInvisibleSpectral) {
  const RenderResult r = render(build_scene(rough_furnace(GetParam(), true)));
  const Stats st = ball_pixels(r.image);
  ASSERT_LT(5.0 * st.error, 0.01 * kSurround);
  EXPECT_NEAR(st.mean, kSurround, 0.01 * kSurround);
}

TEST_P(RoughFurnace, RoughWhiteMetalBallIsInvisible) {
  SceneDescription d = rough_furnace(0.0, false);
  d.objects.clear();
  MaterialDescription m;
  m.name = "steel";
  m.kind = MaterialDescription::Kind::metal;
  m.texture.color = {1.0, 1.0, 1.0};
  m.roughness = GetParam();
  d.materials.push_back(m);
  ObjectDescription o;
  o.shape = ObjectDescription::Shape::sphere;
  o.radius = 1.0;
  o.material = "steel";
  d.objects.push_back(o);
  const RenderResult r = render(build_scene(d));
  const Stats st = ball_pixels(r.image);
  ASSERT_LT(5.0 * st.error, 0.01 * kSurround);
  EXPECT_NEAR(st.mean, kSurround, 0.01 * kSurround);
}

INSTANTIATE_TEST_SUITE_P(Roughness, RoughFurnace, ::testing::Values(0.05, 0.3, 0.7));

/// A checker floor lit by ambient light alone, seen from above through a ball.
SceneDescription checker_scene(bool ball, double ball_ior, double roughness) {
  SceneDescription d;
  d.image.width = d.image.height = 32;
  d.image.samples_per_pixel = 4;
  d.image.adaptive = false;
  d.image.background = {0.2, 0.3, 0.4};
  d.image.max_depth = 16;
  d.caustics.enabled = false;
  d.ambient.intensity = 1.0;
  d.camera.position = {0.0, 3.0, 0.5};
  d.camera.look_at = {0.0, 0.0, 0.0};
  d.camera.vertical_fov_deg = 50.0;
  d.media = {test::medium("air", 1.0), test::medium("oil", ball_ior)};
  MaterialDescription m;
  m.name = "floor";
  m.texture.kind = TextureDescription::Kind::checker;
  m.texture.checker_size = 0.25;
  d.materials.push_back(m);
  ObjectDescription f;
  f.shape = ObjectDescription::Shape::plane;
  f.material = "floor";
  d.objects.push_back(f);
  if (ball) {
    ObjectDescription o;
    o.shape = ObjectDescription::Shape::sphere;
    o.center = {0.0, 0.8, 0.0};
    o.radius = 0.6;
    o.inside = "oil";
    o.outside = "air";
    o.roughness = roughness;
    d.objects.push_back(o);
  }
  return d;
}

TEST(RoughSurfaces, RoughIndexMatchedInterfaceIsInvisible) {
  const Image without = render(build_scene(checker_scene(false, 1.0, 0.0))).image;
  for (const double roughness : {0.05, 0.3, 0.7}) {
    const Image with = render(build_scene(checker_scene(true, 1.0, roughness))).image;
    double worst = 0;
    for (std::size_t i = 0; i < with.pixels().size(); ++i) {
      const Rgb a = with.pixels()[i], b = without.pixels()[i];
      worst = std::max({worst, std::abs(double(a.r) - b.r), std::abs(double(a.g) - b.g),
                        std::abs(double(a.b) - b.b)});
    }
    // Each crossing's weight is 1 to the compensation table's 0.2 % (test_microfacet.cpp), two
    // crossings per ray, pixel values <= 0.9.
    EXPECT_LT(worst, 0.9 * 2 * 2e-3) << roughness;
  }
}

TEST(RoughSurfaces, RoughGlassBlursWhatIsSeenThroughIt) {
  // The same ball as glass: smooth, the checker seen through it keeps its black and white; rough,
  // it is blurred towards the mean (so the furnace above is not passed by a no-op).
  auto contrast = [](const Image& img) {
    double lo = 1e9, hi = -1e9;
    for (int y = 12; y < 20; ++y)
      for (int x = 12; x < 20; ++x) {
        const double v = img.at(x, y).r;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    return hi - lo;
  };
  SceneDescription smooth_scene = checker_scene(true, 1.5, 0.0);
  SceneDescription rough_scene = checker_scene(true, 1.5, 0.7);
  // Enough samples that the rough ball's noise is well below the checker's contrast.
  smooth_scene.image.samples_per_pixel = rough_scene.image.samples_per_pixel = 256;
  const double smooth = contrast(render(build_scene(smooth_scene)).image);
  const double rough = contrast(render(build_scene(rough_scene)).image);
  EXPECT_GT(smooth, 0.5);
  EXPECT_LT(rough, 0.5 * smooth);
}

}  // namespace
}  // namespace thaw::render
