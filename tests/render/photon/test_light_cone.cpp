// Photon cones: targets from the dielectric objects, cone geometry and uniform directions.
#include "render/photon/light_cone.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/photon/low_discrepancy.h"
#include "tests/render/photon/photon_test_scenes.h"

namespace thaw::render::photon {
namespace {

using test::scene_from;

// The ice shell's water core is nested in the shell (inside its sphere, outside = the shell's
// inside): one target. An index-matched sphere is no target; a separate glass box is (its sphere
// through the corners), and so is a small glass ball standing in a water ring's sphere (its
// outside is not the ring's inside).
TEST(LightCone, TargetsDropNestedAndIndexMatchedObjects) {
  const Scene scene = scene_from(R"(
[[lights]]
position = [0.0, 10.0, 0.0]
[media.ice]
ior = 1.31
[media.water]
ior = 1.33
[media.matched]
ior = 1.0
[[objects]]
shape = "sphere"
center = [0.0, 0.0, 0.0]
radius = 1.0
inside = "ice"
outside = "vacuum"
[[objects]]
shape = "sphere"
center = [0.0, 0.0, 0.0]
radius = 0.7
inside = "water"
outside = "ice"
[[objects]]
shape = "sphere"
center = [5.0, 0.0, 0.0]
radius = 1.0
inside = "matched"
outside = "vacuum"
[[objects]]
shape = "box"
min = [-5.0, -1.0, -1.0]
max = [-3.0, 1.0, 1.0]
inside = "ice"
outside = "vacuum"
[[objects]]
shape = "sphere"
center = [-4.0, 1.3, 0.0]
radius = 0.1
inside = "water"
outside = "vacuum"
)" + test::kCamera);
  EXPECT_TRUE(scene.objects()[2].index_matched);
  EXPECT_FALSE(scene.objects()[0].index_matched);
  const auto targets = dielectric_targets(scene);
  ASSERT_EQ(targets.size(), 3u);
  EXPECT_NEAR(targets[2].radius, 0.1, 1e-5);  // widened by 1e-6 of the centre's coordinates
  EXPECT_NEAR(targets[0].radius, 1.0, 1e-5);
  EXPECT_NEAR(targets[1].center.x, -4.0, 1e-6);
  EXPECT_NEAR(targets[1].radius, std::sqrt(3.0), 1e-5);
  const auto cones = light_cones(emitters(scene), targets);
  ASSERT_EQ(cones.size(), 3u);
  // Smaller targets first: the ball (0.1), the shell (1), the box (sqrt 3).
  EXPECT_EQ(cones[0].target_index, 2u);
  EXPECT_EQ(cones[1].target_index, 0u);
  EXPECT_EQ(cones[2].target_index, 1u);
  // Solid angle of a sphere of radius 1 seen from 10: 2 pi (1 - sqrt(1 - 0.01)); the bounding
  // sphere is widened by 1e-6 relative, which widens the cone by 2e-6 relative.
  EXPECT_NEAR(cones[1].solid_angle_sr, 2 * M_PI * (1 - std::sqrt(0.99)),
              1e-5 * cones[1].solid_angle_sr);
  EXPECT_NEAR(cones[1].distance, 10.0, 1e-6);
}

// Directions lie inside the cone and are uniform in solid angle: E[cos theta] = (1 + cos_half) / 2
// and E[phi-components] = 0. With 4096 Halton points the quadrature error of these smooth
// integrands is far below 1e-3 of the cone's width (1 - cos_half).
TEST(LightCone, DirectionsUniformInsideTheCone) {
  LightCone c;
  c.axis = normalize(Vec3{0.3f, -1.0f, 0.2f});
  c.cos_half = std::cos(0.3);
  double sum_cos = 0;
  Vec3 sum{0, 0, 0};
  const int n = 4096;
  for (int i = 0; i < n; ++i) {
    const Vec3 d = c.direction(ScrambledHalton::sample(std::uint64_t(i), 0),
                               ScrambledHalton::sample(std::uint64_t(i), 1));
    EXPECT_NEAR(length(d), 1.0f, 1e-6f);
    EXPECT_GE(double(dot(d, c.axis)), c.cos_half - 1e-6);
    sum_cos += dot(d, c.axis);
    sum = sum + (d - c.axis * dot(d, c.axis));
  }
  const double width = 1 - c.cos_half;
  EXPECT_NEAR(sum_cos / n, (1 + c.cos_half) / 2, 1e-3 * width);
  EXPECT_NEAR(length(sum) / n, 0.0, 1e-3 * std::sin(0.3));
}

// A light inside the target's sphere sends photons everywhere.
TEST(LightCone, LightInsideTargetUsesTheWholeSphere) {
  const Scene scene = scene_from(R"(
[[lights]]
position = [0.0, 0.5, 0.0]
[media.glass]
ior = 1.5
[[objects]]
shape = "sphere"
center = [0.0, 0.0, 0.0]
radius = 1.0
inside = "glass"
outside = "vacuum"
)" + test::kCamera);
  const auto cones = light_cones(emitters(scene), dielectric_targets(scene));
  ASSERT_EQ(cones.size(), 1u);
  EXPECT_NEAR(cones[0].solid_angle_sr, 4 * M_PI, 1e-9);
  EXPECT_TRUE(cones[0].contains(Vec3{0, -1, 0}));
}

}  // namespace
}  // namespace thaw::render::photon
