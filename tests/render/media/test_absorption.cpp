// Beer-Lambert absorption: transmittance through a slab is exp(-alpha d) per wavelength, with
// tabulated alpha interpolated linearly; the library's water and ice values are the sources'.
#include <gtest/gtest.h>

#include <cmath>

#include "render/media/absorption.h"
#include "render/media/medium_library.h"
#include "src/common/error.h"

namespace thaw::render::media {
namespace {

SampledWavelengths fixed(float a, float b, float c, float d) {
  return SampledWavelengths::from(SampledSpectrum({a, b, c, d}), SampledSpectrum(1.0f / 400));
}

TEST(Absorption, ConstantSlab) {
  const Absorption a = Absorption::constant(2.0);
  const auto w = fixed(400, 500, 600, 700);
  const SampledSpectrum t = a.transmittance(0.25, w);
  for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_NEAR(t[i], std::exp(-0.5), 1e-7);
  // Two slabs in a row equal one of the summed thickness (multiplicativity).
  const SampledSpectrum t2 = a.transmittance(0.1, w) * a.transmittance(0.15, w);
  for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_NEAR(t2[i], t[i], 1e-7);
}

TEST(Absorption, TablePerWavelengthAndScale) {
  const Absorption a = Absorption::table({380, 580, 780}, {0.0, 1.0, 3.0});
  const auto w = fixed(380, 480, 680, 780);
  const double alpha[] = {0.0, 0.5, 2.0, 3.0};
  const double d = 0.7;
  const SampledSpectrum t = a.transmittance(d, w);
  for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_NEAR(t[i], std::exp(-alpha[i] * d), 1e-7);
  const SampledSpectrum t10 = a.scaled(10).transmittance(d, w);
  for (int i = 0; i < kSpectrumSamples; ++i)
    EXPECT_NEAR(t10[i], std::exp(-10 * alpha[i] * d), 1e-7);
  EXPECT_TRUE(a.scaled(0).is_zero());
  EXPECT_TRUE(Absorption().is_zero());
  EXPECT_FALSE(a.is_zero());
}

TEST(Absorption, LibraryWaterIsPopeAndFry) {
  // Pope & Fry 1997: minimum 0.00442 /m at 417.5 nm, 0.0565 /m at 550 nm, 0.624 /m at 700 nm.
  const Absorption& water = *find_medium_preset("water-20c")->absorption;
  EXPECT_DOUBLE_EQ(water.per_m_at(417.5), 0.00442);
  EXPECT_DOUBLE_EQ(water.per_m_at(550.0), 0.0565);
  EXPECT_DOUBLE_EQ(water.per_m_at(700.0), 0.624);
  // A metre of water keeps ~99.6 % of blue and ~54 % of 700 nm red: the water tint.
  EXPECT_GT(water.per_m_at(650.0), 50 * water.per_m_at(420.0));
}

TEST(Absorption, LibraryIceIsWarrenBrandt) {
  // alpha = 4 pi k / lambda with Warren & Brandt's k = 2.289e-9 at 550 nm -> 0.05230 /m.
  const Absorption& ice = *find_medium_preset("ice-ih")->absorption;
  EXPECT_NEAR(ice.per_m_at(550.0), 4 * M_PI * 2.289e-9 / 550e-9, 1e-4);
}

TEST(Absorption, NegativeAndUncoveredAreErrors) {
  try {
    Absorption::constant(-0.1).validate("scene.toml", "media.water");
    FAIL();
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("media.water.absorption_per_m"), std::string::npos);
  }
  EXPECT_THROW(Absorption::table({380, 780}, {0.1, -0.1}).validate("f", "media.x"), UserError);
  EXPECT_THROW(Absorption::table({400, 780}, {0.1, 0.1}).validate("f", "media.x"), UserError);
  EXPECT_THROW(Absorption::constant(0.1).scaled(-1).validate("f", "media.x"), UserError);
  EXPECT_NO_THROW(Absorption::table({380, 780}, {0.1, 0.2}).validate("f", "media.x"));
}

}  // namespace
}  // namespace thaw::render::media
