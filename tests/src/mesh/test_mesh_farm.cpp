// MeshFarm (src/mesh/mesh_farm.h), this process's threads: every item exactly once, each text at
// its item's index, done() once per item, for any thread count.
#include "src/mesh/mesh_farm.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>

namespace thaw::mesh {
namespace {

TEST(MeshFarm, EveryItemOnceWithItsTextAtItsIndex) {
  for (const int threads : {1, 2, 3}) {
    std::vector<std::atomic<int>> calls(37);
    long done = 0;
    const std::vector<std::string> texts = this_process_farm().run(
        37, threads,
        [&](long k) {
          ++calls[static_cast<std::size_t>(k)];
          return "item " + std::to_string(k);
        },
        [&] { ++done; });
    ASSERT_EQ(texts.size(), 37u);
    for (long k = 0; k < 37; ++k) {
      EXPECT_EQ(calls[static_cast<std::size_t>(k)], 1) << k;
      EXPECT_EQ(texts[static_cast<std::size_t>(k)], "item " + std::to_string(k));
    }
    EXPECT_EQ(done, 37);
  }
}

TEST(MeshFarm, NoItemsNoCalls) {
  EXPECT_TRUE(this_process_farm().run(0, 2, [](long) { return std::string("x"); }, {}).empty());
  EXPECT_TRUE(this_process_farm().leader());
  EXPECT_EQ(this_process_farm().share("path"), "path");
}

}  // namespace
}  // namespace thaw::mesh
