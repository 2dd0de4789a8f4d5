// RanksMeshFarm (src/pipeline/ranks_mesh_farm.h): with one rank, the threads of this process;
// with several, guided chunks farmed out and their texts (any bytes, ':' included) put back at
// their items' indices. The several-rank path is exercised here by ranks whose farm
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

TEST(RanksMeshFarm, GuidedChunksCoverTheItemsLargeFirstThenOneRoundOfThreads) {
  for (const int ranks : {2, 3, 8})
    for (const int threads : {1, 2, 4})
      for (const long n : {0L, 1L, 5L, 103L, 1000L}) {
        const std::vector<Chunk> chunks = guided_chunks(n, ranks, threads);
        long next = 0;
        for (std::size_t c = 0; c < chunks.size(); ++c) {
          EXPECT_EQ(chunks[c].first, next);
          EXPECT_GT(chunks[c].count, 0);
          if (c + 1 < chunks.size()) {
            EXPECT_EQ(chunks[c].count % threads, 0) << "whole rounds of threads but the last";
            EXPECT_GE(chunks[c].count, chunks[c + 1].count) << "non-increasing";
          }
          // About 1/(2R) of what is left: rounded up to whole rounds of threads, never more.
          const long left = n - next;
          EXPECT_LE(chunks[c].count,
                    std::max<long>(threads, (left + 2 * ranks - 1) / (2 * ranks) + threads - 1));
          next += chunks[c].count;
        }
        EXPECT_EQ(next, n);
        if (n > 0) {
          EXPECT_LE(chunks.back().count, threads) << "ends within one round of threads";
        }
      }
  // The default film's 103 surfaces over 2 single-thread ranks: 103 hand-outs before, now each
  // takes a quarter of what is left: 26, 20, 15, ... so about 2 R ln(n / 2 R) + 2 R of them.
  const auto film = guided_chunks(103, 2, 1);
  EXPECT_EQ(film.front().count, 26);
  EXPECT_LE(film.size(), 20u);
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
