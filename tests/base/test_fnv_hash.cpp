// Tests base/fnv_hash.h against the published FNV-1a 64-bit test vectors (Fowler, Noll,
// Vo: the reference implementation's test suite), so the constants cannot drift again.
#include "base/fnv_hash.h"

#include <gtest/gtest.h>

namespace thaw {
namespace {

TEST(Fnv1a64, MatchesThePublishedTestVectors) {
  EXPECT_EQ(fnv1a_64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a_64("a"), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(fnv1a_64("foobar"), 0x85944171f73967e8ULL);
}

TEST(Fnv1a64, OneStepOverAnOctetIsFnv1aOfThatOctet) {
  EXPECT_EQ(fnv1a_64_step(kFnv1aOffset, 'a'), fnv1a_64("a"));
  EXPECT_EQ(fnv1a_64_step(fnv1a_64("fooba"), 'r'), fnv1a_64("foobar"));
}

TEST(Fnv1a64, ContinuesFromAGivenState) {
  EXPECT_EQ(fnv1a_64("bar", fnv1a_64("foo")), fnv1a_64("foobar"));
}

}  // namespace
}  // namespace thaw
