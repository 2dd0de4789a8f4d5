// Hero-wavelength sampling: layout of the rotated wavelengths, normalised densities, the
// terminate_secondary() bookkeeping, and unbiasedness of the spectral estimator (statistical).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/spectrum/colour.h"
#include "render/spectrum/sampled_wavelengths.h"

namespace thaw::render {
namespace {

TEST(SampledWavelengths, RotationsAreEquallySpacedAndWrap) {
  const auto w = SampledWavelengths::sample(0.9, HeroDensity::uniform);  // hero at 740 nm
  EXPECT_NEAR(w.lambda_nm(0), 740.0, 1e-4);
  EXPECT_NEAR(w.lambda_nm(1), 440.0, 1e-4);  // 740 + 100 wraps to 440
  EXPECT_NEAR(w.lambda_nm(2), 540.0, 1e-4);
  EXPECT_NEAR(w.lambda_nm(3), 640.0, 1e-4);
  for (int i = 0; i < kSpectrumSamples; ++i) EXPECT_FLOAT_EQ(w.pdf(i), 1.0f / 400.0f);
}

TEST(SampledWavelengths, StaysInRangeForAllU) {
  for (HeroDensity d : {HeroDensity::uniform, HeroDensity::visible})
    for (double u : {0.0, 1e-12, 0.25, 0.5, 0.999999, std::nextafter(1.0, 0.0)}) {
      const auto w = SampledWavelengths::sample(u, d);
      for (int i = 0; i < kSpectrumSamples; ++i) {
        EXPECT_GE(w.lambda_nm(i), kLambdaMinNm);
        EXPECT_LE(w.lambda_nm(i), kLambdaMaxNm);
        EXPECT_GT(w.pdf(i), 0);
      }
    }
}

TEST(SampledWavelengths, HeroDensitiesIntegrateToOne) {
  // Midpoint rule at 0.01 nm: error ~ h^2/24 * max|p''| * 400 nm, far below 1e-6.
  for (HeroDensity d : {HeroDensity::uniform, HeroDensity::visible}) {
    double sum = 0;
    const double h = 0.01;
    for (double l = kLambdaMinNm + h / 2; l < kLambdaMaxNm; l += h)
      sum += SampledWavelengths::hero_pdf(l, d) * h;
    EXPECT_NEAR(sum, 1.0, 1e-6);
  }
}

TEST(SampledWavelengths, TerminateSecondaryKeepsOnlyTheHero) {
  auto w = SampledWavelengths::sample(0.3, HeroDensity::visible);
  const double hero_pdf = SampledWavelengths::hero_pdf(w.lambda_nm(0), HeroDensity::visible);
  EXPECT_FALSE(w.secondary_terminated());
  w.terminate_secondary();
  EXPECT_TRUE(w.secondary_terminated());
  EXPECT_NEAR(w.pdf(0), hero_pdf / kSpectrumSamples, 1e-9);
  for (int i = 1; i < kSpectrumSamples; ++i) EXPECT_EQ(w.pdf(i), 0.0f);
  const float before = w.pdf(0);
  w.terminate_secondary();  // idempotent
  EXPECT_EQ(w.pdf(0), before);
}

/// A smooth test spectrum with structure across the range [relative radiance].
double test_spectrum(double l) {
  return 1.0 + 0.8 * std::sin(l / 37.0) + 0.5 * std::exp(-std::pow((l - 610) / 25.0, 2));
}

Xyz reference_xyz() {
  // Dense midpoint quadrature at 0.005 nm of the same piecewise-linear CMF interpolant the
  // estimator samples: quadrature error < 1e-7 relative, negligible against the MC tolerance.
  Xyz r;
  const double h = 0.005;
  for (double l = kLambdaMinNm + h / 2; l < kLambdaMaxNm; l += h) {
    const Xyz b = cie_xyz_bar(l);
    const double s = test_spectrum(l) * h;
    r.x += s * b.x;
    r.y += s * b.y;
    r.z += s * b.z;
  }
  return r;
}

/// Mean of n estimator samples vs quadrature, within 4 standard errors (a false alarm has
/// probability ~6e-5 per component for a normal mean; n = 200000 makes the CLT apply).
void check_unbiased(HeroDensity density, bool terminate) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const int n = 200000;
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  for (int k = 0; k < n; ++k) {
    auto w = SampledWavelengths::sample(uni(rng), density);
    if (terminate) w.terminate_secondary();
    SampledSpectrum L;
    for (int i = 0; i < kSpectrumSamples; ++i)
      L[i] = static_cast<float>(test_spectrum(w.lambda_nm(i)));
    const Xyz e = spectrum_to_xyz(L, w);
    const double v[3] = {e.x, e.y, e.z};
    for (int c = 0; c < 3; ++c) {
      sum[c] += v[c];
      sum2[c] += v[c] * v[c];
    }
  }
  const Xyz ref = reference_xyz();
  const double r[3] = {ref.x, ref.y, ref.z};
  for (int c = 0; c < 3; ++c) {
    const double mean = sum[c] / n;
    const double var = (sum2[c] / n - mean * mean) * n / (n - 1);
    const double se = std::sqrt(var / n);
    EXPECT_LT(std::abs(mean - r[c]), 4 * se)
        << "component " << c << " mean " << mean << " reference " << r[c] << " se " << se;
    EXPECT_GT(se, 0);
  }
}

TEST(SpectralEstimator, UnbiasedUniformHero) {
  check_unbiased(HeroDensity::uniform, false);
}
TEST(SpectralEstimator, UnbiasedVisibleHeroWithMis) {
  check_unbiased(HeroDensity::visible, false);
}
TEST(SpectralEstimator, UnbiasedAfterTerminateSecondary) {
  check_unbiased(HeroDensity::visible, true);
}

}  // namespace
}  // namespace thaw::render
