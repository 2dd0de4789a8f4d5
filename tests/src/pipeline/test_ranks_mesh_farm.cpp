// RanksMeshFarm (src/pipeline/ranks_mesh_farm.h): with one rank, the threads of this process;
// with several, chunks of `threads` items farmed out and their texts (any bytes, ':' included)
// put back at their items' indices. The several-rank path is exercised here by ranks whose farm
// runs the chunks in this process (MPI itself: test_pipeline_mpi.cpp).
#include "src/pipeline/ranks_mesh_farm.h"

#include <gtest/gtest.h>

#include <string>

namespace thaw::pipeline {
namespace {

class TwoRanksHere final : public RunRanks {
 public:
  int size() const override { return 2; }
};

std::string text_of(long k) {
  return std::string(static_cast<std::size_t>(k % 4), ':') + "t" + std::to_string(k);
}

TEST(RanksMeshFarm, ChunksComeBackAtTheirItemsWithProgressPerItem) {
  for (const int threads : {1, 2, 3}) {
    for (const long n : {0L, 1L, 7L, 12L}) {
      TwoRanksHere ranks;
      RanksMeshFarm farm(ranks);
      long done = 0;
      const auto texts = farm.run(n, threads, text_of, [&] { ++done; });
      ASSERT_EQ(texts.size(), static_cast<std::size_t>(n));
      for (long k = 0; k < n; ++k) EXPECT_EQ(texts[static_cast<std::size_t>(k)], text_of(k));
      EXPECT_EQ(done, n) << threads;
    }
  }
}

TEST(RanksMeshFarm, OneRankIsThisProcessesThreads) {
  const auto ranks = single_process();
  RanksMeshFarm farm(*ranks);
  EXPECT_TRUE(farm.leader());
  EXPECT_EQ(farm.share("dir"), "dir");
  const auto texts = farm.run(5, 2, text_of, {});
  ASSERT_EQ(texts.size(), 5u);
  EXPECT_EQ(texts[4], text_of(4));
}

}  // namespace
}  // namespace thaw::pipeline
