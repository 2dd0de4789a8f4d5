// Tests render/math/rng.h: a pixel's stream depends only on its sequence and seed, and the
// shuffle is a permutation.
#include "render/math/rng.h"

#include <gtest/gtest.h>

#include <set>

namespace thaw::render {
namespace {

TEST(Pcg32, StreamDependsOnSequenceAndSeedOnly) {
  Pcg32 a(5, 3), b(5, 3), c(6, 3);
  for (int i = 0; i < 8; ++i) {
    const std::uint32_t va = a.next_u32();
    EXPECT_EQ(va, b.next_u32());
    EXPECT_NE(va, c.next_u32());  // distinct streams: a collision has probability 2^-32 per draw
  }
}

TEST(Pcg32, ShuffleIsAPermutation) {
  Pcg32 rng(1);
  std::vector<int> p(9);
  shuffle_indices(p, rng);
  EXPECT_EQ(std::set<int>(p.begin(), p.end()).size(), 9u);
}

}  // namespace
}  // namespace thaw::render
