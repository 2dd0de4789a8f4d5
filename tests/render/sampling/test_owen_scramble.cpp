#include "render/sampling/owen_scramble.h"

#include <gtest/gtest.h>

#include <set>

namespace thaw::render::sampling {
namespace {

TEST(OwenScramble, ReverseBitsIsAnInvolution) {
  EXPECT_EQ(reverse_bits(1u), 0x80000000u);
  EXPECT_EQ(reverse_bits(0x0000000fu), 0xf0000000u);
  for (std::uint32_t v : {0u, 1u, 12345u, 0xdeadbeefu}) EXPECT_EQ(reverse_bits(reverse_bits(v)), v);
}

TEST(OwenScramble, DigitKDependsOnlyOnTheDigitsAboveIt) {
  // Owen's nesting: two fractions that agree in their first k digits still agree after
  // scrambling in their first k digits (the elementary interval of size 2^-k maps to one).
  for (std::uint32_t seed : {1u, 77u, 0x9e3779b9u}) {
    for (int k = 1; k <= 24; ++k) {
      const std::uint32_t mask = ~0u << (32 - k);
      for (std::uint32_t v : {0x12345678u, 0x87654321u, 0xffff0000u}) {
        const std::uint32_t w = (v & mask) | (~v & ~mask);  // same top k digits, the rest flipped
        EXPECT_EQ(owen_scramble(v, seed) & mask, owen_scramble(w, seed) & mask) << k;
      }
    }
  }
}

TEST(OwenScramble, IsABijectionOnEveryPrefixLength) {
  // On fractions of 12 digits (the low 20 bits zero) the scramble permutes the 4096 intervals.
  for (std::uint32_t seed : {3u, 0xabcdef01u}) {
    std::set<std::uint32_t> seen;
    for (std::uint32_t i = 0; i < 4096; ++i) seen.insert(owen_scramble(i << 20, seed) >> 20);
    EXPECT_EQ(seen.size(), 4096u);
  }
}

TEST(OwenScramble, SeedsGiveDifferentScrambles) {
  EXPECT_NE(owen_scramble(0x40000000u, 1u), owen_scramble(0x40000000u, 2u) + 0u * 0u);
  EXPECT_NE(hash_seed(0, 0, 0, 0), hash_seed(1, 0, 0, 0));
  EXPECT_NE(hash_seed(0, 1, 0, 0), hash_seed(1, 0, 0, 0));
}

}  // namespace
}  // namespace thaw::render::sampling
