// Tests render/integrator/stratified_pixel_sampler.h: one sample per stratum (jittered grid for a
// square count, one per row and column otherwise), the pixel centre for one sample, and streams
// that depend on the pixel alone.
#include "render/integrator/stratified_pixel_sampler.h"

#include <gtest/gtest.h>

#include <set>

namespace thaw::render {
namespace {

TEST(StratifiedPixelSampler, OneSampleIsThePixelCentre) {
  StratifiedPixelSampler s(1, 10, 0);
  s.start_pixel(3, 4);
  const auto [x, y] = s.position(0);
  EXPECT_EQ(x, 0.5f);
  EXPECT_EQ(y, 0.5f);
}

TEST(StratifiedPixelSampler, SquareCountFillsEveryGridCell) {
  constexpr int kGrid = 4;
  StratifiedPixelSampler s(kGrid * kGrid, 10, 7);
  s.start_pixel(1, 2);
  std::set<std::pair<int, int>> cells;
  for (int i = 0; i < kGrid * kGrid; ++i) {
    const auto [x, y] = s.position(i);
    ASSERT_GE(x, 0.0f);
    ASSERT_LT(x, 1.0f);
    ASSERT_GE(y, 0.0f);
    ASSERT_LT(y, 1.0f);
    cells.insert({int(x * kGrid), int(y * kGrid)});
  }
  EXPECT_EQ(cells.size(), std::size_t(kGrid * kGrid));
}

TEST(StratifiedPixelSampler, OtherCountsAreALatinHypercube) {
  constexpr int kN = 7;
  StratifiedPixelSampler s(kN, 10, 7);
  s.start_pixel(5, 0);
  std::set<int> rows, columns;
  for (int i = 0; i < kN; ++i) {
    const auto [x, y] = s.position(i);
    columns.insert(int(x * kN));
    rows.insert(int(y * kN));
  }
  EXPECT_EQ(columns.size(), std::size_t(kN));
  EXPECT_EQ(rows.size(), std::size_t(kN));
}

TEST(StratifiedPixelSampler, StreamDependsOnThePixelOnly) {
  StratifiedPixelSampler a(5, 10, 3), b(5, 10, 3);
  a.start_pixel(2, 2);
  b.start_pixel(9, 9);  // another pixel in between must not matter
  b.start_pixel(2, 2);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(a.position(i), b.position(i));
  EXPECT_EQ(a.rng().next_u32(), b.rng().next_u32());
  a.start_pixel(3, 2);
  b.start_pixel(2, 2);
  EXPECT_NE(a.position(0), b.position(0));
}

TEST(StratifiedPixelSampler, ShuffleIsAPermutation) {
  Pcg32 rng(1);
  std::vector<int> p(9);
  shuffle_indices(p, rng);
  EXPECT_EQ(std::set<int>(p.begin(), p.end()).size(), 9u);
}

}  // namespace
}  // namespace thaw::render
