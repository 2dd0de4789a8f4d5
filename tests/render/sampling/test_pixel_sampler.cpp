#include "render/sampling/pixel_sampler.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/render/sampling/sampling_test_util.h"

namespace thaw::render::sampling {
namespace {

std::vector<Point2> block(const PixelSampler& s, std::uint32_t first, int m, std::uint32_t dim) {
  std::vector<Point2> pts;
  for (std::uint32_t i = 0; i < (1u << m); ++i) pts.push_back(s.get_2d(first + i, dim));
  return pts;
}

TEST(PixelSampler, EveryPowerOfTwoPrefixIsA02Net) {
  // Shuffling maps [0, 2^m) onto an aligned Sobol block and Owen scrambling keeps nets: so any
  // adaptive stop at a power of two is perfectly stratified, in every pixel and dimension.
  for (int x : {0, 17, 639})
    for (std::uint32_t dim : {0u, 1u, 7u})
      for (int m = 0; m <= 9; ++m) {
        const PixelSampler s(x, 3 * x + 1, 42);
        EXPECT_TRUE(test::is_02_net(block(s, 0, m, dim), m)) << x << " " << dim << " " << m;
        EXPECT_TRUE(test::is_02_net(block(s, 1u << m, m, dim), m)) << "second block";
      }
}

TEST(PixelSampler, OneDimensionalPrefixesAreStratified) {
  const PixelSampler s(5, 9);
  for (int m = 0; m <= 10; ++m) {
    std::vector<int> count(std::size_t{1} << m, 0);
    for (std::uint32_t i = 0; i < (1u << m); ++i)
      ++count[static_cast<std::size_t>(s.get_1d(i, 3) * float(1 << m))];
    for (int c : count) ASSERT_EQ(c, 1) << m;
  }
}

TEST(PixelSampler, IsAPureFunctionOfPixelIndexDimensionAndSeed) {
  // Whatever order (thread, tile) asks, the same point comes back; different pixels, dimensions
  // and seeds get different points.
  const PixelSampler a(12, 34, 7), b(12, 34, 7);
  std::vector<Point2> forward;
  for (std::uint32_t i = 0; i < 64; ++i) forward.push_back(a.get_2d(i, 2));
  for (std::uint32_t i = 64; i-- > 0;) {
    const Point2 p = b.get_2d(i, 2);
    EXPECT_EQ(p.x, forward[i].x);
    EXPECT_EQ(p.y, forward[i].y);
  }
  EXPECT_NE(a.get_2d(0, 2).x, PixelSampler(13, 34, 7).get_2d(0, 2).x);
  EXPECT_NE(a.get_2d(0, 2).x, a.get_2d(0, 3).x);
  EXPECT_NE(a.get_2d(0, 2).x, PixelSampler(12, 34, 8).get_2d(0, 2).x);
}

TEST(PixelSampler, FirstSamplesOfManyPixelsAreUniform) {
  // Across pixels the points are independent uniform draws: chi-square over 16 x 16 cells of
  // sample 0 (dimension 0) of 256 x 256 pixels (expected 256 per cell, 255 degrees of freedom),
  // at tail probability 1e-6. Same for the 1D sequence over 256 cells.
  std::vector<int> cells(256, 0), cells1d(256, 0);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      const PixelSampler s(x, y);
      const Point2 p = s.get_2d(0, 0);
      ++cells[static_cast<std::size_t>(int(p.x * 16) * 16 + int(p.y * 16))];
      ++cells1d[static_cast<std::size_t>(s.get_1d(0, 1) * 256)];
    }
  EXPECT_LT(test::chi_square_uniform(cells, 256.0), test::chi_square_critical_1e6(255));
  EXPECT_LT(test::chi_square_uniform(cells1d, 256.0), test::chi_square_critical_1e6(255));
}

TEST(PixelSampler, DimensionPairsAreDecorrelated) {
  // Padding: (x of dimension 0, x of dimension 1) over 4096 samples of one pixel must fill the
  // square uniformly (chi-square on 16 x 16 cells), not lie on a curve as unshuffled copies of
  // one sequence would.
  const PixelSampler s(3, 4);
  std::vector<int> cells(256, 0);
  for (std::uint32_t i = 0; i < 4096; ++i) {
    const float u = s.get_2d(i, 0).x, v = s.get_2d(i, 1).x;
    ++cells[static_cast<std::size_t>(int(u * 16) * 16 + int(v * 16))];
  }
  EXPECT_LT(test::chi_square_uniform(cells, 16.0), test::chi_square_critical_1e6(255));
}

TEST(PixelSampler, DiscrepancyIsFarBelowRandomPoints) {
  // The L2 star discrepancy of 256 points: E[T^2] = (1/4 - 1/9) / 256 for independent uniform
  // points; a (0,8,2)-net's is O((log N)^2 / N^2) (Owen-scrambled: O(log N / N^3) in
  // expectation), below a tenth of it here for any pixel.
  const double random_expectation = (0.25 - 1.0 / 9.0) / 256.0;
  for (int x : {0, 1, 100}) {
    const PixelSampler s(x, x);
    EXPECT_LT(test::l2_star_discrepancy_squared(block(s, 0, 8, 0)), 0.1 * random_expectation) << x;
  }
}

}  // namespace
}  // namespace thaw::render::sampling
