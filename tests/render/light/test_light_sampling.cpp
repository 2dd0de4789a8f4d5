#include "render/light/light_sampling.h"

#include <gtest/gtest.h>

#include <cmath>

namespace thaw::render {
namespace {

SceneDescription floor_scene(bool blocker) {
  SceneDescription d;
  d.camera.position = {0, 2, 10};
  d.camera.look_at = {0, 0, 0};
  LightDescription l;
  l.kind = LightDescription::Kind::sphere;
  l.position = {0, 3, 0};
  l.radius = 0.5;
  l.intensity = 4.0;
  l.falloff = LightDescription::Falloff::inverse_square;
  l.samples = 16;
  d.lights.push_back(l);
  MaterialDescription m;
  m.name = "grey";
  d.materials.push_back(m);
  if (blocker) {
    ObjectDescription b;
    b.shape = ObjectDescription::Shape::box;
    b.box_min = {-5, 1, -5};
    b.box_max = {5, 1.1, 5};
    b.material = "grey";
    d.objects.push_back(b);
  }
  return d;
}

double irradiance(const Scene& scene, Vec3 p, Vec3 n, std::uint64_t& rays) {
  const sampling::PixelSampler sampler(1, 1);
  double e = 0;
  // Four camera samples' worth: the estimator's mean over them.
  for (std::uint32_t s = 0; s < 4; ++s) {
    sample_sphere_lights(scene, p, Vec3{1e-6f, 1e-6f, 1e-6f}, n, 1, {&sampler, s}, rays,
                         [&](std::size_t k, const Vec3& wi, float w) {
                           e += double(scene.sphere_lights()[k].radiance.r) * dot(wi, n) * w / 4.0;
                         });
  }
  return e;
}

TEST(LightSampling, UnoccludedSamplesSumToTheIrradiance) {
  // E = I / d^2 straight below the light (d = 3); 64 stratified samples, the integrand's
  // relative variation over the cap is cos^2 ~ 1 - (r/d)^2: error well under 1 %.
  const Scene scene = build_scene(floor_scene(false));
  std::uint64_t rays = 0;
  EXPECT_NEAR(irradiance(scene, {0, 0, 0}, {0, 1, 0}, rays), 4.0 / 9.0, 0.01 * 4.0 / 9.0);
  EXPECT_EQ(rays, 64u);
  // Facing away: no sample above the horizon, no shadow ray.
  rays = 0;
  EXPECT_EQ(irradiance(scene, {0, 0, 0}, {0, -1, 0}, rays), 0.0);
  EXPECT_EQ(rays, 0u);
}

TEST(LightSampling, ABlockerCastsAFullShadowAndTheLightItselfDoesNot) {
  std::uint64_t rays = 0;
  EXPECT_EQ(irradiance(build_scene(floor_scene(true)), {0, 0, 0}, {0, 1, 0}, rays), 0.0);
  // Right under the light's own sphere (bottom at y = 2.5), the emitter must not shadow itself.
  EXPECT_GT(irradiance(build_scene(floor_scene(false)), {0, 2.4f, 0}, {0, 1, 0}, rays), 0.0);
}

}  // namespace
}  // namespace thaw::render
