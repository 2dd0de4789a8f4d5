#include "render/film/adaptive_pixel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace thaw::render {
namespace {

Rgb identity(const Rgb& c) {
  return c;
}

TEST(AdaptivePixel, OneSampleGoesThroughThePixelCentre) {
  const Filter f(FilterKind::gaussian, 1.5);
  AntialiasingSettings aa;
  aa.max_samples = 1;
  aa.adaptive = true;
  float fx = -1, fy = -1;
  const auto e = estimate_pixel<Rgb>(
      7, 3, sampling::PixelSampler(7, 3), f, aa,
      [&](float x, float y, std::uint32_t) {
        fx = x;
        fy = y;
        return Rgb::gray(2);
      },
      identity);
  EXPECT_EQ(e.samples, 1);
  EXPECT_EQ(fx, 7.5f);
  EXPECT_EQ(fy, 3.5f);
  EXPECT_EQ(e.value.g, 2.0f);
}

TEST(AdaptivePixel, FlatPixelsStopAfterTheFirstBatch) {
  const Filter box(FilterKind::box, 0.5);
  AntialiasingSettings aa;
  aa.max_samples = 64;
  aa.adaptive = true;
  aa.min_samples = 4;
  const auto e = estimate_pixel<Rgb>(
      0, 0, sampling::PixelSampler(0, 0), box, aa,
      [](float, float, std::uint32_t) {
        return Rgb{0.2f, 0.4f, 0.6f};
      },
      identity);
  EXPECT_EQ(e.samples, 4);
  EXPECT_FLOAT_EQ(e.value.b, 0.6f);
  aa.adaptive = false;
  EXPECT_EQ(estimate_pixel<Rgb>(
                0, 0, sampling::PixelSampler(0, 0), box, aa,
                [](float, float, std::uint32_t) { return Rgb{}; }, identity)
                .samples,
            64);
}

TEST(AdaptivePixel, AnEdgeThroughThePixelTakesTheCapAndItsExactCoverage) {
  // A vertical black/white edge through the middle of pixel (4, 4): the display-space standard
  // error is ~0.5 / sqrt(n) >> threshold, so sampling goes to the cap (64); a (0,6,2)-net puts
  // exactly 32 of its 64 points on each side of x = 4.5, so the box-filtered value is 1/2 exactly.
  const Filter box(FilterKind::box, 0.5);
  AntialiasingSettings aa;
  aa.max_samples = 64;
  aa.adaptive = true;
  const auto edge = [](float x, float, std::uint32_t) { return x < 4.5f ? Rgb{} : Rgb::gray(1); };
  const auto e = estimate_pixel<Rgb>(4, 4, sampling::PixelSampler(4, 4), box, aa, edge, identity);
  EXPECT_EQ(e.samples, 64);
  EXPECT_EQ(e.value.r, 0.5f);
  // A cap that is not a power of two is honoured.
  aa.max_samples = 24;
  EXPECT_EQ(
      estimate_pixel<Rgb>(4, 4, sampling::PixelSampler(4, 4), box, aa, edge, identity).samples, 24);
}

TEST(AdaptivePixel, ThresholdIsInDisplayUnits) {
  // Samples alternating 0.5 +- 0.05 (linear): display-space deviation about 0.05 * d(sRGB)/dx at
  // 0.5 (~0.67) = 0.034; after 4 samples the standard error ~0.019: above 0.01 (continue), below
  // 0.05 (stop). Exposure 2^-10 darkens everything to ~0: stops (the metric sees what the PNG
  // shows).
  const Filter box(FilterKind::box, 0.5);
  AntialiasingSettings aa;
  aa.max_samples = 256;
  aa.adaptive = true;
  const auto noisy = [](float, float, std::uint32_t i) { return Rgb::gray(i % 2 ? 0.55f : 0.45f); };
  aa.threshold = 0.01f;
  EXPECT_GT(
      estimate_pixel<Rgb>(0, 0, sampling::PixelSampler(0, 0), box, aa, noisy, identity).samples, 4);
  aa.threshold = 0.05f;
  EXPECT_EQ(
      estimate_pixel<Rgb>(0, 0, sampling::PixelSampler(0, 0), box, aa, noisy, identity).samples, 4);
  aa.threshold = 0.01f;
  aa.exposure_scale = std::ldexp(1.0f, -10);
  EXPECT_EQ(
      estimate_pixel<Rgb>(0, 0, sampling::PixelSampler(0, 0), box, aa, noisy, identity).samples, 4);
}

TEST(AdaptivePixel, NoiseSharedWithinPairsDoesNotRefine) {
  // Spectral renders give both samples of a pair the same wavelengths: a value that changes only
  // from pair to pair (wavelength noise, shared by all pixels) is not image variation, and more
  // samples would not remove it; a value that changes within pairs is.
  const Filter box(FilterKind::box, 0.5);
  AntialiasingSettings aa;
  aa.max_samples = 64;
  aa.adaptive = true;
  aa.min_samples = 4;
  const auto per_pair = [](float, float, std::uint32_t i) {
    return Rgb::gray((i / 2) % 2 ? 0.9f : 0.1f);
  };
  EXPECT_EQ(
      estimate_pixel<Rgb>(0, 0, sampling::PixelSampler(0, 0), box, aa, per_pair, identity).samples,
      4);
  const auto within = [](float, float, std::uint32_t i) { return Rgb::gray(i % 2 ? 0.9f : 0.1f); };
  EXPECT_EQ(
      estimate_pixel<Rgb>(0, 0, sampling::PixelSampler(0, 0), box, aa, within, identity).samples,
      64);
}

TEST(AdaptivePixel, GaussianFilterAveragesTheNeighbourhood) {
  // A linear ramp L = x is reproduced at the centre by any symmetric filter: the estimate of
  // pixel (10, 0) has expectation 10.5 exactly. Its standard error: x has deviation s = 0.5 px
  // under the Gaussian (r = 1.5, s = r / 3) and the weights are 1 to within 1 %, so 5 standard
  // errors of 256 samples are 5 * 0.5 / 16 = 0.16 (the stratified estimate is far closer).
  const Filter g(FilterKind::gaussian, 1.5);
  AntialiasingSettings aa;
  aa.max_samples = 256;
  aa.adaptive = false;
  const auto ramp = [](float x, float, std::uint32_t) { return Rgb::gray(x); };
  const auto e = estimate_pixel<Rgb>(10, 0, sampling::PixelSampler(10, 0), g, aa, ramp, identity);
  EXPECT_NEAR(e.value.r, 10.5, 0.16);
}

TEST(AdaptivePixel, DisplayValueIsTheSrgbCurve) {
  EXPECT_FLOAT_EQ(display_value(0.0f, 1.0f), 0.0f);
  EXPECT_FLOAT_EQ(display_value(1.0f, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(display_value(4.0f, 1.0f), 1.0f);
  EXPECT_NEAR(display_value(0.18f, 1.0f), 0.4614, 1e-3);  // middle grey
  EXPECT_FLOAT_EQ(display_value(0.001f, 1.0f), 0.01292f);
  EXPECT_EQ(display_value(std::nanf(""), 1.0f), 0.0f);
}

TEST(AdaptivePixel, DisplayTableFollowsTheFormula) {
  // Linear interpolation between nodes h = 1/4096 apart: error <= h^2/8 max|f''| (f = 1.055
  // v^(5/12), |f''| = 0.2564 v^(-19/12) <= 2366 above the linear segment's end 0.0031308) =
  // 1.77e-5, or in the interval holding that end <= h/4 x the jump of slope there (12.92 -
  // 12.70 = 0.22): 1.34e-5; plus float rounding of a value <= 1 (a few 1e-7).
  const double h = 1.0 / kSrgbTableSize;
  const double bound = std::max(h * h / 8.0 * 2366.0, h / 4.0 * 0.22) + 1e-6;
  double worst = 0.0;
  for (int i = 0; i <= 200000; ++i) {
    const float v = float(i) / 200000.0f;
    worst = std::max(worst, std::abs(double(display_value(v, 1.0f)) - double(srgb_encode(v))));
  }
  EXPECT_LE(worst, bound);
  EXPECT_GT(worst, 0.0);  // it is the table, not the formula
}

TEST(AdaptivePixel, StandsOutOnlyBeyondAllNeighbours) {
  // Neighbours between 0.2 and 0.25 (linear) in every channel; display margin 3 x 0.01.
  AntialiasingSettings aa;
  aa.threshold = 0.01f;
  const Rgb hi = Rgb::gray(0.25f), lo = Rgb::gray(0.2f);
  const float d_hi = display_value(0.25f, 1.0f), d_lo = display_value(0.2f, 1.0f);
  // The linear value whose display value is d (bisection on the monotonic curve).
  const auto linear = [](float d) {
    float a = 0.0f, b = 1.0f;
    for (int i = 0; i < 60; ++i) (display_value(0.5f * (a + b), 1.0f) < d ? a : b) = 0.5f * (a + b);
    return 0.5f * (a + b);
  };
  // Beyond the margin above the brightest neighbour, in one channel: a speck.
  EXPECT_TRUE(stands_out(Rgb{0.22f, linear(d_hi + 0.031f), 0.22f}, hi, lo, aa));
  EXPECT_TRUE(stands_out(Rgb{linear(d_lo - 0.031f), 0.22f, 0.22f}, hi, lo, aa));
  // Within it: the neighbours' own errors may explain it.
  EXPECT_FALSE(stands_out(Rgb::gray(linear(d_hi + 0.029f)), hi, lo, aa));
  EXPECT_FALSE(stands_out(Rgb::gray(linear(d_lo - 0.029f)), hi, lo, aa));
  // Inside the neighbours' range (a ridge, an edge): real structure of the image.
  EXPECT_FALSE(stands_out(Rgb::gray(0.22f), hi, lo, aa));
  // The margin is in display units: exposure counts.
  aa.exposure_scale = 0.5f;
  EXPECT_FALSE(stands_out(Rgb{0.22f, linear(d_hi + 0.031f), 0.22f}, hi, lo, aa));
}

TEST(AdaptivePixel, DoubledFirstBatchKeepsTheCap) {
  AntialiasingSettings aa;
  aa.adaptive = true;
  aa.max_samples = 8;
  aa.min_samples = 2;
  EXPECT_EQ(first_batch(aa), 2);
  EXPECT_EQ(doubled_first_batch(aa, 2).min_samples, 4);
  EXPECT_EQ(doubled_first_batch(aa, 4).min_samples, 8);
  EXPECT_EQ(doubled_first_batch(aa, 6).min_samples, 8);
}

}  // namespace
}  // namespace thaw::render
