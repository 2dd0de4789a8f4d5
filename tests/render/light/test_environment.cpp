// Tests render/light/environment.h: the constant background, and the sky's colours at the
// zenith, the horizon (continuous from above and below) and the ground, and its gradient.
#include "render/light/environment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

namespace thaw::render {
namespace {

TEST(Environment, ConstantIsTheBackgroundEverywhere) {
  Environment e;
  e.background = {0.25f, 0.3f, 0.4f};
  EXPECT_EQ(e.radiance({0, 1, 0}), e.background);
  EXPECT_EQ(e.radiance({0, -1, 0}), e.background);
}

TEST(Environment, SkyGradientAndGround) {
  Environment e;
  e.kind = Environment::Kind::sky;
  e.zenith = {0.0f, 0.0f, 1.0f};
  e.horizon = {1.0f, 1.0f, 1.0f};
  e.ground = {0.2f, 0.1f, 0.0f};
  e.exponent = 1.0f;
  EXPECT_EQ(e.radiance({0, 1, 0}), e.zenith);
  EXPECT_EQ(e.radiance({1, 0, 0}), e.horizon);
  EXPECT_EQ(e.radiance({0, -1, 0}), e.ground);
  // exponent 1: linear in sin(elevation); 30 degrees up is halfway.
  const Rgb mid = e.radiance({std::sqrt(0.75f), 0.5f, 0.0f});
  EXPECT_NEAR(mid.r, 0.5f, 1e-6f);
  EXPECT_NEAR(mid.b, 1.0f, 1e-6f);
  // Continuous across the horizon: just below is within 1e-3 / 0.035 of the horizon colour.
  const Rgb below = e.radiance(normalize(Vec3{1.0f, -1e-3f, 0.0f}));
  EXPECT_NEAR(below.r, 1.0f, 1e-3f / 0.035f);
  // Another zenith direction.
  e.up = {0, 0, 1};
  EXPECT_EQ(e.radiance({0, 0, 1}), e.zenith);
}

TEST(Environment, LatLongMapTurnsAboutUp) {
  // A map bright only at its centre texels (facing -z): unrotated it is seen towards -z; turned
  // +90 degrees (right-handed about +y) towards -x; -90 towards +x. Intensity scales it.
  std::vector<Rgb> texels(32, Rgb{0.1f, 0.1f, 0.1f});
  for (int j = 0; j < 4; ++j) texels[j * 8 + 3] = texels[j * 8 + 4] = Rgb{2.0f, 2.0f, 2.0f};
  Environment e;
  e.kind = Environment::Kind::latlong;
  e.map = std::make_shared<const LatLongMap>(8, 4, texels);
  e.map_scale = 1.5f;
  EXPECT_NEAR(e.radiance({0, 0, -1}).g, 3.0f, 1e-5f);
  EXPECT_NEAR(e.radiance({0, 0, 1}).g, 0.15f, 1e-5f);
  const double a = std::numbers::pi / 2;
  e.map_cos = static_cast<float>(std::cos(a)), e.map_sin = static_cast<float>(std::sin(a));
  EXPECT_NEAR(e.radiance({-1, 0, 0}).g, 3.0f, 1e-5f);
  EXPECT_NEAR(e.radiance({0, 0, -1}).g, 0.15f, 1e-5f);
  e.map_sin = -e.map_sin;
  EXPECT_NEAR(e.radiance({1, 0, 0}).g, 3.0f, 1e-5f);
}

}  // namespace
}  // namespace thaw::render
