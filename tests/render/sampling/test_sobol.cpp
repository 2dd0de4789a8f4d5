#include "render/sampling/sobol.h"

#include <gtest/gtest.h>

#include "tests/render/sampling/sampling_test_util.h"

namespace thaw::render::sampling {
namespace {

TEST(Sobol, FirstPointsAreTheKnownSequence) {
  // Sobol's dimension 1 in natural (not Gray-code) order: x_i = xor of v_k over the set bits k
  // of i, with v_k = 1/2, 3/4, 5/8, 15/16 (Joe & Kuo's direction numbers for x + 1):
  // 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
  const double expected1[] = {0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  const double expected0[] = {0.0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
  for (std::uint32_t i = 0; i < 8; ++i) {
    EXPECT_EQ(sobol_dimension1(i) * 0x1p-32, expected1[i]) << i;
    EXPECT_EQ(sobol_dimension0(i) * 0x1p-32, expected0[i]) << i;
  }
  EXPECT_EQ(detail::kSobolDimension1[3], 0xf0000000u);
  EXPECT_EQ(detail::kSobolDimension1[4], 0x88000000u);
}

// The byte tables compute the same product as the definition, xor of column k over the set bits
// k, for indices with any of the 32 bits set (the pixel sampler's scrambled indices).
TEST(Sobol, ByteTablesEqualTheBitwiseProduct) {
  std::uint32_t index = 0x9e3779b9u;
  for (int i = 0; i < 100000; ++i) {
    index = index * 1664525u + 1013904223u;
    std::uint32_t want = 0;
    for (std::size_t k = 0; k < 32; ++k)
      if (index & (1u << k)) want ^= detail::kSobolDimension1[k];
    ASSERT_EQ(sobol_dimension1(index), want) << index;
  }
  EXPECT_EQ(sobol_dimension1(0xffffffffu), [] {
    std::uint32_t v = 0;
    for (std::uint32_t c : detail::kSobolDimension1) v ^= c;
    return v;
  }());
}

TEST(Sobol, EveryAlignedBlockIsA02Net) {
  // The (0,2)-sequence property: points [k 2^m, (k+1) 2^m) form a (0,m,2)-net, for all m, k.
  for (int m = 0; m <= 10; ++m) {
    for (std::uint32_t k : {0u, 1u, 5u, 1000u}) {
      std::vector<Point2> pts;
      for (std::uint32_t i = 0; i < (1u << m); ++i) {
        const std::uint32_t index = (k << m) + i;
        pts.push_back({fraction_to_float(sobol_dimension0(index)),
                       fraction_to_float(sobol_dimension1(index))});
      }
      EXPECT_TRUE(test::is_02_net(pts, m)) << "m = " << m << ", block " << k;
    }
  }
}

TEST(Sobol, FractionToFloatStaysBelowOne) {
  EXPECT_LT(fraction_to_float(0xffffffffu), 1.0f);
  EXPECT_EQ(fraction_to_float(0x80000000u), 0.5f);
}

}  // namespace
}  // namespace thaw::render::sampling
