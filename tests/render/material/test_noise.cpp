// Tests the procedural noise of render/material/noise.h: values in range, deterministic, and
// filtered: a footprint wider than every feature returns the pattern's mean (what keeps the far
// table from aliasing), while a point lookup varies; and the mesh rotation of rotate_deg.
#include <gtest/gtest.h>

#include <cmath>

#include "render/geometry/triangle_mesh.h"
#include "render/material/noise.h"
#include "render/material/texture.h"

namespace thaw::render {
namespace {

TEST(Noise, PointLookupsVaryAndStayInRange) {
  for (const auto pattern : {Texture::Pattern::perlin, Texture::Pattern::worley,
                             Texture::Pattern::wood, Texture::Pattern::slate}) {
    Texture t;
    t.kind = Texture::Kind::noise;
    t.pattern = pattern;
    t.size = 0.1f;
    float lo = 1.0f, hi = 0.0f;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 p{0.0137f * float(i), 0.3f, 0.0071f * float(i)};
      const float v = t.noise_value(p, 0.0f);
      ASSERT_GE(v, 0.0f);
      ASSERT_LE(v, 1.0f);
      EXPECT_EQ(v, t.noise_value(p, 0.0f));  // deterministic
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    EXPECT_GT(hi - lo, 0.2f) << int(pattern);
  }
}

TEST(Noise, WideFootprintsFadeToTheMean) {
  // Every octave with f w >= 1/2 is replaced by its mean 0: perlin fBm at w = 1 is exactly 0.
  EXPECT_EQ(noise::fbm(Vec3{0.3f, 1.7f, -2.2f}, 1.0f, 8), 0.0f);
  EXPECT_NE(noise::fbm(Vec3{0.3f, 1.7f, -2.2f}, 0.0f, 8), 0.0f);
  EXPECT_EQ(noise::worley(Vec3{0.3f, 1.7f, -2.2f}, 1.0f), noise::kWorleyMean);
  Texture t;
  t.kind = Texture::Kind::noise;
  t.pattern = Texture::Pattern::perlin;
  t.color0 = {0.0f, 0.0f, 0.0f};
  t.color1 = {1.0f, 1.0f, 1.0f};
  for (int i = 0; i < 50; ++i) {
    const Rgb c =
        t.eval_filtered(Vec3{0.37f * float(i), 0.0f, 0.11f * float(i)}, Vec3{1.0f, 1.0f, 1.0f});
    EXPECT_EQ(c.g, 0.5f);
  }
}

TEST(Noise, NamesOfPatterns) {
  Texture::Pattern p;
  EXPECT_TRUE(noise_pattern_from_name("wood", p));
  EXPECT_EQ(p, Texture::Pattern::wood);
  EXPECT_FALSE(noise_pattern_from_name("marble", p));
}

TEST(RotateMesh, RightHandedTurnsAboutXThenYThenZ) {
  TriangleMesh m;
  m.positions = {Vec3{1.0f, 0.0f, 0.0f}, Vec3{0.0f, 1.0f, 0.0f}, Vec3{0.0f, 0.0f, 1.0f}};
  rotate_mesh(m, {0.0, 90.0, 0.0});  // about +y: x -> -z, z -> x
  EXPECT_NEAR(m.positions[0].z, -1.0f, 1e-6f);
  EXPECT_NEAR(m.positions[2].x, 1.0f, 1e-6f);
  EXPECT_NEAR(m.positions[1].y, 1.0f, 1e-6f);
  TriangleMesh n;
  n.positions = {Vec3{0.0f, 1.0f, 0.0f}};
  rotate_mesh(n, {90.0, 0.0, 90.0});  // x first: y -> z; then z: z stays
  EXPECT_NEAR(n.positions[0].z, 1.0f, 1e-6f);
}

}  // namespace
}  // namespace thaw::render
