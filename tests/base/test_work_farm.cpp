// WorkFarm (base/work_farm.h), this process's threads: every item exactly once, each text at its
// item's index, done() once per item, for any thread count and grain; a failing item's outcome
// thrown as it was (the lowest failing item's), the items not yet begun skipped.
#include "base/work_farm.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>

#include "base/error.h"
#include "base/interrupt.h"
#include "base/outcome.h"

namespace thaw {
namespace {

TEST(WorkFarm, EveryItemOnceWithItsTextAtItsIndex) {
  for (const auto grain : {WorkFarm::Grain::fine, WorkFarm::Grain::coarse})
    for (const int threads : {1, 2, 3}) {
      std::vector<std::atomic<int>> calls(37);
      long done = 0;
      const std::vector<std::string> texts = this_process_farm().run(
          37, threads,
          [&](long k) {
            ++calls[static_cast<std::size_t>(k)];
            return "item " + std::to_string(k);
          },
          [&] { ++done; }, grain);
      ASSERT_EQ(texts.size(), 37u);
      for (long k = 0; k < 37; ++k) {
        EXPECT_EQ(calls[static_cast<std::size_t>(k)], 1) << k;
        EXPECT_EQ(texts[static_cast<std::size_t>(k)], "item " + std::to_string(k));
      }
      EXPECT_EQ(done, 37);
    }
}

TEST(WorkFarm, NoItemsNoCalls) {
  EXPECT_TRUE(this_process_farm().run(0, 2, [](long) { return std::string("x"); }, {}).empty());
  EXPECT_TRUE(this_process_farm().leader());
  EXPECT_EQ(this_process_farm().processes(), 1);
  EXPECT_EQ(this_process_farm().share("path"), "path");
  const Outcome failed = Outcome::user("a.toml", "[mesh] x", "bad");
  EXPECT_EQ(this_process_farm().leaders_outcome(failed), failed);
}

// A user error keeps its file and key through the farm, an internal error stays internal and an
// interrupt stays one; of several failures the lowest item's is thrown, whatever the threads.
TEST(WorkFarm, FailingItemIsThrownAsItWasAndLaterItemsAreSkipped) {
  for (const int threads : {1, 4}) {
    std::atomic<int> calls{0};
    try {
      this_process_farm().run(400, threads,
                              [&](long k) -> std::string {
                                ++calls;
                                if (k == 3 || k == 5)
                                  throw UserError("step_" + std::to_string(k) + ".obj", "line 2",
                                                  "x");
                                return "";
                              },
                              {});
      ADD_FAILURE() << "no error";
    } catch (const UserError& e) {
      EXPECT_EQ(e.file(), "step_3.obj");
      EXPECT_EQ(e.where(), "line 2");
    }
    EXPECT_LT(calls.load(), 400) << threads;  // the items after the failure were skipped
  }
  // Any other exception is an internal error (exit 3), thrown again as one with its text.
  EXPECT_EQ(Outcome::of([] {
              this_process_farm().run(
                  3, 2, [](long) -> std::string { throw std::logic_error("broken"); }, {});
            }).kind(),
            Outcome::Kind::internal);
  try {
    this_process_farm().run(3, 2, [](long) -> std::string { throw std::logic_error("broken"); },
                            {});
  } catch (const UserError&) {
    ADD_FAILURE() << "an internal error became a user error";
  } catch (const std::exception& e) {
    EXPECT_STREQ(e.what(), "broken");
  }
  EXPECT_THROW(
      this_process_farm().run(
          2, 1, [](long) -> std::string { throw Interrupted(); }, {}, WorkFarm::Grain::coarse),
      Interrupted);
  // done() may throw too (a progress display interrupted): the same way.
  EXPECT_THROW(this_process_farm().run(
                   5, 2, [](long) { return std::string(); }, [] { throw Interrupted(); }),
               Interrupted);
}

}  // namespace
}  // namespace thaw
