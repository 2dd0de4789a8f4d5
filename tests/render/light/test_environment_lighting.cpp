// Tests render/light/environment_lighting.h: under a uniform environment of radiance L a floor
// receives pi L (no ray cast where nothing opaque can hide the sky); a sphere light takes its cap
// out exactly (nothing counted twice); a dielectric ball lets the environment through; an opaque
// ball hides its cap (cosine-weighted share sin^2(sigma) straight above), found by stratified
// rays within the scrambled-net error bound; and a rendered matte floor shows albedo * L (the
// white furnace: the Lambertian BRDF).
#include "render/light/environment_lighting.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "render/integrator/whitted.h"
#include "tests/render/test_util.h"

namespace thaw::render {
namespace {

constexpr float kL = 0.5f;  // the environment's radiance

SceneDescription floor_under_uniform_sky() {
  SceneDescription d;
  d.camera.position = {0, 2, 10};
  d.camera.look_at = {0, 0, 0};
  d.image.background = {kL, kL, kL};
  d.environment.light_surfaces = true;
  MaterialDescription m;
  m.name = "grey";
  m.texture.color = {0.5, 0.5, 0.5};
  d.materials.push_back(m);
  ObjectDescription floor;
  floor.shape = ObjectDescription::Shape::plane;
  floor.point = {0, 0, 0};
  floor.normal = {0, 1, 0};
  floor.material = "grey";
  d.objects.push_back(floor);
  return d;
}

void add_ball(SceneDescription& d, bool dielectric, double radius = 0.5, double height = 1.0) {
  ObjectDescription b;
  b.shape = ObjectDescription::Shape::sphere;
  b.center = {0, height, 0};
  b.radius = radius;
  if (dielectric) {
    d.media.push_back(test::medium("glass", 1.5));
    b.inside = "glass";
    b.outside = "vacuum";
  } else {
    b.material = "grey";
  }
  d.objects.push_back(b);
}

/// Environment irradiance at floor point p from pixel (x, y)'s camera sample 0.
Rgb floor_irradiance(const Scene& scene, Vec3 p, std::uint64_t& rays, int x = 0, int y = 0) {
  const EnvironmentOccluders occluders(scene);
  const sampling::PixelSampler sampler(x, y);
  const Vec3 n{0, 1, 0};
  return environment_irradiance(scene, occluders, p, Vec3{1e-6f, 1e-6f, 1e-6f}, n, n, 0, 1,
                                {&sampler, 0}, rays);
}

TEST(EnvironmentLighting, UniformSkyGivesPiLWithoutRays) {
  const Scene scene = build_scene(floor_under_uniform_sky());
  std::uint64_t rays = 0;
  const Rgb e = floor_irradiance(scene, {0.3f, 0, -0.2f}, rays);
  EXPECT_NEAR(e.g, std::numbers::pi * kL, 1e-4);  // SH projection of a constant: rounding only
  EXPECT_EQ(rays, 0u);  // the floor's own plane cannot hide its upper hemisphere
}

TEST(EnvironmentLighting, SphereLightTakesItsCapOut) {
  SceneDescription d = floor_under_uniform_sky();
  LightDescription l;
  l.kind = LightDescription::Kind::sphere;
  l.position = {0, 2, 0};
  l.radius = 0.5;
  d.lights.push_back(l);
  const Scene scene = build_scene(d);
  std::uint64_t rays = 0;
  // Straight below the light: the cap's cosine-weighted solid angle is pi sin^2(sigma),
  // sin^2 = r^2 / d^2 = 1/16; no ray (the light sphere is not an occluder).
  const Rgb e = floor_irradiance(scene, {0, 0, 0}, rays);
  EXPECT_NEAR(e.g, std::numbers::pi * kL * (1.0 - 1.0 / 16.0), 1e-4);
  EXPECT_EQ(rays, 0u);
}

TEST(EnvironmentLighting, DielectricBallLetsTheSkyThrough) {
  SceneDescription d = floor_under_uniform_sky();
  add_ball(d, true);
  const Scene scene = build_scene(d);
  std::uint64_t rays = 0;
  EXPECT_NEAR(floor_irradiance(scene, {0, 0, 0}, rays).g, std::numbers::pi * kL, 1e-4);
  EXPECT_EQ(rays, 0u);
}

TEST(EnvironmentLighting, OpaqueBallHidesItsCap) {
  // Ball of radius 0.5 centred 1 above the point: hidden cosine-weighted share sin^2(sigma) =
  // 0.25. With 64 samples (one (0,6,2)-net, no refinement) per pixel, an Owen-scrambled net's
  // variance is at most 2 sigma^2 / N for an indicator (Owen 1997, b / (b - 1) in 2D): one pixel
  // errs by at most sqrt(2 * 0.25 * 0.75 / 64) = 0.077 (1 sd); the mean of 256 independently
  // scrambled pixels by 0.0048; 5 sd = 0.024.
  SceneDescription d = floor_under_uniform_sky();
  d.environment.occlusion_samples = 64;
  add_ball(d, false);
  const Scene scene = build_scene(d);
  std::uint64_t rays = 0;
  double sum = 0.0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) sum += floor_irradiance(scene, {0, 0, 0}, rays, x, y).g;
  const double hidden = 1.0 - sum / 256.0 / (std::numbers::pi * kL);
  EXPECT_NEAR(hidden, 0.25, 0.024);
  EXPECT_EQ(rays, 256u * 64u);
  // Far from the ball (its bounds below the horizon of nothing: they still reach above the
  // tangent plane, so rays are cast) every sample is seen: exact.
  EXPECT_NEAR(floor_irradiance(scene, {50, 0, 0}, rays).g, std::numbers::pi * kL, 1e-4);
}

TEST(EnvironmentLighting, FloorHidesTheLowerHalfFromAWall) {
  // A vertical surface 1 above an infinite floor sees sky in half its cosine-weighted hemisphere
  // (view factor (1 + cos 90) / 2): E = pi L / 2. The same net bound as above with p = 1/2:
  // sqrt(2 * 0.25 / 64) / sqrt(256) = 0.0055 (1 sd of the mean), 5 sd = 0.028.
  SceneDescription d = floor_under_uniform_sky();
  d.environment.occlusion_samples = 64;
  const Scene scene = build_scene(d);
  const EnvironmentOccluders occluders(scene);
  const Vec3 n{1, 0, 0};
  std::uint64_t rays = 0;
  double sum = 0.0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const sampling::PixelSampler sampler(x, y);
      sum += environment_irradiance(scene, occluders, {0, 1, 0}, Vec3{1e-6f, 1e-6f, 1e-6f}, n, n,
                                    1000, 1, {&sampler, 0}, rays)
                 .g;
    }
  EXPECT_NEAR(sum / 256.0 / (std::numbers::pi * kL), 0.5, 0.028);
  EXPECT_GT(rays, 0u);
}

TEST(EnvironmentLighting, RaysAreStratifiedAcrossThePixelsCameraSamples) {
  // The wall of the test above with one ray per camera sample (occlusion_samples = 1: one ray
  // always agrees with itself, so no penumbra rays): a pixel's 64 camera samples see the floor
  // with their 64 rays, points 0 .. 63 of one pair, a (0,6,2)-net. The floor hides a half-plane
  // through the centre of the unit square (the concentric map keeps lines through its centre),
  // which crosses at most 15 of the net's 8 x 8 elementary squares of one point each; only those
  // err, each by a Bernoulli of variance <= 1/4 (Owen scrambling: independent across squares),
  // so the pixel's hidden share errs by sqrt(15 / 4) / 64 = 0.030 (1 sd) at most. Rays spread
  // unstratified over the camera samples (every 8th point, as before) err as independent ones,
  // sqrt(1/4 / 64) = 0.0625: the RMS over 64 pixels must stay below 1.5 x 0.030.
  SceneDescription d = floor_under_uniform_sky();
  d.environment.occlusion_samples = 1;
  const Scene scene = build_scene(d);
  const EnvironmentOccluders occluders(scene);
  const Vec3 n{1, 0, 0};
  std::uint64_t rays = 0;
  double squares = 0.0;
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      const sampling::PixelSampler sampler(x, y);
      double sum = 0.0;
      for (std::uint32_t s = 0; s < 64; ++s)
        sum += environment_irradiance(scene, occluders, {0, 1, 0}, Vec3{1e-6f, 1e-6f, 1e-6f}, n, n,
                                      1000, 1, {&sampler, s}, rays)
                   .g;
      const double hidden = 1.0 - sum / 64.0 / (std::numbers::pi * kL);
      squares += (hidden - 0.5) * (hidden - 0.5);
    }
  }
  EXPECT_EQ(rays, 64u * 64u);
  EXPECT_LT(std::sqrt(squares / 64.0), 1.5 * 0.030);
}

TEST(EnvironmentLighting, RenderedMatteFloorShowsAlbedoTimesL) {
  SceneDescription d = floor_under_uniform_sky();
  d.camera.position = {0, 1, 0};
  d.camera.look_at = {0, 0, 0};
  d.camera.up = {0, 0, -1};
  d.image.width = 8;
  d.image.height = 8;
  const Scene scene = build_scene(d);
  const RenderResult r = render(scene, RenderOptions{});
  // The white furnace: the Lambertian BRDF albedo / pi under E = pi L shows albedo * L.
  EXPECT_NEAR(r.image.at(4, 4).g, 0.5 * kL, 1e-5);
}

TEST(EnvironmentLighting, HazeFadesASurfaceIntoTheHorizonSky) {
  // Aerial perspective: a surface 1 away behind haze of distance 2 keeps exp(-1/2) of its
  // radiance (the furnace's albedo L) and takes the rest from the horizon sky (here L).
  SceneDescription d = floor_under_uniform_sky();
  d.camera.position = {0, 1, 0};
  d.camera.look_at = {0, 0, 0};
  d.camera.up = {0, 0, -1};
  d.image.width = 8;
  d.image.height = 8;
  d.environment.haze_distance = 2.0;
  const RenderResult r = render(build_scene(d), RenderOptions{});
  // Pixel (4, 4)'s centre is half a pixel off the axis in x and y: tan(20 deg) / 8 each (the
  // default 40 degree field over 8 pixels), so t = sqrt(1 + 2 (tan(20 deg) / 8)^2).
  const double half_pixel = std::tan(20.0 * std::numbers::pi / 180.0) / 8.0;
  const double t = std::sqrt(1.0 + 2.0 * half_pixel * half_pixel);
  const double fade = std::exp(-t / 2.0);
  EXPECT_NEAR(r.image.at(4, 4).g, 0.5 * kL * fade + kL * (1.0 - fade), 1e-5);
}

}  // namespace
}  // namespace thaw::render
