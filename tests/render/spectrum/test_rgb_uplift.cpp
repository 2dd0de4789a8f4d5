// Smits uplifting: the key property that a scene without dispersion renders the same
// spectrally as in RGB: uplift(rgb) lit by white (unit D65), integrated with the CIE functions
// (by dense quadrature: the Monte-Carlo expectation of the film estimator) and converted to
// sRGB gives rgb back within 1/255 per channel. Also bounds and illuminant scaling.
#include <gtest/gtest.h>

#include <random>

#include "render/spectrum/colour.h"
#include "render/spectrum/rgb_uplift.h"

namespace thaw::render {
namespace {

template <class F>
LinearSrgb render_white_lit(F spectrum) {
  // Midpoint rule at 0.05 nm; the integrand is piecewise smooth with jumps only at the 10 nm
  // bin edges, where the midpoint rule's error is O(h * jump) per edge: < 1e-5 in total.
  Xyz r;
  const double h = 0.05;
  for (double l = kLambdaMinNm + h / 2; l < kLambdaMaxNm; l += h) {
    const Xyz b = cie_xyz_bar(l);
    const double s = spectrum(l) * h;
    r.x += s * b.x;
    r.y += s * b.y;
    r.z += s * b.z;
  }
  return xyz_to_linear_srgb(r);
}

void expect_round_trip(const LinearSrgb& rgb) {
  const RgbReflectanceSpectrum refl(rgb);
  const LinearSrgb out = render_white_lit([&](double l) { return refl(l) * illuminant_d65(l); });
  const double tol = 1.0 / 255.0;
  EXPECT_NEAR(out.r, rgb.r, tol) << rgb.r << " " << rgb.g << " " << rgb.b;
  EXPECT_NEAR(out.g, rgb.g, tol) << rgb.r << " " << rgb.g << " " << rgb.b;
  EXPECT_NEAR(out.b, rgb.b, tol) << rgb.r << " " << rgb.g << " " << rgb.b;
}

TEST(RgbUplift, CornersOfTheCubeRoundTrip) {
  for (int r = 0; r < 2; ++r)
    for (int g = 0; g < 2; ++g)
      for (int b = 0; b < 2; ++b) expect_round_trip({double(r), double(g), double(b)});
}

TEST(RgbUplift, RandomColoursRoundTripWithin1Over255) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 40; ++k) expect_round_trip({u(rng), u(rng), u(rng)});
  // Grey ramp and the checker colours of the reference scenes.
  for (double v : {0.0, 0.18, 0.5, 0.9}) expect_round_trip({v, v, v});
  expect_round_trip({0.8, 0.1, 0.1});
  expect_round_trip({0.9, 0.9, 0.9});
}

TEST(RgbUplift, ReflectancesStayWithinZeroAndOne) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const RgbReflectanceSpectrum s({u(rng), u(rng), u(rng)});
    for (double l = kLambdaMinNm; l <= kLambdaMaxNm; l += 2.5) {
      EXPECT_GE(s(l), 0.0);
      EXPECT_LE(s(l), 1.0 + 1e-12);
    }
  }
  // Out-of-gamut inputs are clamped, not extrapolated.
  const RgbReflectanceSpectrum over({2.0, -1.0, 0.5});
  for (double l = kLambdaMinNm; l <= kLambdaMaxNm; l += 5) EXPECT_LE(over(l), 1.0 + 1e-12);
}

TEST(RgbUplift, WhiteIsExactlyOne) {
  const RgbReflectanceSpectrum white({1, 1, 1});
  for (double l = kLambdaMinNm; l <= kLambdaMaxNm; l += 1) EXPECT_EQ(white(l), 1.0);
}

TEST(RgbUplift, WhiteLightIsExactlyD65WithUnitLuminance) {
  const RgbIlluminantSpectrum white({1, 1, 1});
  for (double l = kLambdaMinNm; l <= kLambdaMaxNm; l += 1)
    EXPECT_DOUBLE_EQ(white(l), illuminant_d65(l));
  const RgbIlluminantSpectrum bright({4, 4, 4});
  EXPECT_DOUBLE_EQ(bright(550.0), 4 * illuminant_d65(550.0));
  const RgbIlluminantSpectrum black({0, 0, 0});
  EXPECT_EQ(black(550.0), 0.0);
}

TEST(RgbUplift, ColouredLightRoundTrips) {
  // A light colour renders as itself on a white surface: scale * uplift * D65.
  for (const LinearSrgb c :
       {LinearSrgb{1.0, 0.9, 0.2}, LinearSrgb{0.2, 0.3, 1.0}, LinearSrgb{3.0, 1.5, 0.0}}) {
    const RgbIlluminantSpectrum light(c);
    const LinearSrgb out = render_white_lit([&](double l) { return light(l); });
    const double tol = std::max({c.r, c.g, c.b}) / 255.0;  // 1/255 relative to the light's scale
    EXPECT_NEAR(out.r, c.r, tol);
    EXPECT_NEAR(out.g, c.g, tol);
    EXPECT_NEAR(out.b, c.b, tol);
  }
}

TEST(RgbUplift, SampledMatchesPointwise) {
  const RgbReflectanceSpectrum s({0.3, 0.6, 0.1});
  const auto w = SampledWavelengths::sample(0.37);
  const SampledSpectrum v = s.sample(w);
  for (int i = 0; i < kSpectrumSamples; ++i)
    EXPECT_FLOAT_EQ(v[i], static_cast<float>(s(w.lambda_nm(i))));
}

}  // namespace
}  // namespace thaw::render
