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

/// Mean over four camera samples of the irradiance the sampler reports at p (normal n), and the
/// number of specular (unoccluded) samples seen.
double irradiance(const Scene& scene, Vec3 p, Vec3 n, std::uint64_t& rays,
                  int* unoccluded = nullptr) {
  const sampling::PixelSampler sampler(1, 1);
  double e = 0;
  for (std::uint32_t s = 0; s < 4; ++s) {
    sample_sphere_lights(
        scene, p, Vec3{1e-6f, 1e-6f, 1e-6f}, n, n, 1, {&sampler, s}, rays,
        [&](std::size_t k, float f) { e += double(scene.sphere_lights()[k].radiance.r) * f / 4.0; },
        [&](std::size_t, const Vec3&, float) {
          if (unoccluded) ++*unoccluded;
        });
  }
  return e;
}

TEST(LightSampling, UnoccludedSamplesSumToTheIrradiance) {
  // E = I / d^2 straight below the light (d = 3), exactly: the unoccluded value is analytic and
  // every sample is visible (float rounding: 1e-6 relative). Tilted: I cos / d^2. Nothing lies
  // between the point and the light (Scene::light_unoccluded), so no shadow ray is cast, but the
  // highlight's 16 samples per camera sample are still drawn.
  const Scene scene = build_scene(floor_scene(false));
  std::uint64_t rays = 0;
  int seen = 0;
  EXPECT_NEAR(irradiance(scene, {0, 0, 0}, {0, 1, 0}, rays, &seen), 4.0 / 9.0, 1e-6);
  EXPECT_EQ(rays, 0u);
  EXPECT_EQ(seen, 64);
  const Vec3 tilted = normalize(Vec3{1, 2, 0});
  EXPECT_NEAR(irradiance(scene, {0, 0, 0}, tilted, rays), 4.0 / 9.0 * tilted.y, 1e-6);
  // Facing away: no sample above the horizon, no shadow ray.
  rays = 0;
  EXPECT_EQ(irradiance(scene, {0, 0, 0}, {0, -1, 0}, rays), 0.0);
  EXPECT_EQ(rays, 0u);
}

TEST(LightSampling, ABlockerCastsAFullShadowAndTheLightItselfDoesNot) {
  std::uint64_t rays = 0;
  EXPECT_EQ(irradiance(build_scene(floor_scene(true)), {0, 0, 0}, {0, 1, 0}, rays), 0.0);
  // The blocker lies in the shadow cone: the rays decide (16 per camera sample, all hidden).
  EXPECT_EQ(rays, 64u);
  // Right under the light's own sphere (bottom at y = 2.5), the emitter must not shadow itself.
  EXPECT_GT(irradiance(build_scene(floor_scene(false)), {0, 2.4f, 0}, {0, 1, 0}, rays), 0.0);
}

TEST(LightSampling, AllSeenWhereSomethingMayHideTheLightLooksTwice) {
  // A slab beside the shadow cone (x >= 0.4 at heights 1.5-1.6, where every ray from the origin
  // to the light, x / y <= tan(asin(0.5 / 3)) = 0.17, passes at x <= 0.27): its bounding sphere
  // meets the cone, so the rays must decide, and none is hidden. The first 16 are all seen, 16
  // more look for an occluder (2 n = 32 per camera sample, 4 camera samples), then the point
  // counts as fully lit: the exact unoccluded irradiance I / d^2 = 4/9, as with no slab.
  SceneDescription d = floor_scene(false);
  ObjectDescription b;
  b.shape = ObjectDescription::Shape::box;
  b.box_min = {0.4, 1.5, -5};
  b.box_max = {5, 1.6, 5};
  b.material = "grey";
  d.objects.push_back(b);
  std::uint64_t rays = 0;
  EXPECT_NEAR(irradiance(build_scene(d), {0, 0, 0}, {0, 1, 0}, rays), 4.0 / 9.0, 1e-6);
  EXPECT_EQ(rays, 4u * 32u);
}

}  // namespace
}  // namespace thaw::render
