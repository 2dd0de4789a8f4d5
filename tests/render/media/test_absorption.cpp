// Beer-Lambert absorption: transmittance through a slab is exp(-alpha d) per wavelength, with
// tabulated alpha interpolated linearly; the library's water and ice values are the sources'; the
// RGB renderer's per-channel coefficients are the slope of white light's channel transmittance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "render/format/medium_library.h"
#include "render/media/absorption.h"

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

/// Transmittance of white light (D65) through d metres in each linear-sRGB channel, from the
/// spectrum by direct quadrature (0.1 nm midpoints, independent of srgb_per_m's 1 nm loop);
/// `negative`: per channel, the mass of the channel's weights w_c(l) below zero (the sRGB
/// matching functions' negative lobes), relative to the channel's white.
LinearSrgb white_transmittance(const Absorption& a, double d, LinearSrgb* negative = nullptr) {
  Xyz kept, white;
  LinearSrgb neg;
  for (double l = 380.05; l < 780.0; l += 0.1) {
    const Xyz bar = cie_xyz_bar(l);
    const double e = illuminant_d65(l), t = std::exp(-a.per_m_at(l) * d);
    white.x += e * bar.x, white.y += e * bar.y, white.z += e * bar.z;
    kept.x += e * t * bar.x, kept.y += e * t * bar.y, kept.z += e * t * bar.z;
    const LinearSrgb c = xyz_to_linear_srgb(Xyz{e * bar.x, e * bar.y, e * bar.z});
    neg.r += std::max(0.0, -c.r), neg.g += std::max(0.0, -c.g), neg.b += std::max(0.0, -c.b);
  }
  const LinearSrgb k = xyz_to_linear_srgb(kept), w = xyz_to_linear_srgb(white);
  if (negative) *negative = {neg.r / w.r, neg.g / w.g, neg.b / w.b};
  return {k.r / w.r, k.g / w.g, k.b / w.b};
}

TEST(Absorption, SrgbCoefficientsOfAConstantAreThatConstant) {
  // The channel weights are normalised, so a wavelength-independent alpha comes back exactly.
  const LinearSrgb c = Absorption::constant(2.5).srgb_per_m();
  EXPECT_NEAR(c.r, 2.5, 1e-12);
  EXPECT_NEAR(c.g, 2.5, 1e-12);
  EXPECT_NEAR(c.b, 2.5, 1e-12);
  const LinearSrgb none = Absorption().srgb_per_m();
  EXPECT_EQ(none.r + none.g + none.b, 0.0);
}

TEST(Absorption, SrgbCoefficientsAreTheSlopeOfWhiteLightTransmittance) {
  // T_c(d) = sum_l w_c(l) exp(-alpha(l) d) with sum_l w_c = 1 (W_c = sum |w_c| = 1 + 2 N_c, N_c
  // the negative lobes' mass), so T_c(d) = 1 - a_c d + m2_c d^2 / 2 - ..., with the raw slope a_c
  // and m2_c = sum w_c alpha^2, |m2_c| <= W_c alpha_max^2. Hence
  // |T_c(d) - exp(-a_c d)| <= (W_c + 1) alpha_max^2 d^2 / 2 + O(d^3). srgb_per_m clamps a_c at 0;
  // a_c >= -N_c alpha_max, so the clamp adds at most N_c alpha_max d. Quadrature: < 1e-6.
  for (const char* name : {"ice-ih", "water-0c", "water-20c"}) {
    SCOPED_TRACE(name);
    const Absorption& a = *find_medium_preset(name)->absorption;
    double alpha_max = 0;
    for (double l = 380; l <= 780; l += 0.5) alpha_max = std::max(alpha_max, a.per_m_at(l));
    const LinearSrgb c = a.srgb_per_m();
    for (const double d : {0.01, 0.06}) {
      LinearSrgb n;
      const LinearSrgb t = white_transmittance(a, d, &n);
      auto bound = [&](double neg) {
        const double x = alpha_max * d;
        return (2.0 + 2.0 * neg) * x * x / 2.0 + 1.01 * neg * x + 1e-6;
      };
      EXPECT_NEAR(t.r, std::exp(-c.r * d), bound(n.r));
      EXPECT_NEAR(t.g, std::exp(-c.g * d), bound(n.g));
      EXPECT_NEAR(t.b, std::exp(-c.b * d), bound(n.b));
    }
    // Water and ice absorb red most (their blue-green colour); blue's raw slope is slightly
    // negative (its matching function's negative lobe sits where alpha is largest) and clamped.
    EXPECT_GT(c.r, c.g);
    EXPECT_GT(c.g, c.b);
    EXPECT_GE(c.b, 0.0);
    EXPECT_LT(c.r, alpha_max);
  }
  // Magnitudes quoted in the default scenario's comment (data/scenarios/default.toml).
  const LinearSrgb ice = find_medium_preset("ice-ih")->absorption->srgb_per_m();
  const LinearSrgb water = find_medium_preset("water-0c")->absorption->srgb_per_m();
  EXPECT_NEAR(ice.r, 0.21, 0.005);
  EXPECT_NEAR(ice.g, 0.042, 0.001);
  EXPECT_NEAR(water.r, 0.30, 0.005);
  EXPECT_NEAR(water.g, 0.046, 0.001);
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
