// SampledSpectrum arithmetic: element-wise operations, safe division (terminated wavelengths
// with pdf 0 give 0, never NaN), reductions and the element-wise exp.
#include <gtest/gtest.h>

#include <cmath>

#include "render/spectrum/sampled_spectrum.h"

namespace thaw::render {
namespace {

TEST(SampledSpectrum, ElementWiseArithmetic) {
  const SampledSpectrum a({1, 2, 3, 4});
  const SampledSpectrum b({2, 2, 2, 2});
  EXPECT_EQ(a + b, SampledSpectrum({3, 4, 5, 6}));
  EXPECT_EQ(a - b, SampledSpectrum({-1, 0, 1, 2}));
  EXPECT_EQ(a * b, SampledSpectrum({2, 4, 6, 8}));
  EXPECT_EQ(a * 0.5f, SampledSpectrum({0.5f, 1, 1.5f, 2}));
  EXPECT_EQ(a / b, SampledSpectrum({0.5f, 1, 1.5f, 2}));
  EXPECT_FLOAT_EQ(a.max_component(), 4);
  EXPECT_FLOAT_EQ(a.min_component(), 1);
  EXPECT_FLOAT_EQ(a.average(), 2.5f);
  EXPECT_TRUE(SampledSpectrum().is_black());
  EXPECT_FALSE(a.is_black());
}

TEST(SampledSpectrum, DivisionByZeroGivesZero) {
  const SampledSpectrum q = SampledSpectrum(1.0f) / SampledSpectrum({0.5f, 0, 0, 0});
  EXPECT_EQ(q, SampledSpectrum({2, 0, 0, 0}));
}

TEST(SampledSpectrum, ExpElementwise) {
  const SampledSpectrum e = exp_elementwise(SampledSpectrum({0, -1, -2, 1}));
  EXPECT_FLOAT_EQ(e[0], 1.0f);
  EXPECT_FLOAT_EQ(e[1], std::exp(-1.0f));
  EXPECT_FLOAT_EQ(e[2], std::exp(-2.0f));
  EXPECT_FLOAT_EQ(e[3], std::exp(1.0f));
}

}  // namespace
}  // namespace thaw::render
