// The grid solver's thread team (sim/grid/block_team.h): every block is done exactly once per
// phase, whatever the thread count, a phase sees everything the previous one wrote, and the
// helpers return once the leader has finished.
#include "sim/grid/block_team.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <vector>

namespace thaw::sim {
namespace {

TEST(BlockTeam, EveryBlockOncePerPhaseAndPhasesAreOrdered) {
  const long blocks = 7;
  const int phases = 200;
  for (int threads : {1, 2, 3, 4}) {
    std::vector<int> count(blocks, 0);
    std::vector<long> value(blocks, 0);
    std::vector<char> ordered(static_cast<std::size_t>(threads), 1);
    TeamShared shared;
#pragma omp parallel num_threads(threads)
    {
      BlockTeam team(shared, omp_get_thread_num(), blocks);
      if (!team.leader()) {
        team.serve();
      } else {
        for (int phase = 0; phase < phases; ++phase) {
          // each block reads its neighbour's value from the previous phase: wrong if a phase
          // started before the previous one ended everywhere
          team.for_blocks([&](long b) {
            ++count[static_cast<std::size_t>(b)];
            if (value[static_cast<std::size_t>((b + 1) % blocks)] != phase)
              ordered[static_cast<std::size_t>(omp_get_thread_num())] = 0;
          });
          team.for_blocks([&](long b) { value[static_cast<std::size_t>(b)] = phase + 1; });
        }
        team.finish();
      }
    }
    for (long b = 0; b < blocks; ++b)
      EXPECT_EQ(count[static_cast<std::size_t>(b)], phases) << threads;
    for (char ok : ordered) EXPECT_TRUE(ok) << threads << " threads";
  }
}

}  // namespace
}  // namespace thaw::sim
