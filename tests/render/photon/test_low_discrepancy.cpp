// Scrambled Halton points: in [0, 1), deterministic, and stratified as Halton points are (digit
// permutations map elementary intervals onto elementary intervals, Kocis & Whiten 1997).
#include "render/photon/low_discrepancy.h"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace thaw::render::photon {
namespace {

TEST(ScrambledHalton, InUnitIntervalAndDeterministic) {
  for (int d = 0; d < ScrambledHalton::kDimensions; ++d)
    for (std::uint64_t i = 0; i < 2000; ++i) {
      const double v = ScrambledHalton::sample(i, d);
      EXPECT_GE(v, 0.0);
      EXPECT_LT(v, 1.0);
      EXPECT_EQ(v, ScrambledHalton::sample(i, d));
    }
  // Large indices (a billion photons) stay in range.
  EXPECT_LT(ScrambledHalton::sample(999999999ULL, 0), 1.0);
}

// The first b^m points of dimension d put exactly one point in each interval [k/b^m, (k+1)/b^m).
TEST(ScrambledHalton, OnePointPerElementaryInterval) {
  for (int d = 0; d < 4; ++d) {
    const int b = ScrambledHalton::base(d);
    int n = 1;
    while (n * b <= 20000) n *= b;
    std::set<long long> cells;
    for (int i = 0; i < n; ++i)
      cells.insert(static_cast<long long>(ScrambledHalton::sample(std::uint64_t(i), d) * n));
    EXPECT_EQ(cells.size(), std::size_t(n)) << "dimension " << d;
  }
}

// 2D: the first 2^a 3^b points (dimensions 0 and 1) fill every box [i/2^a, ...) x [j/3^b, ...) once
// (Halton's (0, m)-type property; Niederreiter 1992, sec. 3.1), e.g. 16 x 27 boxes by 432 points.
TEST(ScrambledHalton, OnePointPerBoxIn2D) {
  const int nx = 16, ny = 27;
  std::vector<int> count(nx * ny, 0);
  for (int i = 0; i < nx * ny; ++i) {
    const int x = static_cast<int>(ScrambledHalton::sample(std::uint64_t(i), 0) * nx);
    const int y = static_cast<int>(ScrambledHalton::sample(std::uint64_t(i), 1) * ny);
    ++count[static_cast<std::size_t>(y * nx + x)];
  }
  for (int c : count) EXPECT_EQ(c, 1);
}

// Scrambled: not the plain radical inverse (whose point 1 is exactly 1/2 in base 2).
TEST(ScrambledHalton, DiffersFromUnscrambled) {
  int same = 0;
  for (std::uint64_t i = 1; i < 64; ++i) same += ScrambledHalton::sample(i, 2) == 0.0 ? 1 : 0;
  EXPECT_LT(same, 2);
  EXPECT_NE(ScrambledHalton::sample(1, 1), 1.0 / 3.0);
}

}  // namespace
}  // namespace thaw::render::photon
