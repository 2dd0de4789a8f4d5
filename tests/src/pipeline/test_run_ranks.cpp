// RunRanks as the run's work farm (src/pipeline/run_ranks.h): with one rank, the threads of this
// process; with several, guided chunks (fine grain) or single items (coarse) handed out and their
// texts (any bytes, ':' included) put back at their items' indices, a failure thrown as it was.
// The several-rank path is exercised here by ranks whose hand-out runs the items in this process
// (MPI itself: test_pipeline_mpi.cpp, test_rank_failure_mpi.cpp).
#include "src/pipeline/run_ranks.h"

#include <gtest/gtest.h>

#include <ctime>
#include <string>

#include "base/error.h"

namespace thaw::pipeline {
namespace {

class TwoRanksHere final : public RunRanks {
 public:
  int size() const override { return 2; }
};

std::string text_of(long k) {
  return std::string(static_cast<std::size_t>(k % 4), ':') + "t" + std::to_string(k);
}

TEST(RunRanks, ChunksComeBackAtTheirItemsWithProgressPerItem) {
  for (const auto grain : {WorkFarm::Grain::fine, WorkFarm::Grain::coarse})
    for (const int threads : {1, 2, 3}) {
      for (const long n : {0L, 1L, 7L, 12L}) {
        TwoRanksHere farm;
        long done = 0;
        const auto texts = farm.run(
            n, threads, text_of, [&] { ++done; }, grain);
        ASSERT_EQ(texts.size(), static_cast<std::size_t>(n));
        for (long k = 0; k < n; ++k) EXPECT_EQ(texts[static_cast<std::size_t>(k)], text_of(k));
        EXPECT_EQ(done, n) << threads;
      }
    }
}

TEST(RunRanks, AFailingItemIsThrownAsItWasOverTheRanks) {
  for (const auto grain : {WorkFarm::Grain::fine, WorkFarm::Grain::coarse}) {
    TwoRanksHere farm;
    try {
      farm.run(
          9, 2,
          [](long k) -> std::string {
            if (k == 4) throw UserError("frames/frame_000004.png", "", "disk full");
            return "";
          },
          {}, grain);
      ADD_FAILURE() << "no error";
    } catch (const UserError& e) {
      EXPECT_EQ(e.file(), "frames/frame_000004.png");
    }
  }
}

TEST(RunRanks, RanksAgreeOnTheFirstFailureAndTheLeadersOutcome) {
  const auto ranks = single_process();
  const Outcome user = Outcome::user("a.toml", "[film] fps", "must be > 0");
  EXPECT_EQ(ranks->first_failure(user), user);
  EXPECT_TRUE(ranks->first_failure(Outcome()).ok());
  EXPECT_EQ(ranks->leaders_outcome(Outcome::internal("x")), Outcome::internal("x"));
}

TEST(RunRanks, GuidedChunksCoverTheItemsLargeFirstThenOneRoundOfThreads) {
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
          // About 1/(4R) of what is left: rounded up to whole rounds of threads, never more.
          const long left = n - next;
          EXPECT_LE(chunks[c].count,
                    std::max<long>(threads, (left + 4 * ranks - 1) / (4 * ranks) + threads - 1));
          next += chunks[c].count;
        }
        EXPECT_EQ(next, n);
        if (n > 0) {
          EXPECT_LE(chunks.back().count, threads) << "ends within one round of threads";
        }
      }
  // The default film's 103 surfaces over 2 single-thread ranks: one hand-out per surface would be
  // 103; each chunk takes an eighth of what is left: 13, 12, 10, ... so about
  // 4 R ln(n / 4 R) + 4 R of them (the sum of a geometric series down to chunks of one).
  const auto film = guided_chunks(103, 2, 1);
  EXPECT_EQ(film.front().count, 13);
  EXPECT_LE(film.size(), 30u);
}

// What each run() cost is recorded for bench/pipeline/mpi_scaling.sh: one entry per run, the
// run's item count, and the CPU spent inside the items (here: a busy loop of known CPU) counted
// once per item and within the run's process CPU.
TEST(RunRanks, EveryRunsCostIsRecordedPerPhase) {
  TwoRanksHere farm;
  const auto thread_cpu_s = [] {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  };
  const auto spin = [&](long k) {
    for (const double start = thread_cpu_s(); thread_cpu_s() - start < 0.01;) {  // 10 ms of CPU
    }
    return std::to_string(k);
  };
  farm.run(3, 1, spin, {});
  farm.run(0, 1, spin, {});
  ASSERT_EQ(farm.costs().size(), 2u);
  EXPECT_EQ(farm.costs()[0].items, 3);
  EXPECT_EQ(farm.costs()[1].items, 0);
  // 3 items of >= 10 ms of this thread's CPU each (the clock the farm reads too): >= 0.03 s
  // inside them; the run's process CPU holds the items' (same kernel accounting, read after).
  EXPECT_GE(farm.costs()[0].work_cpu_s, 0.03);
  EXPECT_GE(farm.costs()[0].cpu_s, farm.costs()[0].work_cpu_s);
  EXPECT_EQ(farm.costs()[1].work_cpu_s, 0.0);
  // This fake's ranks run every chunk here: all 3 items worked on in this process.
  EXPECT_EQ(farm.costs()[0].items_here, 3);
  EXPECT_EQ(farm.costs()[1].items_here, 0);
  EXPECT_EQ(cost_note({{3, 0.5, 0.75, 0.25, 2}, {1, 1, 2, 0.125, 0}}),
            "farm 0 items 3 cpu_s 0.5000 wall_s 0.7500 work_cpu_s 0.2500 items_here 2; "
            "farm 1 items 1 cpu_s 1.0000 wall_s 2.0000 work_cpu_s 0.1250 items_here 0");
}

TEST(RunRanks, OneRankIsThisProcessesThreads) {
  const auto ranks = single_process();
  RunRanks& farm = *ranks;
  EXPECT_TRUE(farm.leader());
  EXPECT_EQ(farm.share("dir"), "dir");
  const auto texts = farm.run(5, 2, text_of, {});
  ASSERT_EQ(texts.size(), 5u);
  EXPECT_EQ(texts[4], text_of(4));
}

}  // namespace
}  // namespace thaw::pipeline
